// core/frontier_order.cpp: spanning forest, leaf-peeling numbering, block layout (docs/method.md §3).
#include "core/frontier_order.h"

#include "core/joints/drive.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <numeric>

namespace frontier::core
{

bool jointToWorld(const Model& model, const Joint& joint)
{
    return joint.parent == cWorld || model.bodies[static_cast<std::size_t>(joint.parent)].isStatic;
}

namespace
{

struct DisjointSets
{
    std::vector<int> parent;
    explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    int find(int x)
    {
        while (parent[static_cast<std::size_t>(x)] != x)
        {
            x = parent[static_cast<std::size_t>(x)] =
                parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
        }
        return x;
    }
};

struct Adjacent
{
    int body;
    int joint;
};

// The spanning forest over moving bodies (step 1 of buildFrontierLayout).
struct Forest
{
    explicit Forest(std::size_t bodies) : sets(bodies), adjacent(bodies), worldJointOfComponent(bodies, -1) {}
    DisjointSets sets;                           // the components
    std::vector<std::vector<Adjacent>> adjacent; // per body: its tree joints
    std::vector<int> worldJointOfComponent;      // per component root: the joint rooting it, -1
};

// 1. Spanning forest over moving bodies: body-body joints first (a cycle is a loop), then the
//    first joint to the world in each component roots it; any further one is a loop (into
//    layout.loopJoints, sorted).
Forest spanningForest(const Model& model, FrontierLayout& layout)
{
    Forest forest(model.bodies.size());
    DisjointSets& sets = forest.sets;
    for (std::size_t j = 0; j < model.joints.size(); ++j)
    {
        const Joint& joint = model.joints[j];
        if (jointToWorld(model, joint))
        {
            continue;
        }
        const int a = sets.find(joint.parent);
        const int b = sets.find(joint.child);
        if (a == b)
        {
            layout.loopJoints.push_back(static_cast<int>(j));
            continue;
        }
        sets.parent[static_cast<std::size_t>(a)] = b;
        forest.adjacent[static_cast<std::size_t>(joint.parent)].push_back({joint.child, static_cast<int>(j)});
        forest.adjacent[static_cast<std::size_t>(joint.child)].push_back({joint.parent, static_cast<int>(j)});
    }
    for (std::size_t j = 0; j < model.joints.size(); ++j)
    {
        const Joint& joint = model.joints[j];
        if (!jointToWorld(model, joint))
        {
            continue;
        }
        int& slot = forest.worldJointOfComponent[static_cast<std::size_t>(sets.find(joint.child))];
        if (slot >= 0)
        {
            layout.loopJoints.push_back(static_cast<int>(j));
            continue;
        }
        slot = static_cast<int>(j);
    }
    std::sort(layout.loopJoints.begin(), layout.loopJoints.end());
    return forest;
}

// Per body while numbering: its parent in its tree, the joint to it, children not yet numbered.
struct TreeLinks
{
    explicit TreeLinks(std::size_t bodies)
        : parent(bodies, -1), parentJoint(bodies, -1), pendingChildren(bodies, 0)
    {
    }
    std::vector<int> parent, parentJoint, pendingChildren;
};

// Orients the tree of `root` by a breadth-first walk (its bodies get tree index `tree`); returns
// its bodies by body index.
std::vector<int> orientTree(const Forest& forest, int root, int tree, std::vector<bool>& visited,
                            TreeLinks& links, FrontierLayout& layout)
{
    std::vector<int> members{root};
    visited[static_cast<std::size_t>(root)] = true;
    for (std::size_t k = 0; k < members.size(); ++k)
    {
        const int node = members[k];
        layout.treeOfBody[static_cast<std::size_t>(node)] = tree;
        for (const Adjacent& next : forest.adjacent[static_cast<std::size_t>(node)])
        {
            if (!visited[static_cast<std::size_t>(next.body)])
            {
                visited[static_cast<std::size_t>(next.body)] = true;
                links.parent[static_cast<std::size_t>(next.body)] = node;
                links.parentJoint[static_cast<std::size_t>(next.body)] = next.joint;
                ++links.pendingChildren[static_cast<std::size_t>(node)];
                members.push_back(next.body);
            }
        }
    }
    std::sort(members.begin(), members.end());
    return members;
}

// Numbers one oriented tree by leaf peeling: each round removes every node whose children are all
// removed, by body index, each node followed by the edge to its parent (the root's: worldJoint).
void peelLeaves(const Model& model, const std::vector<int>& members, int root, int worldJoint,
                const std::vector<std::uint8_t>& actuated, TreeLinks& links, FrontierLayout& layout)
{
    std::vector<int> leaves, nextLeaves;
    for (int body : members)
    {
        if (links.pendingChildren[static_cast<std::size_t>(body)] == 0)
        {
            leaves.push_back(body);
        }
    }
    while (!leaves.empty())
    {
        nextLeaves.clear();
        for (int body : leaves)
        {
            LayoutBlock node;
            node.kind = LayoutBlock::Kind::Node;
            node.index = body;
            node.dim = 6;
            layout.bodyBlock[static_cast<std::size_t>(body)] = static_cast<int>(layout.blocks.size());
            layout.blocks.push_back(node);
            const int edgeJoint =
                body == root ? worldJoint : links.parentJoint[static_cast<std::size_t>(body)];
            if (edgeJoint >= 0)
            {
                LayoutBlock edge;
                edge.kind = LayoutBlock::Kind::Edge;
                edge.index = edgeJoint;
                const Joint& joint = model.joints[static_cast<std::size_t>(edgeJoint)];
                edge.dim = jointBlockRows(joint, actuated[static_cast<std::size_t>(edgeJoint)]);
                edge.driveRows = blockDriveRows(joint, actuated[static_cast<std::size_t>(edgeJoint)]);
                layout.jointBlock[static_cast<std::size_t>(edgeJoint)] =
                    static_cast<int>(layout.blocks.size());
                layout.blocks.push_back(edge);
            }
            const int parent = links.parent[static_cast<std::size_t>(body)];
            if (parent >= 0 && --links.pendingChildren[static_cast<std::size_t>(parent)] == 0)
            {
                nextLeaves.push_back(parent);
            }
        }
        std::sort(nextLeaves.begin(), nextLeaves.end());
        leaves.swap(nextLeaves);
    }
}

// 3. Parent links and offsets: a node's later neighbour is its edge; an edge's is the node on its
//    parent side (none for an edge to the world).
void linkBlocks(const Model& model, FrontierLayout& layout)
{
    int offset = 0;
    for (std::size_t k = 0; k < layout.blocks.size(); ++k)
    {
        LayoutBlock& block = layout.blocks[k];
        block.offset = offset;
        offset += block.dim;
        if (block.kind == LayoutBlock::Kind::Node)
        {
            const bool hasEdge =
                k + 1 < layout.blocks.size() && layout.blocks[k + 1].kind == LayoutBlock::Kind::Edge;
            block.parent = hasEdge ? static_cast<int>(k + 1) : -1;
        }
        else
        {
            const Joint& joint = model.joints[static_cast<std::size_t>(block.index)];
            const int child = layout.blocks[k - 1].index;
            block.childIsJointChild = joint.child == child;
            const int other = block.childIsJointChild ? joint.parent : joint.child;
            block.parent = jointToWorld(model, joint) && other == joint.parent
                               ? -1
                               : layout.bodyBlock[static_cast<std::size_t>(other)];
        }
    }
    layout.size = offset;
}

} // namespace

FrontierLayout buildFrontierLayout(const Model& model)
{
    static std::atomic<std::uint64_t> layoutsMade{0};
    const std::size_t nb = model.bodies.size();
    FrontierLayout layout;
    layout.id = ++layoutsMade;
    layout.bodyBlock.assign(nb, -1);
    layout.jointBlock.assign(model.joints.size(), -1);
    layout.treeOfBody.assign(nb, -1);
    const std::vector<std::uint8_t> actuated = actuatedJoints(model); // drive rows for their servos

    Forest forest = spanningForest(model, layout);

    // 2. Per tree: root = the body with the world joint, else the lowest body index. Orient by a
    //    breadth-first walk, then number by leaf peeling (docs/method.md §3, "Order").
    TreeLinks links(nb);
    std::vector<bool> visited(nb, false);
    for (std::size_t start = 0; start < nb; ++start)
    {
        if (model.bodies[start].isStatic || visited[start])
        {
            continue;
        }
        const int component = forest.sets.find(static_cast<int>(start));
        const int worldJoint = forest.worldJointOfComponent[static_cast<std::size_t>(component)];
        const int root = worldJoint >= 0 ? model.joints[static_cast<std::size_t>(worldJoint)].child
                                         : static_cast<int>(start);
        const int tree = layout.treeCount++;
        const std::vector<int> members = orientTree(forest, root, tree, visited, links, layout);
        peelLeaves(model, members, root, worldJoint, actuated, links, layout);
    }

    linkBlocks(model, layout);
    return layout;
}

} // namespace frontier::core
