// io/yaml_scene.h: the parts of a YAML scene (private to io/).
#pragma once

#include "core/model.h"
#include "io/package_paths.h"
#include "io/scene.h"
#include "io/yaml_util.h"

#include <array>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>

namespace frontier::io::detail
{

// What the parts share while a scene is read.
struct SceneBuilder
{
    YamlSource source;
    core::Model model;
    std::map<std::string, YAML::Mark> bodyMarks;     // where each YAML body's name was given
    std::map<std::string, YAML::Mark> jointMarks;    // where each YAML joint's name was given
    std::vector<YAML::Mark> robotMarks;              // where each entry of model.robots was given
    std::map<std::string, int> weldedLinks;          // a URDF link welded into a body (prefixed name -> body)
    UrdfOptions urdf;                                // how `models:` are read
    std::optional<PackagePaths> packages;            // their mesh URIs, made on first use
    LoadReport* report = nullptr;                    // receives warnings and what loading did
    std::vector<std::array<int, 2>> heldJoints;      // joints [first, end) of models held by servos
    std::unordered_map<std::string, int> bodyIndex;  // every body's name -> its index (no linear search)
    std::unordered_map<std::string, int> jointIndex; // every joint's name -> its index (no linear search)

    void addBody(core::Body body)
    {
        bodyIndex.emplace(body.name, static_cast<int>(model.bodies.size()));
        model.bodies.push_back(std::move(body));
    }
    void addJoint(core::Joint joint)
    {
        jointIndex.emplace(joint.name, static_cast<int>(model.joints.size()));
        model.joints.push_back(std::move(joint));
    }
    int findBody(const std::string& name) const
    {
        const auto it = bodyIndex.find(name);
        return it == bodyIndex.end() ? -1 : it->second;
    }
};

// Scene text to model (sourceName for messages and relative paths).
core::Model loadYamlScene(const std::string& text, const std::string& sourceName,
                          const UrdfOptions& urdf = {}, LoadReport* report = nullptr);

// `bodies:` list (each body appended to builder.model.bodies), or its item `index` (0-based) alone.
void readBodies(SceneBuilder& builder, const YamlNode& bodies);
void readBody(SceneBuilder& builder, const YamlNode& node, std::size_t index);
// `joints:` list, after all bodies (YAML and URDF) exist, or its item `index` (0-based) alone.
void readJoints(SceneBuilder& builder, const YamlNode& joints);
void readJoint(SceneBuilder& builder, const YamlNode& node, std::size_t index);

// A body named by `node` (a string): its index, or core::cWorld for "world" when allowWorld. A
// URDF link welded into a body names that body.
// Errors name `what` and suggest the closest body name.
int resolveBodyName(const SceneBuilder& builder, const YamlNode& node, const std::string& what,
                    bool allowWorld);

// A joint named by `node` (a string): its index. Errors name `what` and suggest the closest joint name.
int resolveJointName(const SceneBuilder& builder, const YamlNode& node, const std::string& what);

// `actuators:` list, after all joints exist (core::Actuator).
void readActuators(SceneBuilder& builder, const YamlNode& actuators);
// `loads:` list, after all bodies exist (core::Load).
void readLoads(SceneBuilder& builder, const YamlNode& loads);
// `stability:` (the stability suite's criteria), after all joints and actuators exist.
SceneStabilityCriteria readStabilityCriteria(const SceneBuilder& builder, const YamlNode& node);
// An actuator's target (a number, or a map with sine, keyframes or csv), `what` naming it in
// messages; a csv target's column defaults to defaultColumn.
core::TimeFunction readTarget(const YamlSource& source, const YamlNode& node, const std::string& what,
                              const std::string& defaultColumn);

// Checks a new body or joint name: valid, and not taken.
void checkNewName(const SceneBuilder& builder, const YamlNode& nameNode, const std::string& kind);

} // namespace frontier::io::detail
