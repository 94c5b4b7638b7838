// io/urdf_xml_index.h: where things are in a URDF file's text (urdfdom reports no line numbers).
//
// The text is parsed once with TinyXML (the parser urdfdom itself uses), which gives XML syntax
// errors with their row and column, and the row/column of every <link> and <joint> element and
// of their children.
#pragma once

#include "io/file_util.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace frontier::io::detail
{

class UrdfXmlIndex
{
  public:
    // Throws InputError(file, row, column, ...) when the text is not well-formed XML, holds a
    // <!DOCTYPE>, or nests elements more than 1000 deep (checked by a linear scan before parsing).
    UrdfXmlIndex(const std::string& file, const std::string& text);

    // Position of <link name="name"> (kind "link") or <joint> (kind "joint"), or of a child
    // element path below it ("inertial/mass": the first of each name; "collision#2/geometry": the
    // third <collision>); falls back to the closest existing ancestor, and to {0, 0} when the
    // element is unknown.
    TextPosition element(const std::string& kind, const std::string& name,
                         const std::string& childPath = "") const;

    // Position of the first occurrence of `needle` in the text, or {0, 0}.
    TextPosition find(const std::string& needle) const;

    // Best guess for a urdfdom log message: the first name it quotes in [..] or '..' that names
    // a link or joint (when the message says "link"/"joint") or appears as an attribute value.
    TextPosition locateMessage(const std::string& message) const;

    // Position of the <robot> element, and whether it has a name attribute.
    TextPosition robot() const { return mRobot; }
    bool robotNamed() const { return mRobotNamed; }

    // Names of <link> and <joint> elements in document order.
    const std::vector<std::string>& linkNames() const { return mLinkNames; }
    const std::vector<std::string>& jointNames() const { return mJointNames; }

    // The parent and child link of each <joint> that names both, in document order.
    struct JointLinks
    {
        std::string joint;
        std::string parent;
        std::string child;
        TextPosition at; // the <joint> element
    };
    const std::vector<JointLinks>& jointLinks() const { return mJointLinks; }

    // A link's contact material as written: PyBullet's <link><contact><lateral_friction value=..>
    // and <restitution value=..>, Gazebo's <gazebo reference="LINK"><mu1> (the friction when the
    // link gives none). Values are the attribute or element text, unparsed; at: where each is.
    struct LinkMaterial
    {
        std::optional<std::string> friction;
        TextPosition frictionAt;
        std::optional<std::string> restitution;
        TextPosition restitutionAt;
    };
    // The material of a link, or null when it gives none.
    const LinkMaterial* material(const std::string& link) const;

  private:
    std::string mText;
    std::map<std::string, LinkMaterial> mMaterials;
    TextPosition mRobot;
    bool mRobotNamed = false;
    std::map<std::string, TextPosition> mElements; // "link:NAME/inertial/mass" -> position
    std::vector<std::string> mLinkNames;
    std::vector<std::string> mJointNames;
    std::vector<JointLinks> mJointLinks;
};

} // namespace frontier::io::detail
