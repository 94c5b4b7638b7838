// tests/core/state_test.cpp: the energy of a state (core/state.cpp), which the run loop checks
// every step: the rotational part in the body frame equals the world-frame form, and a rotated
// body spinning about a world axis has the energy of the body axis that maps there.
#include "core/state.h"
#include "random_model.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace frontier::test
{

// 1/2 m v^2 + 1/2 w . (R I_B R^T) w summed over the moving bodies of random forests (random
// inertias, poses and velocities) to round-off.
TEST(StateEnergy, KineticEnergyEqualsTheWorldFrameSum)
{
    for (unsigned seed : {3u, 4u, 5u})
    {
        const core::Model model = randomForest(seed, 3, 8);
        const std::unique_ptr<Problem> problem = makeProblem(model);
        const core::State& state = problem->state;
        double expected = 0.0;
        for (std::size_t i = 0; i < model.bodies.size(); ++i)
        {
            const core::Body& body = model.bodies[i];
            if (body.isStatic)
            {
                continue;
            }
            const core::BodyState& s = state.bodies[i];
            expected += 0.5 * body.mass * s.velocity_W.squaredNorm() +
                        0.5 * s.angularVelocity_W.dot(core::worldInertia(body, s) * s.angularVelocity_W);
        }
        ASSERT_GT(expected, 0.0);
        EXPECT_NEAR(core::kineticEnergy(model, state), expected, 1e-12 * expected) << "seed " << seed;
    }
}

// A body with principal moments (1, 2, 3) kg m^2 turned 120 degrees about (1, 1, 1), which takes
// body x, y, z to world y, z, x: its body z axis lies along world x, so spinning at 2 rad/s about
// world x gives 1/2 * 3 * 2^2 = 6 J (the inverse rotation would pick body y: 4 J).
TEST(StateEnergy, RotatedBodyUsesTheInertiaOfItsBodyAxis)
{
    core::Model model;
    core::Body body;
    body.name = "spinner";
    body.mass = 5.0;
    body.inertia_B = Vec3(1.0, 2.0, 3.0).asDiagonal();
    body.orientation_WB = Quat(Eigen::AngleAxisd(2 * std::numbers::pi / 3, Vec3(1.0, 1.0, 1.0).normalized()));
    body.angularVelocity_W = Vec3(2.0, 0.0, 0.0);
    model.bodies.push_back(body);
    const core::State state = core::initialState(model);
    ASSERT_LT((body.orientation_WB * Vec3::UnitZ() - Vec3::UnitX()).norm(), 1e-12);
    EXPECT_NEAR(core::kineticEnergy(model, state), 6.0, 1e-12);
}

} // namespace frontier::test
