// io/urdf_model.h: URDF models (urdfdom) turned into bodies and joints (private to io/).
#pragma once

#include "core/model.h"

#include <string>

namespace frontier::io::detail
{

// How a URDF is placed in a scene.
struct UrdfPlacement
{
    core::Vec3 position = core::Vec3::Zero();        // of the root link frame, world (m)
    core::Quat orientation = core::Quat::Identity(); // of the root link frame
    std::string prefix;                              // prepended to every body and joint name
    bool selfCollision = true;                       // false: every link goes into one collision group
    bool fixedRoot = false; // true: the root link is a static body (its <inertial> is ignored)
};

// The URDF's links as bodies and its joints, body indices local to the returned model (joints to
// the world use core::cWorld). model.name is the robot name. Throws InputError naming the URDF
// file and, where it can be found, the line.
core::Model loadUrdfFragment(const std::string& path, const UrdfPlacement& placement);

// A URDF alone: the model at its own pose, plus a static floor (plane z = 0) and the default
// simulation settings.
core::Model loadUrdfScene(const std::string& path);

} // namespace frontier::io::detail
