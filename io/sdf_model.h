// io/sdf_model.h: SDF files (Gazebo's SDFormat, read with Debian's libsdformat) as scenes
// (private to io/).
#pragma once

#include "core/model.h"
#include "io/scene.h"

#include <string>

namespace frontier::io::detail
{

// Whether this build reads SDF: it was linked against libsdformat (CMake found sdformat12).
bool sdfSupported();

// An SDF file with a <model> or a <world> as a scene (scenes/README.md "Models and worlds from SDF").
// A <world> is placed as the file says: its models, its ground (if any), its gravity and step. A
// <model> alone is a robot like a bare .urdf: on a static floor, dropped onto it when it floats
// freely. Throws InputError naming the file (an included model's own file) and line; without SDF
// support, an InputError saying which package adds it.
core::Model loadSdfScene(const std::string& path, const UrdfOptions& options, LoadReport* report);

} // namespace frontier::io::detail
