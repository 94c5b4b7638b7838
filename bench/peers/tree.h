// bench/peers/tree.h: the model's joints as trees, in the order the peers build it (every
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
    int parent = -1; // body index of the parent; core::cWorld: a root (free or joined to the world)
};

inline bool isRoot(const TreeLink& link)
{
    return link.parent == core::cWorld;
}

// The moving bodies, tree by tree, each tree in parent-before-child order from its root (static
// bodies are left out: they are collision geometry; a joint to a static body joins its tree to
// the world). Throws Unsupported when the model has a loop, a tree that does not start with one
// rigid velocity (or is joined to the world and starts moving), actuators or loads, or a joint
// other than ball, revolute, angle or fixed (or one with damping or friction, or limits on other
// than a revolute joint).
std::vector<TreeLink> jointTree(const core::Model& model);

// The joint's parent in the tree: its parent body, or core::cWorld for a joint to the world or to
// a static body.
int treeParent(const core::Model& model, const core::Joint& joint);
// The joint's parent-side anchor (m) in the frame of treeParent: the parent body's, or the world's.
core::Vec3 parentAnchor(const core::Model& model, const core::Joint& joint);
// The orientation of the joint's parent frame (its parent body's, static or not; the identity for
// the world): parent-frame vectors such as axisParent turn into the world by it.
core::Quat parentRotation(const core::Model& model, const core::Joint& joint);

// Rotation and position of body b's frame relative to body a's frame at the model's initial pose
// (a = core::cWorld: relative to the world).
core::Quat relativeRotation(const core::Model& model, int a, int b);
core::Vec3 relativePosition(const core::Model& model, int a, int b);

} // namespace frontier::peers
