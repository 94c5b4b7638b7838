// io/yaml_joints.cpp: the `joints:` list of a YAML scene.
//
// Anchors and axes are world quantities at the initial pose; core::setJointFrames turns them into
// the per-body frames. A static parent acts as the world but keeps its index.
#include "core/joints/joint_types.h"
#include "io/scene.h"
#include "io/suggest.h"
#include "io/yaml_scene.h"

namespace frontier::io::detail
{

namespace
{

const std::vector<std::string> cJointKeys = {"name", "type",   "parent",  "child",    "anchor",
                                             "axis", "limits", "damping", "friction", "collide"};
bool needsAxis(const core::JointTypeInfo& info)
{
    return info.needsAxis;
}

// Limits, damping and friction act on the one coordinate of these types (core/joints/coordinates.h).
bool hasLimits(const core::JointTypeInfo& info)
{
    return info.limitCoordinate.has_value();
}

// "takes no 'axis' (only revolute, angle, ... and prismatic joints do)", from the table of types.
std::string onlyTypesDo(bool (*has)(const core::JointTypeInfo&))
{
    return " (only " + core::nameList(core::jointTypeNames(has), "and") + " joints do)";
}

// `damping:` (N m s/rad or N s/m) and `friction:` (N m or N) of a joint's coordinate, >= 0.
void readJointForces(const MapNode& map, const std::string& typeName, core::Joint& joint)
{
    const core::JointTypeInfo& info = core::jointTypeInfo(joint.type);
    const bool turns = info.limitCoordinate == core::JointCoordinate::Rotation;
    for (const std::string key : {"damping", "friction"})
    {
        if (map.has(key) && !hasLimits(info))
        {
            map.failAtKey(key, map.context() + " of type " + typeName + " takes no '" + key + "'" +
                                   onlyTypesDo(hasLimits));
        }
    }
    joint.damping = map.optNonNegative("damping", turns ? "(N m s/rad)" : "(N s/m)").value_or(0.0);
    joint.friction = map.optNonNegative("friction", turns ? "(N m)" : "(N)").value_or(0.0);
}

// `type:`, one of the joint types (core/joints/joint_types.h); the name read is returned too.
core::JointType readJointType(const MapNode& map, std::string& typeName)
{
    const YamlSource& source = map.source();
    const YamlNode typeNode = map.require("type");
    typeName = toString(source, typeNode, map.what("type"));
    const std::optional<core::JointType> type = core::jointTypeFromName(typeName);
    if (!type)
    {
        const std::vector<std::string> known = core::jointTypeNames();
        const std::string match = closestMatch(typeName, known);
        failAt(source, typeNode,
               "unknown joint type '" + typeName + "' in " + map.context() +
                   (match.empty() ? "" : "; did you mean '" + match + "'?") + " (known: " + joinNames(known) +
                   ")");
    }
    return *type;
}

// `parent:` and `child:`: two different bodies, the child moving; a nail's parent is world-like.
void readJointBodies(SceneBuilder& builder, const MapNode& map, core::Joint& joint)
{
    const YamlSource& source = builder.source;
    const core::Model& model = builder.model;
    const std::string& context = map.context();
    const YamlNode parentNode = map.require("parent");
    const YamlNode childNode = map.require("child");
    joint.parent = resolveBodyName(builder, parentNode, "the parent of " + context, true);
    joint.child = resolveBodyName(builder, childNode, "the child of " + context, false);
    const core::Body& child = model.bodies[static_cast<std::size_t>(joint.child)];
    if (joint.child == joint.parent)
    {
        failAt(source, childNode, context + " joins body '" + child.name + "' to itself (parent == child)");
    }
    if (child.isStatic)
    {
        failAt(source, childNode,
               "the child of " + context + ", body '" + child.name +
                   "', is static; the child must be a moving body (swap parent and child?)");
    }
    const bool parentIsWorldLike =
        joint.parent == core::cWorld || model.bodies[static_cast<std::size_t>(joint.parent)].isStatic;
    if (joint.type == core::JointType::Nail && !parentIsWorldLike)
    {
        failAt(source, parentNode,
               "the parent of nail " + context +
                   " must be 'world' or a static body (a nail pins a body to the "
                   "world)");
    }
}

// `axis:` (unit, world frame) of the types that need one; +z, unused, for the others.
core::Vec3 readJointAxis(const MapNode& map, const std::string& typeName, const core::JointTypeInfo& info)
{
    if (info.needsAxis)
    {
        return toDirection(map.source(), map.require("axis"), map.what("axis"));
    }
    if (map.has("axis"))
    {
        map.failAtKey("axis",
                      map.context() + " of type " + typeName + " takes no 'axis'" + onlyTypesDo(needsAxis));
    }
    return core::Vec3::UnitZ();
}

// `limits: [lower, upper]` (rad or m) of the joint's coordinate, if given.
void readJointLimits(const MapNode& map, const std::string& typeName, core::Joint& joint)
{
    if (!map.has("limits"))
    {
        return;
    }
    const YamlSource& source = map.source();
    if (!hasLimits(core::jointTypeInfo(joint.type)))
    {
        map.failAtKey("limits",
                      map.context() + " of type " + typeName + " takes no 'limits'" + onlyTypesDo(hasLimits));
    }
    const YamlNode limitsNode = map.get("limits");
    const std::vector<double> limits =
        toNumbers(source, limitsNode, map.what("limits") + " [lower, upper]", 2);
    if (limits[0] > limits[1])
    {
        failAt(source, limitsNode,
               "expected lower <= upper for " + map.what("limits") + ", got [" + limitsNode[0].scalar() +
                   ", " + limitsNode[1].scalar() + "]");
    }
    joint.limits = std::array<double, 2>{limits[0], limits[1]};
}

} // namespace

void readJoint(SceneBuilder& builder, const YamlNode& node, std::size_t index)
{
    const YamlSource& source = builder.source;
    core::Model& model = builder.model;
    MapNode map(source, node, "joint #" + std::to_string(index + 1));
    if (map.get("name").isScalar())
    {
        map.setContext("joint '" + map.get("name").scalar() + "'");
    }
    map.checkKeys(cJointKeys);
    core::Joint joint;
    const YamlNode nameNode = map.require("name");
    joint.name = toString(source, nameNode, map.what("name"));
    checkNewName(builder, nameNode, "joint");

    std::string typeName;
    joint.type = readJointType(map, typeName);
    readJointBodies(builder, map, joint);

    // Fixed joints: the child's centre of mass (m, world) by default.
    core::Vec3 anchor = model.bodies[static_cast<std::size_t>(joint.child)].position_W;
    if (joint.type != core::JointType::Fixed || map.has("anchor"))
    {
        anchor = toPosition(source, map.require("anchor"), map.what("anchor"));
    }
    const core::Vec3 axis = readJointAxis(map, typeName, core::jointTypeInfo(joint.type));
    readJointLimits(map, typeName, joint);
    readJointForces(map, typeName, joint);
    joint.collideConnected = map.optBool("collide").value_or(false);
    core::setJointFrames(model, joint, anchor, axis);
    builder.jointMarks[joint.name] = nameNode.mark();
    builder.addJoint(std::move(joint));
}

void readJoints(SceneBuilder& builder, const YamlNode& joints)
{
    requireSequence(builder.source, joints, "'joints'");
    for (std::size_t i = 0; i < joints.size(); ++i)
    {
        readJoint(builder, joints[i], i);
    }
}

} // namespace frontier::io::detail
