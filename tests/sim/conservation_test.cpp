// tests/sim/conservation_test.cpp: momentum of the tumbling doll without gravity, and joint drift
// of the doll and of the 30-link chain at every step.
#include "sim_test_util.h"
#include "tests/soak.h"

#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>

namespace frontier::sim::test
{
namespace
{

constexpr double cJointTolM = 1e-6; // m: the bound on the joint position error

// scenes/doll_zero_g.yaml: 15 bodies, 14 joints of every kind but nail, prismatic and fixed,
// tumbling in zero gravity for 5 s. Joint impulses (and the SHAKE projection) are internal, so the
// total linear and angular momentum must stay what they were, to round-off.
TEST(ZeroGravityDoll, MomentumIsConservedAndJointsHoldAtEveryStep)
{
    const core::Model model = loadBundled("doll_zero_g.yaml");
    ASSERT_EQ(model.bodies.size(), 15u);
    ASSERT_EQ(model.joints.size(), 14u);
    ASSERT_TRUE(model.simulation.gravity.isZero());
    core::State state = core::initialState(model);
    const core::Momentum p0 = core::totalMomentum(model, state);
    ASSERT_GT(p0.linear.norm(), 0.1);
    ASSERT_GT(p0.angular.norm(), 1.0);

    core::Simulator simulator(model);
    double linearError = 0.0;
    double angularError = 0.0;
    double jointError = 0.0;
    double pelvisTurn = 0.0; // integral of |w| dt (rad)
    const long steps = stepsFor(model.simulation.duration, model.simulation.dt);
    ASSERT_EQ(steps, 5000);
    for (long k = 0; k < steps; ++k)
    {
        simulator.step(state);
        const core::Momentum p = core::totalMomentum(model, state);
        linearError = std::max(linearError, (p.linear - p0.linear).norm() / p0.linear.norm());
        angularError = std::max(angularError, (p.angular - p0.angular).norm() / p0.angular.norm());
        jointError = std::max(jointError, simulator.lastStep().maxJointErrorM);
        ASSERT_LT(simulator.lastStep().maxJointErrorM, cJointTolM) << "at step " << state.step;
        pelvisTurn += model.simulation.dt * state.bodies[0].angularVelocity_W.norm();
    }
    RecordProperty("linear_momentum_relative_error", sci(linearError));
    RecordProperty("angular_momentum_relative_error", sci(angularError));
    RecordProperty("max_joint_error_m", sci(jointError));
    std::printf("zero-g doll: momentum error linear %.3g, angular %.3g (relative); joint error %.3g m\n",
                linearError, angularError, jointError);
    EXPECT_LT(linearError, 1e-9);
    EXPECT_LT(angularError, 1e-9);
    // The doll really tumbled: the pelvis turned through more than two full turns.
    EXPECT_GT(pelvisTurn, 4.0 * std::numbers::pi);
    // And the joints are also held when measured independently of the step's statistics.
    EXPECT_LT(simulator.jointErrors(state).first, cJointTolM);
}

// scenes/chain30.yaml: 30 capsules on ball joints, released horizontal, swinging and whipping
// for 10 s; under the sanitizers the first 2 s (reference.chain30 runs all 10 s there).
TEST(Chain30, JointErrorStaysBelowAMicrometreForTenSeconds)
{
    const core::Model model = loadBundled("chain30.yaml");
    ASSERT_EQ(model.bodies.size(), 30u);
    ASSERT_EQ(model.joints.size(), 30u);
    core::State state = core::initialState(model);
    core::Simulator simulator(model);
    double jointError = 0.0;
    double fastest = 0.0;
    const double seconds = soakSeconds(10.0, 2.0);
    const long steps = stepsFor(seconds, model.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        simulator.step(state);
        jointError = std::max(jointError, simulator.lastStep().maxJointErrorM);
        ASSERT_LT(simulator.lastStep().maxJointErrorM, cJointTolM) << "at step " << state.step;
        fastest = std::max(fastest, state.bodies.back().velocity_W.norm());
    }
    RecordProperty("max_joint_error_m", sci(jointError));
    std::printf("chain30: largest joint error over %g s %.3g m; tip speed up to %.3g m/s\n", seconds,
                jointError, fastest);
    // It did swing (the tip falls 3 m: several m/s), and ends within the chain's reach of the pivot.
    EXPECT_GT(fastest, 5.0);
    const core::Vec3 pivot = model.joints[0].anchorParent;
    EXPECT_LT((state.bodies.back().position_W - pivot).norm(), 3.0);
}

} // namespace
} // namespace frontier::sim::test
