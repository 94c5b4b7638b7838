// io/urdf_xml_index.cpp: element positions of a URDF file via TinyXML.
#include "io/urdf_xml_index.h"

#include "io/scene.h"
#include "io/xml_scan.h"

#include <algorithm>
#include <string_view>
#include <tinyxml.h>

namespace frontier::io::detail
{

namespace
{
// Child elements under each of `prefixes`: "prefix/name" for the first of each name, and for the
// direct children of a <link> or <joint> (numbered) also "prefix/name#k" for the k-th (0-based).
void indexChildren(const TiXmlElement& parent, const std::vector<std::string>& prefixes, bool numbered,
                   std::map<std::string, TextPosition>& out)
{
    std::map<std::string, int> seen; // element name -> how many came before
    for (const TiXmlElement* child = parent.FirstChildElement(); child != nullptr;
         child = child->NextSiblingElement())
    {
        const TextPosition at{child->Row(), child->Column()};
        std::vector<std::string> keys;
        for (const std::string& prefix : prefixes)
        {
            keys.push_back(prefix + "/" + child->Value());
            out.try_emplace(keys.back(), at); // the first one of a kind
        }
        if (numbered)
        {
            keys.push_back(prefixes.front() + "/" + child->Value() + "#" +
                           std::to_string(seen[child->Value()]++));
            out.try_emplace(keys.back(), at);
        }
        indexChildren(*child, keys, false, out);
    }
}
// A linear scan of the text before any XML parser sees it: TinyXML (the index's and urdfdom's
// parser) recurses once per nesting level, so thousands of nested elements overflow the stack or
// take seconds; and it reports an unclosed comment or a DOCTYPE without a usable location.
void checkXmlShape(const std::string& file, const std::string& text)
{
    XmlDepthCheck depth(file, text, "a URDF needs a few");
    scanXmlTags(file, text, "URDF file", "the <robot> element", [&](const XmlTag& tag) { depth.visit(tag); });
}

// <link><contact><lateral_friction value=".."/><restitution value=".."/></contact> (PyBullet's).
void readContactMaterial(const TiXmlElement& link, UrdfXmlIndex::LinkMaterial& out)
{
    const TiXmlElement* contact = link.FirstChildElement("contact");
    if (contact == nullptr)
    {
        return;
    }
    const auto read = [&](const char* element, std::optional<std::string>& value, TextPosition& at)
    {
        const TiXmlElement* e = contact->FirstChildElement(element);
        if (e != nullptr)
        {
            const char* text = e->Attribute("value");
            value = text != nullptr ? text : "";
            at = {e->Row(), e->Column()};
        }
    };
    read("lateral_friction", out.friction, out.frictionAt);
    read("restitution", out.restitution, out.restitutionAt);
}

// <gazebo reference="LINK"><mu1>..</mu1></gazebo>: the link's friction unless its <contact> gives one.
void readGazeboFriction(const TiXmlElement& gazebo, std::map<std::string, UrdfXmlIndex::LinkMaterial>& out)
{
    const char* link = gazebo.Attribute("reference");
    const TiXmlElement* mu = gazebo.FirstChildElement("mu1");
    if (link == nullptr || mu == nullptr)
    {
        return;
    }
    UrdfXmlIndex::LinkMaterial& material = out[link];
    if (!material.friction)
    {
        material.friction = mu->GetText() != nullptr ? mu->GetText() : "";
        material.frictionAt = {mu->Row(), mu->Column()};
    }
}

} // namespace

const UrdfXmlIndex::LinkMaterial* UrdfXmlIndex::material(const std::string& link) const
{
    const auto it = mMaterials.find(link);
    return it == mMaterials.end() ? nullptr : &it->second;
}

UrdfXmlIndex::UrdfXmlIndex(const std::string& file, const std::string& text) : mText(text)
{
    checkXmlShape(file, text);
    TiXmlDocument document;
    document.Parse(text.c_str());
    if (document.Error())
    {
        // An empty document has no row: the problem is at its start.
        throw InputError(file, std::max(1, document.ErrorRow()), std::max(1, document.ErrorCol()),
                         std::string("invalid XML: ") + document.ErrorDesc());
    }
    const TiXmlElement* robot = document.RootElement();
    if (robot == nullptr || std::string(robot->Value()) != "robot")
    {
        const int row = robot != nullptr ? robot->Row() : 0;
        const int column = robot != nullptr ? robot->Column() : 0;
        throw InputError(file, row, column, "expected a <robot> root element");
    }
    mRobot = {robot->Row(), robot->Column()};
    mRobotNamed = robot->Attribute("name") != nullptr;
    for (const TiXmlElement* e = robot->FirstChildElement(); e != nullptr; e = e->NextSiblingElement())
    {
        const std::string kind = e->Value();
        if (kind == "gazebo")
        {
            readGazeboFriction(*e, mMaterials);
            continue;
        }
        if (kind != "link" && kind != "joint")
        {
            continue;
        }
        const char* name = e->Attribute("name");
        if (name == nullptr)
        {
            continue; // urdfdom reports it
        }
        const std::string key = kind + ":" + name;
        if (!mElements.try_emplace(key, TextPosition{e->Row(), e->Column()}).second)
        {
            continue;
        }
        (kind == "link" ? mLinkNames : mJointNames).push_back(name);
        if (kind == "link")
        {
            readContactMaterial(*e, mMaterials[name]);
        }
        if (kind == "joint")
        {
            const TiXmlElement* parent = e->FirstChildElement("parent");
            const TiXmlElement* child = e->FirstChildElement("child");
            const char* parentLink = parent != nullptr ? parent->Attribute("link") : nullptr;
            const char* childLink = child != nullptr ? child->Attribute("link") : nullptr;
            if (parentLink != nullptr && childLink != nullptr)
            {
                mJointLinks.push_back({name, parentLink, childLink, {e->Row(), e->Column()}});
            }
        }
        indexChildren(*e, {key}, true, mElements);
    }
}

TextPosition UrdfXmlIndex::element(const std::string& kind, const std::string& name,
                                   const std::string& childPath) const
{
    std::string key = kind + ":" + name + (childPath.empty() ? "" : "/" + childPath);
    while (true)
    {
        const auto it = mElements.find(key);
        if (it != mElements.end())
        {
            return it->second;
        }
        const std::size_t slash = key.rfind('/');
        if (slash == std::string::npos)
        {
            return {};
        }
        key.resize(slash);
    }
}

TextPosition UrdfXmlIndex::find(const std::string& needle) const
{
    const std::size_t pos = mText.find(needle);
    return pos == std::string::npos ? TextPosition{} : positionOf(mText, pos);
}

TextPosition UrdfXmlIndex::locateMessage(const std::string& message) const
{
    // Names quoted as [name] or 'name', in order.
    std::vector<std::pair<std::string, std::size_t>> names; // name, position in message
    for (std::size_t i = 0; i < message.size(); ++i)
    {
        const char open = message[i];
        if (open != '[' && open != '\'')
        {
            continue;
        }
        const char close = open == '[' ? ']' : '\'';
        const std::size_t end = message.find(close, i + 1);
        if (end == std::string::npos)
        {
            break;
        }
        names.emplace_back(message.substr(i + 1, end - i - 1), i);
        i = end;
    }
    for (const auto& [name, at] : names)
    {
        if (name.empty())
        {
            continue;
        }
        // The word just before the name says what it is: "Link [a]", "joint [j]".
        const std::string before = message.substr(at >= 6 ? at - 6 : 0, at >= 6 ? 6 : at);
        for (const char* kind : {"link", "joint"})
        {
            const std::string upper = std::string(1, static_cast<char>(kind[0] - 'a' + 'A')) + (kind + 1);
            if (before.find(kind) != std::string::npos || before.find(upper) != std::string::npos)
            {
                const TextPosition p = element(kind, name);
                if (p.line > 0)
                {
                    return p;
                }
            }
        }
        for (const std::string& quoted :
             {"\"" + name + "\"", "'" + name + "'", "\"" + name + " ", " " + name + "\"", "<" + name})
        {
            const TextPosition p = find(quoted);
            if (p.line > 0)
            {
                return p;
            }
        }
    }
    return {};
}

} // namespace frontier::io::detail
