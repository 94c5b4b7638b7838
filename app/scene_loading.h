// app/scene_loading.h: a scene as every command loads it: the file, then the robots' starting
// overlaps excluded from collision (collision::startingOverlaps).
#pragma once

#include "core/model.h"
#include "io/scene.h"
#include "io/trajectory.h"

#include <string>

namespace frontier::app
{

struct LoadedScene
{
    core::Model model;
    io::LoadReport report;
};

// Throws io::InputError naming the first moving body whose initial energy is not finite.
void checkFiniteEnergy(const core::Model& model, const std::string& path);

// Throws io::InputError (also from checkFiniteEnergy).
LoadedScene loadSceneWithRobots(const std::string& path, const io::UrdfOptions& options);
// The same from the YAML text of a scene; `path` names it in messages and resolves its relative files.
LoadedScene loadSceneTextWithRobots(const std::string& yamlText, const std::string& path,
                                    const io::UrdfOptions& options);

// Warnings of the load to stderr ("frontier: FILE:LINE: warning: ...").
void printLoadWarnings(const io::LoadReport& report);

} // namespace frontier::app
