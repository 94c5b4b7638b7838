// io/yaml_actuators.cpp: the `actuators:` list of a YAML scene (core::Actuator): servos, motors and
// efforts on joint coordinates, named by joint (a URDF model's joints with its prefix).
#include "core/joints/coordinates.h"
#include "core/joints/joint_types.h"
#include "io/scene.h"
#include "io/suggest.h"
#include "io/yaml_scene.h"

#include <map>
#include <string>
#include <vector>

namespace frontier::io::detail
{

namespace
{

const std::vector<std::string> cActuatorKeys = {"joint", "type",   "coordinate",  "kp",
                                                "kd",    "target", "effort_limit"};
const std::vector<std::string> cActuatorTypes = {"position", "velocity", "effort"};
const std::vector<std::string> cCoordinates = {"rotation", "slide"};

core::ActuatorKind readKind(const MapNode& map)
{
    const YamlNode node = map.require("type");
    const std::string name = toString(map.source(), node, map.what("type"));
    if (name == "position")
    {
        return core::ActuatorKind::Position;
    }
    if (name == "velocity")
    {
        return core::ActuatorKind::Velocity;
    }
    if (name != "effort")
    {
        failAt(map.source(), node,
               "unknown actuator type " + quotedName(name) + " for " + map.what("type") +
                   suggestionSuffix(name, cActuatorTypes, true));
    }
    return core::ActuatorKind::Effort;
}

// The coordinate the actuator drives: the joint's one, or for a cylindrical joint the one
// `coordinate:` names.
core::JointCoordinate readCoordinate(const MapNode& map, const core::Joint& joint)
{
    const std::span<const core::JointCoordinate> coordinates = core::jointCoordinates(joint.type);
    if (!map.has("coordinate"))
    {
        if (coordinates.size() > 1)
        {
            std::vector<std::string> choices;
            for (const core::JointCoordinate coordinate : coordinates)
            {
                choices.push_back("'coordinate: " + std::string(core::coordinateName(coordinate)) + "'");
            }
            map.fail(map.context() + " drives " + core::jointTypeName(joint.type) + " joint '" + joint.name +
                     "', which has " + std::to_string(coordinates.size()) + " coordinates; give " +
                     core::nameList(choices, "or"));
        }
        return coordinates.front();
    }
    const std::string name = map.string("coordinate");
    for (const core::JointCoordinate coordinate : coordinates)
    {
        if (name == core::coordinateName(coordinate))
        {
            return coordinate;
        }
    }
    std::vector<std::string> known;
    for (const core::JointCoordinate coordinate : coordinates)
    {
        known.emplace_back(core::coordinateName(coordinate));
    }
    map.failAtValue("coordinate", "joint '" + joint.name + "' (" + core::jointTypeName(joint.type) +
                                      ") has no coordinate '" + name + "'; expected " + joinNames(known));
}

// Keys that only some types take.
void checkGainKeys(const MapNode& map, core::ActuatorKind kind)
{
    if (map.has("kp") && kind != core::ActuatorKind::Position)
    {
        map.failAtKey("kp", "'kp' (stiffness) is for position actuators only");
    }
    if (map.has("kd") && kind == core::ActuatorKind::Effort)
    {
        map.failAtKey("kd", "'kd' (damping) is for position and velocity actuators only");
    }
}

void readActuator(SceneBuilder& builder, const YamlNode& node, std::size_t index,
                  std::map<std::pair<int, int>, YAML::Mark>& taken)
{
    const YamlSource& source = builder.source;
    MapNode map(source, node, "actuator #" + std::to_string(index + 1));
    map.checkKeys(cActuatorKeys);
    const YamlNode jointNode = map.require("joint");
    core::Actuator actuator;
    actuator.joint = resolveJointName(builder, jointNode, map.what("joint"));
    const core::Joint& joint = builder.model.joints[static_cast<std::size_t>(actuator.joint)];
    map.setContext("the actuator on joint '" + joint.name + "'");
    if (core::jointCoordinates(joint.type).empty())
    {
        failAt(source, jointNode,
               "joint '" + joint.name + "' is a " + core::jointTypeName(joint.type) +
                   " joint; an actuator drives a " +
                   core::nameList(core::jointTypeNames([](const core::JointTypeInfo& type)
                                                       { return !type.coordinates.empty(); }),
                                  "or") +
                   " joint (continuous in a URDF)");
    }
    actuator.kind = readKind(map);
    actuator.coordinate = readCoordinate(map, joint);
    checkGainKeys(map, actuator.kind);
    const bool turns = actuator.coordinate == core::JointCoordinate::Rotation;
    if (actuator.kind == core::ActuatorKind::Position)
    {
        map.require("kp");
        actuator.kp = *map.optPositive("kp");
    }
    actuator.kd = map.optNonNegative("kd", turns ? "(N m s/rad)" : "(N s/m)").value_or(0.0);
    actuator.effortLimit = map.optPositive("effort_limit").value_or(joint.effortLimit);
    actuator.target = readTarget(source, map.require("target"), map.what("target"), joint.name);
    const std::pair<int, int> coordinate(actuator.joint, static_cast<int>(actuator.coordinate));
    if (const auto first = taken.find(coordinate); first != taken.end())
    {
        failAt(source, jointNode,
               "a second actuator on the " + std::string(core::coordinateName(actuator.coordinate)) +
                   " of joint '" + joint.name + "' (the first is on line " +
                   std::to_string(first->second.line + 1) + "); one actuator per joint coordinate");
    }
    taken[coordinate] = jointNode.mark();
    builder.model.actuators.push_back(std::move(actuator));
}

} // namespace

int resolveJointName(const SceneBuilder& builder, const YamlNode& node, const std::string& what)
{
    const std::string name = toString(builder.source, node, what);
    if (const auto it = builder.jointIndex.find(name); it != builder.jointIndex.end())
    {
        return it->second;
    }
    std::vector<std::string> names;
    for (const core::Joint& joint : builder.model.joints)
    {
        names.push_back(joint.name);
    }
    failAt(builder.source, node,
           "unknown joint " + quotedName(name) + " for " + what + suggestionSuffix(name, names, false));
}

void readActuators(SceneBuilder& builder, const YamlNode& actuators)
{
    requireSequence(builder.source, actuators, "'actuators'");
    std::map<std::pair<int, int>, YAML::Mark> taken; // (joint, coordinate) -> where
    for (std::size_t i = 0; i < actuators.size(); ++i)
    {
        readActuator(builder, actuators[i], i, taken);
    }
}

} // namespace frontier::io::detail
