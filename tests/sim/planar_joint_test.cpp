// tests/sim/planar_joint_test.cpp: a body on a planar joint (docs/method.md §2) under gravity and
// a push with components off the plane stays in its plane and keeps its axis, while it moves and
// turns in the plane as a free body would; two free bodies on one keep their momentum and angular
// momentum.
#include "joint_models.h"
#include "sim_test_util.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <utility>

namespace frontier::sim::test
{
namespace
{

// A 2 kg cube of 0.2 m sides (inertia the same about every axis) at (0.3, 0, 1) on a planar joint
// to the world, anchored at its centre, the plane's normal (0, 1, 1)/sqrt(2) tilted against
// gravity; it starts moving along x (in the plane) and turning about the normal. A constant force
// with a component along the normal and a torque about x (in the plane) push it off the plane.
struct PlanarCase
{
    core::Model model;
    core::Vec3 normal_W = core::Vec3(0.0, 1.0, 1.0).normalized();
    core::Vec3 force_W = core::Vec3(0.0, 5.0, -3.0); // N
    core::Vec3 torque_W = core::Vec3(4.0, 0.0, 0.0); // N m
    core::Vec3 velocity0_W = core::Vec3(1.0, 0.0, 0.0);
    double spin0 = 2.0; // rad/s about the normal
};

PlanarCase planarCase(core::IntegratorKind integrator)
{
    PlanarCase c;
    c.model = emptyTestModel(core::Vec3(0.0, 0.0, -9.81), integrator, 1e-3);
    core::Body cube = jointTestBox("cube", 2.0, core::Vec3::Constant(0.2), core::Vec3(0.3, 0.0, 1.0));
    cube.velocity_W = c.velocity0_W;
    cube.angularVelocity_W = c.spin0 * c.normal_W;
    c.model.bodies.push_back(cube);
    addTestJoint(c.model, core::JointType::Planar, core::cWorld, 0, cube.position_W, c.normal_W);
    core::Load push;
    push.body = 0;
    push.force = c.force_W;
    push.torque = c.torque_W;
    c.model.loads.push_back(push);
    return c;
}

TEST(PlanarJoint, StaysInItsPlaneAndMovesFreelyInIt)
{
    for (const core::IntegratorKind integrator : cIntegrators)
    {
        SCOPED_TRACE(core::integratorName(integrator));
        const PlanarCase c = planarCase(integrator);
        const core::Joint& joint = c.model.joints[0];
        ASSERT_EQ(core::jointRowCount(joint.type), 3);
        const core::Mat3 inPlane = core::Mat3::Identity() - c.normal_W * c.normal_W.transpose();
        const core::Vec3 acceleration_W = inPlane * (c.model.simulation.gravity + c.force_W / 2.0);
        core::Simulator sim(c.model);
        core::State state = core::initialState(c.model);
        double worstGap = 0.0, worstTilt = 0.0, worstVelocity = 0.0, worstSpin = 0.0;
        for (long k = 0; k < stepsFor(1.0, c.model.simulation.dt); ++k)
        {
            sim.step(state);
            const core::BodyState& b = state.bodies[0];
            const core::Vec3 anchor_W = b.position_W + b.orientation_WB * joint.anchorChild;
            worstGap = std::max(worstGap, std::abs(c.normal_W.dot(anchor_W - joint.anchorParent)));
            worstTilt = std::max(worstTilt, (b.orientation_WB * joint.axisChild).cross(c.normal_W).norm());
            const core::Vec3 free_W = inPlane * c.velocity0_W + state.time * acceleration_W;
            worstVelocity = std::max(worstVelocity, (inPlane * b.velocity_W - free_W).norm());
            // The torque lies in the plane and the cube turns alike about every axis: the spin about
            // the normal stays.
            worstSpin = std::max(worstSpin, std::abs(b.angularVelocity_W.dot(c.normal_W) - c.spin0));
        }
        RecordProperty(std::string("worst_gap_m_") + core::integratorName(integrator), sci(worstGap));
        EXPECT_LE(worstGap, 1e-9) << "the anchor stays in the plane";
        EXPECT_LE(worstTilt, 1e-9) << "the cube's copy of the normal stays on it";
        EXPECT_LE(worstVelocity, 1e-9) << "in the plane it moves as a free body";
        EXPECT_LE(worstSpin, 1e-9) << "it turns freely about the normal";
        EXPECT_GT(state.bodies[0].velocity_W.norm(), 4.0) << "it did move";
    }
}

// Two cubes in free space on a planar joint between them (the parent moves too: its lever arm and its
// copy of the normal turn with it), both moving and turning off the plane at the start: the joint
// impulses are internal, so the total momentum and angular momentum stay, and the joint holds.
TEST(PlanarJoint, BetweenTwoFreeBodiesConservesMomentum)
{
    for (const core::IntegratorKind integrator : cIntegrators)
    {
        SCOPED_TRACE(core::integratorName(integrator));
        core::Model model = emptyTestModel(core::Vec3::Zero(), integrator, 1e-3);
        core::Body a = jointTestBox("a", 3.0, core::Vec3(0.4, 0.2, 0.3), core::Vec3(0.0, 0.0, 1.0));
        core::Body b = jointTestBox("b", 1.0, core::Vec3(0.2, 0.2, 0.2), core::Vec3(0.5, 0.1, 1.2));
        a.velocity_W = core::Vec3(0.2, -0.1, 0.3);
        a.angularVelocity_W = core::Vec3(0.5, 1.0, -0.3);
        b.velocity_W = core::Vec3(-0.4, 0.6, -0.5);
        b.angularVelocity_W = core::Vec3(-1.0, 0.2, 2.0);
        model.bodies = {a, b};
        const core::Vec3 normal_W = core::Vec3(0.0, 1.0, 1.0).normalized();
        addTestJoint(model, core::JointType::Planar, 0, 1, core::Vec3(0.3, 0.0, 1.1), normal_W);
        const auto momenta = [&model](const core::State& state)
        {
            core::Vec3 p = core::Vec3::Zero();
            core::Vec3 l = core::Vec3::Zero(); // about the origin
            for (std::size_t k = 0; k < model.bodies.size(); ++k)
            {
                const core::BodyState& s = state.bodies[k];
                const core::Mat3 inertia_W = s.orientation_WB * model.bodies[k].inertia_B *
                                             s.orientation_WB.toRotationMatrix().transpose();
                p += model.bodies[k].mass * s.velocity_W;
                l +=
                    model.bodies[k].mass * s.position_W.cross(s.velocity_W) + inertia_W * s.angularVelocity_W;
            }
            return std::pair(p, l);
        };
        core::Simulator sim(model);
        core::State state = core::initialState(model);
        sim.step(state); // the first step takes out the velocities the joint forbids
        const auto [p0, l0] = momenta(state);
        double worstP = 0.0, worstL = 0.0;
        for (long k = 1; k < stepsFor(1.0, model.simulation.dt); ++k)
        {
            sim.step(state);
            const auto [p, l] = momenta(state);
            worstP = std::max(worstP, (p - p0).norm());
            worstL = std::max(worstL, (l - l0).norm());
        }
        const auto [position, rotation] = sim.jointErrors(state);
        EXPECT_LE(position, 1e-9) << "the child's anchor stays in the parent's plane";
        EXPECT_LE(rotation, 1e-9) << "the child's normal stays on the parent's";
        EXPECT_LE(worstP, 1e-12 * p0.norm() + 1e-13) << "momentum";
        EXPECT_LE(worstL, 1e-9 * l0.norm()) << "angular momentum about the origin";
        EXPECT_GT((state.bodies[1].position_W - model.bodies[1].position_W).norm(), 0.1) << "it did move";
    }
}

} // namespace
} // namespace frontier::sim::test
