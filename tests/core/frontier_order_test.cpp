// tests/core/frontier_order_test.cpp: the frontier order of docs/method.md §3 on random forests, and
// loop detection.
#include "core/dense_solver.h"
#include "core/frontier_order.h"
#include "random_model.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <set>

namespace frontier::test
{
namespace
{

using core::FrontierLayout;
using core::JointType;
using core::LayoutBlock;
using core::Model;

// Checks the structural facts the elimination relies on.
void expectFrontierProperty(const Model& model, const FrontierLayout& layout)
{
    const int nblocks = static_cast<int>(layout.blocks.size());
    int offset = 0;
    std::vector<int> seenJoint(model.joints.size(), 0);
    std::vector<int> seenBody(model.bodies.size(), 0);
    for (int b = 0; b < nblocks; ++b)
    {
        const LayoutBlock& block = layout.blocks[static_cast<std::size_t>(b)];
        SCOPED_TRACE("block " + std::to_string(b));
        EXPECT_EQ(block.offset, offset);
        offset += block.dim;
        if (block.kind == LayoutBlock::Kind::Node)
        {
            ++seenBody[static_cast<std::size_t>(block.index)];
            EXPECT_EQ(block.dim, 6);
            EXPECT_EQ(layout.bodyBlock[static_cast<std::size_t>(block.index)], b);
            // A node's only later neighbour is its own edge, the next block (or none: a free root).
            const bool nextIsEdge = b + 1 < nblocks && layout.blocks[static_cast<std::size_t>(b + 1)].kind ==
                                                           LayoutBlock::Kind::Edge;
            EXPECT_EQ(block.parent, nextIsEdge ? b + 1 : -1);
            if (nextIsEdge)
            {
                const core::Joint& joint = model.joints[static_cast<std::size_t>(
                    layout.blocks[static_cast<std::size_t>(b + 1)].index)];
                EXPECT_TRUE(joint.parent == block.index || joint.child == block.index);
            }
        }
        else
        {
            ++seenJoint[static_cast<std::size_t>(block.index)];
            const core::Joint& joint = model.joints[static_cast<std::size_t>(block.index)];
            EXPECT_EQ(block.dim, core::jointRowCount(joint.type));
            EXPECT_EQ(layout.jointBlock[static_cast<std::size_t>(block.index)], b);
            // An edge follows its child node ...
            ASSERT_GT(b, 0);
            const LayoutBlock& child = layout.blocks[static_cast<std::size_t>(b - 1)];
            ASSERT_EQ(child.kind, LayoutBlock::Kind::Node);
            EXPECT_TRUE(joint.parent == child.index || joint.child == child.index);
            // ... and its parent node, the joint's other body, comes later (none for the world).
            const int other = joint.child == child.index ? joint.parent : joint.child;
            if (other == core::cWorld || model.bodies[static_cast<std::size_t>(other)].isStatic)
            {
                EXPECT_EQ(block.parent, -1);
            }
            else
            {
                EXPECT_GT(block.parent, b);
                ASSERT_LT(block.parent, nblocks);
                const LayoutBlock& parentBlock = layout.blocks[static_cast<std::size_t>(block.parent)];
                EXPECT_EQ(parentBlock.kind, LayoutBlock::Kind::Node);
                EXPECT_EQ(parentBlock.index, other);
                EXPECT_EQ(layout.treeOfBody[static_cast<std::size_t>(other)],
                          layout.treeOfBody[static_cast<std::size_t>(child.index)]);
            }
        }
    }
    EXPECT_EQ(layout.size, offset);
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        EXPECT_EQ(seenBody[i], model.bodies[i].isStatic ? 0 : 1) << "body " << i;
    }
    const std::set<int> loops(layout.loopJoints.begin(), layout.loopJoints.end());
    EXPECT_EQ(loops.size(), layout.loopJoints.size()) << "a loop joint is listed twice";
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const bool loop = loops.count(static_cast<int>(k)) > 0;
        EXPECT_EQ(seenJoint[k], loop ? 0 : 1) << "joint " << model.joints[k].name;
        EXPECT_EQ(layout.jointBlock[k] < 0, loop) << "joint " << model.joints[k].name;
    }
}

TEST(FrontierOrder, RandomForestsHaveTheFrontierProperty)
{
    for (unsigned seed = 1; seed <= 40; ++seed)
    {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const Model model =
            randomForest(seed, 1 + static_cast<int>(seed % 5), 2 + static_cast<int>(seed * 7 % 150));
        const FrontierLayout layout = core::buildFrontierLayout(model);
        EXPECT_TRUE(layout.loopJoints.empty());
        expectFrontierProperty(model, layout);
    }
}

TEST(FrontierOrder, TreesAreCountedAndRootsComeLast)
{
    Rng rng(7);
    Model model;
    RandomTreeOptions options;
    options.bodies = 12;
    options.attachToWorld = true;
    appendRandomTree(model, rng, options);
    options.attachToWorld = false;
    options.bodies = 9;
    appendRandomTree(model, rng, options);
    options.bodies = 1;
    appendRandomTree(model, rng, options);
    const FrontierLayout layout = core::buildFrontierLayout(model);
    expectFrontierProperty(model, layout);
    EXPECT_EQ(layout.treeCount, 3);
    // The world-attached tree is rooted at its world joint's child, whose edge (the world joint)
    // is the tree's last block.
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        if (model.joints[k].parent != core::cWorld)
        {
            continue;
        }
        const int edge = layout.jointBlock[k];
        const int root = layout.bodyBlock[static_cast<std::size_t>(model.joints[k].child)];
        EXPECT_EQ(edge, root + 1);
        for (std::size_t i = 0; i < model.bodies.size(); ++i)
        {
            if (layout.treeOfBody[i] == layout.treeOfBody[static_cast<std::size_t>(model.joints[k].child)])
            {
                EXPECT_LE(layout.bodyBlock[i], root);
            }
        }
    }
    // Sizes: 6 rows per body plus the rows of every tree joint.
    int rows = 6 * static_cast<int>(model.bodies.size());
    for (const core::Joint& joint : model.joints)
    {
        rows += core::jointRowCount(joint.type);
    }
    EXPECT_EQ(layout.size, rows);
}

// Lemma 1 and "no fill-in" on the assembled matrix: in layout order, every block's non-zeros
// beyond its own diagonal block and earlier blocks lie in its parent block only.
TEST(FrontierOrder, AssembledMatrixCouplesEachBlockOnlyToItsParentLater)
{
    for (unsigned seed = 100; seed < 110; ++seed)
    {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const Model model = randomForest(seed, 3, 30);
        const auto problem = makeProblem(model);
        const Eigen::MatrixXd a = core::DenseSolver::assemble(problem->system);
        const FrontierLayout& layout = problem->layout;
        ASSERT_EQ(a.rows(), layout.size);
        // Symmetric up to the rounding of R I R^T.
        EXPECT_LT((a - a.transpose()).cwiseAbs().maxCoeff(), 1e-14 * a.cwiseAbs().maxCoeff());
        int couplings = 0;
        for (std::size_t b = 0; b < layout.blocks.size(); ++b)
        {
            const LayoutBlock& block = layout.blocks[b];
            for (std::size_t c = b + 1; c < layout.blocks.size(); ++c)
            {
                const LayoutBlock& other = layout.blocks[c];
                const double coupling =
                    a.block(block.offset, other.offset, block.dim, other.dim).cwiseAbs().maxCoeff();
                if (static_cast<int>(c) == block.parent)
                {
                    EXPECT_GT(coupling, 0.0);
                    ++couplings;
                }
                else
                {
                    EXPECT_EQ(coupling, 0.0) << "blocks " << b << " and " << c;
                }
            }
        }
        // Every edge couples to its child node (earlier) and, unless it goes to the world, to its
        // parent node (later): the later couplings are the nodes' edges plus body-body edges.
        int expected = 0;
        for (std::size_t b = 0; b < layout.blocks.size(); ++b)
        {
            expected += layout.blocks[b].parent >= 0 ? 1 : 0;
        }
        EXPECT_EQ(couplings, expected);
    }
}

TEST(FrontierOrder, FourCycleHasOneLoopJoint)
{
    Model model;
    const Vec3 corners[4] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    for (int i = 0; i < 4; ++i)
    {
        model.bodies.push_back(boxBody("b" + std::to_string(i), 1.0, Vec3(0.2, 0.2, 0.2), corners[i]));
    }
    for (int i = 0; i < 4; ++i)
    {
        const int j = (i + 1) % 4;
        addJoint(model, "ring" + std::to_string(i), JointType::Ball, i, j, 0.5 * (corners[i] + corners[j]),
                 Vec3::UnitZ());
    }
    const FrontierLayout layout = core::buildFrontierLayout(model);
    ASSERT_EQ(layout.loopJoints.size(), 1u);
    EXPECT_EQ(layout.loopJoints[0], 3); // the joint that closes the cycle, in joint order
    EXPECT_EQ(layout.jointBlock[3], -1);
    EXPECT_EQ(layout.treeCount, 1);
    expectFrontierProperty(model, layout);
    EXPECT_EQ(layout.size, 4 * 6 + 3 * 3);
}

TEST(FrontierOrder, SecondWorldJointOfATreeIsALoop)
{
    // A chain of 5 nailed to the world at both ends (a hanging bridge): one loop through the world.
    Model model = straightChain({1, 1, 1, 1, 1}, JointType::Ball, /*nailToWorld=*/true);
    const int second =
        addJoint(model, "nail_end", JointType::Nail, core::cWorld, 4, Vec3(5, 0, 0), Vec3::UnitZ());
    const FrontierLayout layout = core::buildFrontierLayout(model);
    ASSERT_EQ(layout.loopJoints.size(), 1u);
    EXPECT_EQ(layout.loopJoints[0], second);
    EXPECT_EQ(layout.treeCount, 1);
    expectFrontierProperty(model, layout);
    // The first world joint roots the tree at body 0: its block is the very last one.
    EXPECT_EQ(layout.jointBlock[static_cast<std::size_t>(second - 1)],
              static_cast<int>(layout.blocks.size()) - 1);
}

TEST(FrontierOrder, StaticBodiesAreNotNodes)
{
    Model model = straightChain({1, 2, 3}, JointType::Revolute, false);
    core::Body ground = boxBody("ground", 0.0, Vec3(10, 10, 1), Vec3(0, 0, -1));
    ground.isStatic = true;
    model.bodies.push_back(ground);
    addJoint(model, "pin", JointType::Revolute, 3, 1, Vec3(1.5, 0, 0), Vec3::UnitY());
    const FrontierLayout layout = core::buildFrontierLayout(model);
    EXPECT_TRUE(layout.loopJoints.empty());
    EXPECT_EQ(layout.bodyBlock[3], -1);
    EXPECT_EQ(layout.treeOfBody[3], -1);
    EXPECT_EQ(layout.treeCount, 1);
    // Rooted at the pinned body 1: the pin (to a static body) is the last block, with no parent.
    EXPECT_EQ(layout.jointBlock[2], static_cast<int>(layout.blocks.size()) - 1);
    EXPECT_EQ(layout.blocks.back().parent, -1);
    expectFrontierProperty(model, layout);
}

} // namespace
} // namespace frontier::test
