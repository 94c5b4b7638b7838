// tests/contact/loop_limits_test.cpp: extra rows that are not contacts: the loop-closing joint of
// scenes/four_bar.yaml and the joint limits of scenes/limits.yaml (core/extra_rows.h).
#include "contact_harness.h"
#include "core/extra_rows.h"
#include "core/frontier_order.h"
#include "core/joints/coordinates.h"

#include <cstdio>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>

namespace frontier::test
{
namespace
{

Vec3 anchorWorld(const core::Model& model, const core::State& state, int body, const Vec3& anchor)
{
    if (body == core::cWorld || model.bodies[static_cast<std::size_t>(body)].isStatic)
    {
        return anchor; // static frames are the world's (scenes/README.md)
    }
    const core::BodyState& s = state.bodies[static_cast<std::size_t>(body)];
    return s.position_W + s.orientation_WB * anchor;
}

Vec3 axisWorld(const core::Model& model, const core::State& state, int body, const Vec3& axis)
{
    if (body == core::cWorld || model.bodies[static_cast<std::size_t>(body)].isStatic)
    {
        return axis;
    }
    return state.bodies[static_cast<std::size_t>(body)].orientation_WB * axis;
}

// The four-bar linkage for 5 s: the tree is world-crank-coupler-rocker and one revolute closes
// the loop. Bounds, every step: the loop joint's two anchors (computed here from the poses)
// within 1e-6 m of each other and its two axis copies within 1e-6 rad; every joint's error
// (Simulator's measure) under 1e-6 m. The linkage really moves (the crank turns by more than
// 1 rad), and the energy stays within 1% of the largest kinetic energy of its start value
// (symplectic Euler with projection: the error oscillates, it does not grow; measured 0.36%,
// bound 1%).
TEST(FourBar, LoopJointStaysClosed)
{
    SceneRun run(io::loadScene(scenePath("four_bar.yaml")));
    ASSERT_EQ(run.simulator.layout().loopJoints.size(), 1u);
    const int loop = run.simulator.layout().loopJoints[0];
    const core::Joint& joint = run.model.joints[static_cast<std::size_t>(loop)];
    std::printf("loop-closing joint: %s\n", joint.name.c_str());
    ASSERT_EQ(joint.type, core::JointType::Revolute);
    const int crankPivot = [&]
    {
        for (std::size_t k = 0; k < run.model.joints.size(); ++k)
        {
            if (run.model.joints[k].name == "crank_pivot")
            {
                return static_cast<int>(k);
            }
        }
        return -1;
    }();
    ASSERT_GE(crankPivot, 0);
    const double e0 = core::totalEnergy(run.model, run.state);
    double gap = 0.0, twist = 0.0, jointError = 0.0, energyDeviation = 0.0, kinetic = 0.0;
    double crankMin = 0.0, crankMax = 0.0, previousCrank = 0.0, crankUnwrapped = 0.0;
    const long steps = run.stepsFor(5.0);
    for (long k = 0; k < steps; ++k)
    {
        run.step();
        ASSERT_TRUE(allFinite(run.state)) << "step " << k;
        const Vec3 a = anchorWorld(run.model, run.state, joint.parent, joint.anchorParent);
        const Vec3 b = anchorWorld(run.model, run.state, joint.child, joint.anchorChild);
        gap = std::max(gap, (a - b).norm());
        const Vec3 ka = axisWorld(run.model, run.state, joint.parent, joint.axisParent);
        const Vec3 kb = axisWorld(run.model, run.state, joint.child, joint.axisChild);
        twist = std::max(twist, ka.cross(kb).norm());
        jointError = std::max(jointError, run.simulator.lastStep().maxJointErrorM);
        const double energy = core::totalEnergy(run.model, run.state);
        energyDeviation = std::max(energyDeviation, std::abs(energy - e0));
        double ke = 0.0;
        for (std::size_t i = 0; i < run.model.bodies.size(); ++i)
        {
            const core::BodyState& s = run.state.bodies[i];
            ke += 0.5 * run.model.bodies[i].mass * s.velocity_W.squaredNorm() +
                  0.5 * s.angularVelocity_W.dot(core::worldInertia(run.model.bodies[i], s) *
                                                s.angularVelocity_W);
        }
        kinetic = std::max(kinetic, ke);
        // The crank angle, unwrapped across +-pi.
        const double crank = core::jointCoordinate(run.model, run.state, crankPivot);
        double d = crank - previousCrank;
        d -= 2.0 * M_PI * std::round(d / (2.0 * M_PI));
        crankUnwrapped += d;
        previousCrank = crank;
        crankMin = std::min(crankMin, crankUnwrapped);
        crankMax = std::max(crankMax, crankUnwrapped);
    }
    std::printf("four-bar: loop gap %.3g m, axis misalignment %.3g rad, joint error %.3g m, crank range "
                "[%.3f, %.3f] rad, energy deviation %.3g J of largest kinetic energy %.3g J\n",
                gap, twist, jointError, crankMin, crankMax, energyDeviation, kinetic);
    EXPECT_LT(gap, 1e-6);
    EXPECT_LT(twist, 1e-6);
    EXPECT_LT(jointError, 1e-6);
    EXPECT_GT(crankMax - crankMin, 1.0);
    EXPECT_LT(energyDeviation, 1e-2 * kinetic);
}

int jointIndex(const core::Model& model, const std::string& name)
{
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        if (model.joints[k].name == name)
        {
            return static_cast<int>(k);
        }
    }
    return -1;
}

// scenes/limits.yaml for 4 s: the pendulum (revolute, limits [-0.3, 1.0] rad) is thrown into its
// lower limit and falls onto its upper one; the slider (prismatic, limits [-0.1, 0.3] m) is thrown
// into its lower limit and slides down onto its upper one. Bounds: every step each coordinate
// (core::jointCoordinate) within its limits to 1e-3 rad or m; both reach each limit (within 1e-2
// of it); at the end both rest pressed on the upper limit (within 1e-3) slower than 1e-3 m/s.
// Redundant constraints: the same loop-closing joint twice makes the loop rows of G singular. The
// projection treats the zero pivots as a pseudo-inverse, so the linkage moves exactly as with one
// copy (no NaN, no fight between the copies), and both copies hold.
TEST(FourBar, RedundantLoopJointMovesLikeTheSingleOne)
{
    std::ifstream in(scenePath("four_bar.yaml"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string line = "  - {name: rocker_pivot,";
    const std::size_t at = text.find(line);
    ASSERT_NE(at, std::string::npos);
    const std::size_t end = text.find('\n', at) + 1;
    std::string copy = text.substr(at, end - at);
    copy.replace(0, line.size(), "  - {name: rocker_pivot_again,");
    text.insert(end, copy);

    SceneRun single(io::loadScene(scenePath("four_bar.yaml")));
    SceneRun doubled(io::loadSceneFromString(text, scenePath("four_bar_redundant.yaml")));
    ASSERT_EQ(doubled.simulator.layout().loopJoints.size(), 2u);
    double gap = 0.0;
    for (long k = 0; k < single.stepsFor(2.0); ++k)
    {
        single.step();
        doubled.step();
        gap = std::max(gap, doubled.simulator.lastStep().maxJointErrorM);
    }
    EXPECT_LT(gap, 1e-6);
    for (const char* body : {"crank", "coupler", "rocker"})
    {
        EXPECT_LT((single.body(body).position_W - doubled.body(body).position_W).norm(), 1e-6) << body;
    }
}

TEST(Limits, RevoluteAndPrismaticLimitsHold)
{
    SceneRun run(io::loadScene(scenePath("limits.yaml")));
    const int hinge = jointIndex(run.model, "hinge");
    const int rail = jointIndex(run.model, "rail");
    ASSERT_GE(hinge, 0);
    ASSERT_GE(rail, 0);
    EXPECT_NEAR(core::jointCoordinate(run.model, run.state, hinge), 0.0, 1e-12);
    EXPECT_NEAR(core::jointCoordinate(run.model, run.state, rail), 0.0, 1e-12);
    const auto& hl = *run.model.joints[static_cast<std::size_t>(hinge)].limits;
    const auto& rl = *run.model.joints[static_cast<std::size_t>(rail)].limits;
    double hMin = 0.0, hMax = 0.0, rMin = 0.0, rMax = 0.0, jointError = 0.0;
    const long steps = run.stepsFor(4.0);
    for (long k = 0; k < steps; ++k)
    {
        run.step();
        ASSERT_TRUE(allFinite(run.state)) << "step " << k;
        const double h = core::jointCoordinate(run.model, run.state, hinge);
        const double r = core::jointCoordinate(run.model, run.state, rail);
        hMin = std::min(hMin, h);
        hMax = std::max(hMax, h);
        rMin = std::min(rMin, r);
        rMax = std::max(rMax, r);
        jointError = std::max(jointError, run.simulator.lastStep().maxJointErrorM);
    }
    const double hEnd = core::jointCoordinate(run.model, run.state, hinge);
    const double rEnd = core::jointCoordinate(run.model, run.state, rail);
    std::printf("hinge: range [%.6f, %.6f] rad (limits [%g, %g]), ends at %.6f; rail: range [%.6f, %.6f] m "
                "(limits [%g, %g]), ends at %.6f; joint error %.3g m; end speed %.3g m/s\n",
                hMin, hMax, hl[0], hl[1], hEnd, rMin, rMax, rl[0], rl[1], rEnd, jointError,
                maxPointSpeed(run.model, run.state));
    EXPECT_GT(hMin, hl[0] - 1e-3);
    EXPECT_LT(hMax, hl[1] + 1e-3);
    EXPECT_GT(rMin, rl[0] - 1e-3);
    EXPECT_LT(rMax, rl[1] + 1e-3);
    EXPECT_LT(hMin, hl[0] + 1e-2) << "the pendulum never reached its lower limit";
    EXPECT_LT(rMin, rl[0] + 1e-2) << "the slider never reached its lower limit";
    EXPECT_NEAR(hEnd, hl[1], 1e-3);
    EXPECT_NEAR(rEnd, rl[1], 1e-3);
    EXPECT_LT(maxPointSpeed(run.model, run.state), 1e-3);
    EXPECT_LT(jointError, 1e-6);
}

} // namespace
} // namespace frontier::test
