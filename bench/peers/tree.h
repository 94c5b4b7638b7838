// bench/peers/tree.h: the model's joints as one tree, in the order the peers build it (every
// body after its parent), and the checks that the model fits the harness's scope (engine.h).
#pragma once

#include "core/model.h"

#include <vector>

namespace frontier::peers
{

struct TreeLink
{
    int body = 0;    // Model::bodies index
    int joint = -1;  // Model::joints index of the joint to its parent; -1: a free root
    int parent = -1; // body index of the parent; core::cWorld: joined to the world
};

// Bodies in parent-before-child order; the first is the root. Throws Unsupported when the model
// has a loop, several trees, a static body, a body that starts moving, actuators or loads, or a
// joint other than ball, revolute or fixed (or one with limits).
std::vector<TreeLink> jointTree(const core::Model& model);

// Rotation and position of body b's frame relative to body a's frame at the model's initial pose
// (a = core::cWorld: relative to the world).
core::Quat relativeRotation(const core::Model& model, int a, int b);
core::Vec3 relativePosition(const core::Model& model, int a, int b);

} // namespace frontier::peers
