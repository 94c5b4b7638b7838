// io/xml_scan.cpp: the tags of an XML text in one pass, without a parser.
#include "io/xml_scan.h"

#include "io/scene.h"

#include <cctype>

namespace frontier::io::detail
{

namespace
{
[[noreturn]] void failAtOffset(const std::string& file, const std::string& text, std::size_t offset,
                               const std::string& message)
{
    const TextPosition at = positionOf(text, offset);
    throw InputError(file, at.line, at.column, message);
}

bool isNameEnd(char c)
{
    return std::isspace(static_cast<unsigned char>(c)) != 0 || c == '>' || c == '/';
}

// UTF-8 bytes of code point `c` appended to `out`.
void appendUtf8(unsigned long c, std::string& out)
{
    if (c < 0x80)
    {
        out += static_cast<char>(c);
    }
    else if (c < 0x800)
    {
        out += static_cast<char>(0xC0 | (c >> 6));
        out += static_cast<char>(0x80 | (c & 0x3F));
    }
    else if (c < 0x10000)
    {
        out += static_cast<char>(0xE0 | (c >> 12));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (c & 0x3F));
    }
    else
    {
        out += static_cast<char>(0xF0 | ((c >> 18) & 0x07));
        out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (c & 0x3F));
    }
}

// `raw` with &lt; &gt; &amp; &quot; &apos; &#N; and &#xN; decoded (anything else kept as written).
std::string decodeEntities(std::string_view raw)
{
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i)
    {
        const std::size_t semicolon = raw[i] == '&' ? raw.find(';', i) : std::string_view::npos;
        if (semicolon == std::string_view::npos || semicolon - i > 10)
        {
            out += raw[i];
            continue;
        }
        const std::string_view entity = raw.substr(i + 1, semicolon - i - 1);
        static constexpr std::pair<std::string_view, char> cNamed[] = {
            {"lt", '<'}, {"gt", '>'}, {"amp", '&'}, {"quot", '"'}, {"apos", '\''}};
        bool decoded = false;
        for (const auto& [text, c] : cNamed)
        {
            if (entity == text)
            {
                out += c;
                decoded = true;
            }
        }
        if (!decoded && entity.size() > 1 && entity[0] == '#')
        {
            const bool hex = entity[1] == 'x' || entity[1] == 'X';
            const std::string digits(entity.substr(hex ? 2 : 1));
            char* end = nullptr;
            const unsigned long code = std::strtoul(digits.c_str(), &end, hex ? 16 : 10);
            if (!digits.empty() && *end == '\0' && code <= 0x10FFFF)
            {
                appendUtf8(code, out);
                decoded = true;
            }
        }
        if (!decoded)
        {
            out += raw[i];
            continue;
        }
        i = semicolon;
    }
    return out;
}
// The '>' that ends the tag starting at `start` (an end tag at its first '>', a start tag at its
// first '>' outside quoted values); text.size() when the tag is unfinished.
std::size_t tagEnd(const std::string& text, std::size_t start, bool endTag)
{
    char quote = 0;
    std::size_t i = start + 1;
    for (; i < text.size(); ++i)
    {
        if (endTag)
        {
            if (text[i] == '>')
            {
                break;
            }
            continue;
        }
        const char c = text[i];
        if (quote != 0)
        {
            quote = c == quote ? 0 : quote;
        }
        else if (c == '"' || c == '\'')
        {
            quote = c;
        }
        else if (c == '>')
        {
            break;
        }
    }
    return i;
}

// The tag from `start` to its '>' at `close`: its name and attributes.
XmlTag tagAt(const std::string& text, std::size_t start, std::size_t close, bool endTag)
{
    XmlTag tag;
    tag.offset = start;
    tag.end = endTag;
    tag.empty = !endTag && text[close - 1] == '/';
    const std::size_t nameStart = start + (endTag ? 2 : 1);
    std::size_t nameEnd = nameStart;
    while (nameEnd < close && !isNameEnd(text[nameEnd]))
    {
        ++nameEnd;
    }
    tag.name = std::string_view(text).substr(nameStart, nameEnd - nameStart);
    tag.attributes = std::string_view(text).substr(nameEnd, close - (tag.empty ? 1 : 0) - nameEnd);
    return tag;
}

// Just past what starts at `from` with `open` and ends with `close` (a comment, ...).
std::size_t pastClose(const std::string& file, const std::string& text, std::size_t from, const char* open,
                      const char* close, const char* what)
{
    const std::size_t end = text.find(close, from + std::char_traits<char>::length(open));
    if (end == std::string::npos)
    {
        failAtOffset(file, text, from,
                     std::string("invalid XML: ") + what + " '" + open + "' is never closed; expected '" +
                         close + "'");
    }
    return end + std::char_traits<char>::length(close);
}
} // namespace

void scanXmlTags(const std::string& file, const std::string& text, const std::string& kind,
                 const std::string& expected, const std::function<void(const XmlTag&)>& visit)
{
    std::size_t i = 0;
    while ((i = text.find('<', i)) != std::string::npos)
    {
        const std::string_view rest(text.data() + i, text.size() - i);
        if (rest.starts_with("<!--"))
        {
            i = pastClose(file, text, i, "<!--", "-->", "the comment");
        }
        else if (rest.starts_with("<![CDATA["))
        {
            i = pastClose(file, text, i, "<![CDATA[", "]]>", "the CDATA section");
        }
        else if (rest.starts_with("<?"))
        {
            i = pastClose(file, text, i, "<?", "?>", "the processing instruction");
        }
        else if (rest.starts_with("<!DOCTYPE") || rest.starts_with("<!ENTITY"))
        {
            failAtOffset(file, text, i,
                         "a <!DOCTYPE> declaration (and the entities it may define) is not supported in a " +
                             kind + "; expected " + expected + " with plain text");
        }
        else if (rest.starts_with("<!"))
        {
            const std::size_t end = text.find('>', i);
            i = end == std::string::npos ? text.size() : end + 1;
        }
        else
        {
            const bool endTag = rest.starts_with("</");
            const std::size_t close = tagEnd(text, i, endTag);
            if (close >= text.size())
            {
                return; // an unfinished tag: the parser reports it
            }
            visit(tagAt(text, i, close, endTag));
            i = close + 1;
        }
    }
}

void XmlDepthCheck::visit(const XmlTag& tag)
{
    if (tag.end)
    {
        --mDepth;
    }
    else if (!tag.empty && ++mDepth > cMaxXmlDepth)
    {
        failAtOffset(mFile, mText, tag.offset,
                     "elements nested more than " + std::to_string(cMaxXmlDepth) + " levels deep; " + mNeeds);
    }
}

std::optional<std::string> xmlAttribute(std::string_view attributes, std::string_view name)
{
    std::size_t i = 0;
    while (i < attributes.size())
    {
        while (i < attributes.size() && std::isspace(static_cast<unsigned char>(attributes[i])) != 0)
        {
            ++i;
        }
        const std::size_t nameStart = i;
        while (i < attributes.size() && attributes[i] != '=' &&
               std::isspace(static_cast<unsigned char>(attributes[i])) == 0)
        {
            ++i;
        }
        const std::string_view attribute = attributes.substr(nameStart, i - nameStart);
        while (i < attributes.size() && std::isspace(static_cast<unsigned char>(attributes[i])) != 0)
        {
            ++i;
        }
        if (i >= attributes.size() || attributes[i] != '=')
        {
            if (i == nameStart)
            {
                ++i; // a stray character: step over it
            }
            continue; // an attribute without a value (not XML; the parser reports it)
        }
        ++i;
        while (i < attributes.size() && std::isspace(static_cast<unsigned char>(attributes[i])) != 0)
        {
            ++i;
        }
        if (i >= attributes.size() || (attributes[i] != '"' && attributes[i] != '\''))
        {
            return std::nullopt; // an unquoted value: not XML
        }
        const char quote = attributes[i];
        const std::size_t close = attributes.find(quote, i + 1);
        if (close == std::string_view::npos)
        {
            return std::nullopt;
        }
        if (attribute == name)
        {
            return decodeEntities(attributes.substr(i + 1, close - i - 1));
        }
        i = close + 1;
    }
    return std::nullopt;
}

} // namespace frontier::io::detail
