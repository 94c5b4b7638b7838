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

// Throws io::InputError.
LoadedScene loadSceneWithRobots(const std::string& path, const io::UrdfOptions& options);

// Warnings of the load to stderr ("frontier: FILE:LINE: warning: ...").
void printLoadWarnings(const io::LoadReport& report);

// The robot flags as key=value pairs of a trajectory's header (only those given), and back, so
// `check` and `render` load the scene as the run did.
void addUrdfOptions(io::TrajectoryMetadata& metadata, const io::UrdfOptions& options);
// Throws io::InputError naming `file` when a value cannot be read.
io::UrdfOptions urdfOptionsFrom(const std::map<std::string, std::string>& metadata, const std::string& file);

} // namespace frontier::app
