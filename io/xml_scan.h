// io/xml_scan.h: a linear scan over the tags of an XML text, for what must be known before an XML
// parser sees the text (nesting depth, the structure of a COLLADA file's nodes): TinyXML and
// assimp's COLLADA reader recurse once per nesting level and would overflow the stack.
#pragma once

#include "io/file_util.h"

#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace frontier::io::detail
{

// A start or end tag found by scanXmlTags.
struct XmlTag
{
    std::string_view name;       // the element name ("node"; a namespace prefix is kept)
    std::string_view attributes; // a start tag's text after the name, up to '>' or "/>"
    std::size_t offset = 0;      // of the tag's '<' in the text
    bool end = false;            // "</name>"
    bool empty = false;          // "<name ... />": opens nothing
};

// Visits every start and end tag of `text` in order, skipping comments, CDATA sections,
// processing instructions and declarations; stops at an unfinished tag (the parser then reports
// it). Throws InputError(file, line, column, ...) at an unclosed comment, CDATA section or
// processing instruction, and at a <!DOCTYPE> or <!ENTITY> (entities are not expanded, a DOCTYPE
// is refused), naming `kind` ("URDF file") and what `kind` expects ("the <robot> element").
void scanXmlTags(const std::string& file, const std::string& text, const std::string& kind,
                 const std::string& expected, const std::function<void(const XmlTag&)>& visit);

// The most levels elements may nest in an XML input (a URDF or COLLADA file needs a few).
inline constexpr int cMaxXmlDepth = 1000;

// Throws InputError at the first start tag nested more than cMaxXmlDepth levels deep; `needs`
// ends the message ("a URDF needs a few").
class XmlDepthCheck
{
  public:
    XmlDepthCheck(const std::string& file, const std::string& text, std::string needs)
        : mFile(file), mText(text), mNeeds(std::move(needs))
    {
    }
    void visit(const XmlTag& tag);

  private:
    const std::string& mFile;
    const std::string& mText;
    std::string mNeeds;
    int mDepth = 0;
};

// The value of attribute `name` in a start tag's attribute text, with the predefined and the
// numeric character entities decoded; std::nullopt when the tag has no such attribute.
std::optional<std::string> xmlAttribute(std::string_view attributes, std::string_view name);

} // namespace frontier::io::detail
