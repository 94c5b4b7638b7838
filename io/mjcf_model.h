// io/mjcf_model.h: MJCF models (MuJoCo's compiled model) turned into bodies and joints (private to io/).
//
// How MuJoCo's model maps onto Frontier's (docs/mjcf.md): a body and the bodies welded to it (no
// joint between them) become one body at their common centre of mass; bodies welded to the world
// become one static body; a body with one joint gets the matching joint (hinge: revolute, slide:
// prismatic, ball: ball, free: none); a body with several joints gets a chain of light frames, one
// per joint but the last, each taking cFrameMassFraction of the body's mass and inertia.
#pragma once

#include "io/urdf_model.h"

#include <optional>
#include <string>

namespace frontier::io::detail
{

// The share of a multi-joint body's mass and inertia each of its frames takes. Frontier's bodies
// need mass, and the position correction (docs/method.md §7) converges poorly when a frame carries
// less than about 1e-3 of what it joins: the gym humanoid's hips then come apart at its first impact.
inline constexpr double cFrameMassFraction = 0.01;

// How an MJCF model is placed in a scene: its world frame at `position`, `orientation`.
struct MjcfPlacement
{
    core::Vec3 position = core::Vec3::Zero();        // m
    core::Quat orientation = core::Quat::Identity(); // of the model's world frame
    std::string prefix;                              // prepended to every body and joint name
    bool selfCollision = true;                       // false: its bodies never collide with each other
    std::optional<std::string> keyframe;             // a <key name="..."> whose qpos, qvel, ctrl start it
};

// Throws InputError naming the file and, where it can be found, the line.
ModelFragment loadMjcfFragment(const std::string& path, const MjcfPlacement& placement);

// An MJCF file alone: the model as MuJoCo places it, with its <option> timestep and gravity.
core::Model loadMjcfScene(const std::string& path, const UrdfOptions& options, LoadReport* report);

} // namespace frontier::io::detail
