// core/frontier_order.h: the frontier order of docs/method.md §3 and the block layout it gives.
//
// Why this order: bodies are nodes, joints edges. In each tree of the spanning forest, leaves are
// removed round by round (left to right = by body index) and numbered as they go; the root comes
// last. Every node k then has exactly one edge numbered k, the edge to its parent, whose number
// is larger. Laying the block rows out as node 1, edge 1, node 2, edge 2, ..., root (and the
// root's edge to the world, if any), each block's only later neighbour is its parent-side block,
// so Gaussian elimination in layout order touches only that block's diagonal: no fill-in, O(n)
// (docs/method.md §3, "No fill-in"). Joints to the world (or to a static body) are the roots'
// edges; a second path to the world or a cycle among bodies closes a loop: those joints are
// listed in loopJoints and are not part of the tree.
#pragma once

#include "core/model.h"

#include <cstdint>
#include <vector>

namespace frontier::core
{

struct LayoutBlock
{
    enum class Kind
    {
        Node, // a moving body: equations (1), (2), 6 rows
        Edge, // a joint: its velocity conditions (jointRowCount rows), then its drive rows
    };
    Kind kind = Kind::Node;
    int index = 0;     // body index (Node) or joint index (Edge)
    int dim = 6;       // rows of the block
    int driveRows = 0; // Edge: its last driveRows rows are compliant drive rows (core/joints/drive.h)
    int parent = -1;   // layout index of the one later neighbour, -1 for the last block of a tree
    int offset = 0;    // first scalar row of the block in the whole system
    // Edge: its child node (the block just before it) is the joint's child body (else its parent).
    bool childIsJointChild = false;
};

struct FrontierLayout
{
    std::vector<LayoutBlock> blocks; // layout (= elimination) order
    std::vector<int> bodyBlock;      // body index -> block index, -1 for static bodies
    std::vector<int> jointBlock;     // joint index -> block index, -1 for loop joints
    std::vector<int> loopJoints;     // joints that close a loop (not in the tree)
    std::vector<int> treeOfBody;     // body index -> tree id, -1 for static bodies
    int treeCount = 0;
    int size = 0; // scalar rows in all
    // Unique to each layout buildFrontierLayout made (copies share it; 0: made another way), so a
    // solver that factors the same layout again may keep what it derived from it.
    std::uint64_t id = 0;
};

// True when the joint's parent is the world or a static body.
bool jointToWorld(const Model& model, const Joint& joint);

FrontierLayout buildFrontierLayout(const Model& model);

} // namespace frontier::core
