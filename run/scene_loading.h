// run/scene_loading.h: a scene as every command and library user loads it: the file, then the
// robots' starting overlaps excluded from collision (collision::startingOverlaps).
#pragma once

#include "core/contact.h"
#include "core/model.h"
#include "io/scene.h"
#include "io/trajectory.h"

#include <optional>
#include <string>

namespace frontier::run
{

// A scene ready to step (run::Simulation): its model and what loading did (robots, warnings).
struct LoadedScene
{
    core::Model model;
    io::LoadReport report;
    // The deepest contact of the initial pose when deeper than model.contact.startPenetration (a
    // warning in the report says so; `frontier run --strict` refuses to start).
    std::optional<core::Contact> startPenetration;
};

// Throws io::InputError naming `path` and the first body whose starting state is out of range
// (core::startingStateDefect: the check of io::loadScene, for a model changed since).
void checkStartingStates(const core::Model& model, const std::string& path);

// A YAML scene or a URDF robot as every command loads it: io::loadScene (a bare URDF placed on its
// floor, hold servos, joint positions, starting states checked), and the pairs of a robot's
// links that overlap in the starting pose kept from colliding. Throws io::InputError.
LoadedScene loadScene(const std::string& path, const io::UrdfOptions& options = {});
// The same from the YAML text of a scene; `path` names it in messages and resolves its relative files.
LoadedScene loadSceneText(const std::string& yamlText, const std::string& path,
                          const io::UrdfOptions& options = {});

// "bodies 'a' and 'b' start inside each other by D m (...)", or "" when they do not.
std::string startPenetrationText(const LoadedScene& scene);

// Warnings of the load to stderr ("frontier: FILE:LINE: warning: ...").
void printLoadWarnings(const io::LoadReport& report);

} // namespace frontier::run
