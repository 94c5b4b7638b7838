// tests/sim/pendulum_test.cpp: the single pendulum's large-angle period against the exact one
// (complete elliptic integral), and the double pendulum's energy drift.
#include "sim_test_util.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>
#include <vector>

namespace frontier::sim::test
{
namespace
{

// Complete elliptic integral of the first kind K(k) (modulus k) by the arithmetic-geometric
// mean: K(k) = pi / (2 AGM(1, sqrt(1 - k^2))).
double ellipticK(double k)
{
    double a = 1.0;
    double b = std::sqrt(1.0 - k * k);
    for (int i = 0; i < 60 && std::abs(a - b) > 1e-16 * a; ++i)
    {
        const double mean = 0.5 * (a + b);
        b = std::sqrt(a * b);
        a = mean;
    }
    return std::numbers::pi / (2.0 * a);
}

TEST(EllipticK, MatchesTheStandardLibraryAndKnownValues)
{
    EXPECT_NEAR(ellipticK(0.0), std::numbers::pi / 2.0, 1e-15);
    // K(1/sqrt 2) = Gamma(1/4)^2 / (4 sqrt(pi)).
    const double g = std::tgamma(0.25);
    EXPECT_NEAR(ellipticK(std::sqrt(0.5)), g * g / (4.0 * std::sqrt(std::numbers::pi)), 1e-14);
    for (double k : {0.1, 0.5, 0.9, 0.99})
    {
        EXPECT_NEAR(ellipticK(k), std::comp_ellint_1(k), 1e-13) << "k = " << k;
    }
}

// scenes/pendulum.yaml: a 1 kg ball (radius 0.05 m) on a revolute pivot at (0, 0, 2), 1 m, released
// at 60 degrees. It is a physical pendulum: I_pivot = I_axis + m d^2.
TEST(Pendulum, LargeAnglePeriodMatchesTheEllipticIntegral)
{
    const core::Model model = loadBundled("pendulum.yaml");
    ASSERT_EQ(model.bodies.size(), 1u);
    ASSERT_EQ(model.joints.size(), 1u);
    ASSERT_DOUBLE_EQ(model.simulation.dt, 1e-3);
    const core::Body& bob = model.bodies[0];
    const core::Joint& pivot = model.joints[0];
    ASSERT_EQ(pivot.type, core::JointType::Revolute);
    ASSERT_EQ(pivot.parent, core::cWorld);

    const core::Vec3 pivot_W = pivot.anchorParent;
    const core::Vec3 axis_W = pivot.axisParent.normalized(); // the world is the parent
    core::State state = core::initialState(model);
    const core::Vec3 arm0 = state.bodies[0].position_W - pivot_W;
    const double d = arm0.norm();
    const double g = model.simulation.gravity.norm();
    const double iAxis = axis_W.dot(core::worldInertia(bob, state.bodies[0]) * axis_W);
    const double iPivot = iAxis + bob.mass * d * d;
    // The angle from the downward vertical, positive towards +x (axis y, gravity -z).
    auto angle = [&](const core::BodyState& s)
    {
        const core::Vec3 arm = s.position_W - pivot_W;
        return std::atan2(arm.x(), -arm.z());
    };
    const double theta0 = angle(state.bodies[0]);
    ASSERT_NEAR(theta0, std::numbers::pi / 3.0, 1e-12);
    ASSERT_NEAR(d, 1.0, 1e-12);
    const double exact = 4.0 * std::sqrt(iPivot / (bob.mass * g * d)) * ellipticK(std::sin(theta0 / 2.0));

    // Zero crossings of the angle, linearly interpolated between steps, over 10 s (~4.6 periods).
    core::Simulator simulator(model);
    std::vector<double> crossings;
    double previous = theta0;
    const long steps = stepsFor(10.0, model.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        const double t = state.time;
        simulator.step(state);
        const double theta = angle(state.bodies[0]);
        if ((previous > 0.0) != (theta > 0.0))
        {
            crossings.push_back(t + model.simulation.dt * previous / (previous - theta));
        }
        previous = theta;
    }
    ASSERT_GE(crossings.size(), 8u);
    // Successive crossings are half a period apart.
    const double measured =
        2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    const double relative = (measured - exact) / exact;
    RecordProperty("period_exact_s", sci(exact));
    RecordProperty("period_measured_s", sci(measured));
    RecordProperty("period_relative_error", sci(relative));
    std::printf("pendulum: period %.6f s, exact %.6f s, relative error %.3g\n", measured, exact, relative);
    EXPECT_LT(std::abs(relative), 0.005) << "measured " << measured << " s, exact " << exact << " s";
    // The exact period is the large-angle one, 7% longer than the small-angle 2 pi sqrt(I/(m g d)).
    EXPECT_GT(exact, 1.07 * 2.0 * std::numbers::pi * std::sqrt(iPivot / (bob.mass * g * d)));
}

// scenes/double_pendulum.yaml: two 0.5 m, 1 kg rods on hinges, released horizontal; chaotic but
// conservative. The energy scale is the initial total energy with the potential's zero at the
// lowest possible point of each rod's centre of mass (both hanging straight down): here
// m g (0.25 m) + m g (0.75 m) = 9.81 J, all of it potential at the release. The drift is the
// largest |E(t) - E(0)| over 10 s at dt = 1 ms, relative to that scale.
// Measured (symplectic Euler + SHAKE projection, dt = 1 ms, linear solver): 2.06e-3 of the
// 9.81 J scale, the largest excursion over 10 s (it oscillates, it does not grow steadily). The
// bound is about 2.4 times that.
constexpr double cDoublePendulumDriftBound = 5e-3;

TEST(DoublePendulum, EnergyDriftOverTenSecondsIsBounded)
{
    const core::Model model = loadBundled("double_pendulum.yaml");
    ASSERT_EQ(model.bodies.size(), 2u);
    ASSERT_EQ(model.joints.size(), 2u);
    ASSERT_DOUBLE_EQ(model.simulation.dt, 1e-3);
    core::State state = core::initialState(model);
    const core::Vec3 down = model.simulation.gravity.normalized();
    const double g = model.simulation.gravity.norm();

    // Lowest possible height of each centre of mass: the path pivot -> anchors -> centre of mass
    // stretched straight down. Joint k has child k and parent k - 1 (or the world) in this scene.
    double lowestPotential = 0.0;
    core::Vec3 pivot_W = model.joints[0].anchorParent;
    double reach = 0.0; // length of the stretched path from the world pivot so far (m)
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const core::Joint& joint = model.joints[k];
        ASSERT_EQ(joint.child, static_cast<int>(k));
        ASSERT_EQ(joint.parent, static_cast<int>(k) - 1);
        const core::Vec3 anchor_W = parentAnchor_W(state, joint);
        if (k > 0)
        {
            const core::Vec3 previousAnchor_W = parentAnchor_W(state, model.joints[k - 1]);
            reach += (anchor_W - previousAnchor_W).norm();
        }
        const core::Body& body = model.bodies[k];
        const double toCentre = (state.bodies[k].position_W - anchor_W).norm();
        const double lowest = -down.dot(pivot_W) - (reach + toCentre); // height along -gravity (m)
        lowestPotential += body.mass * g * lowest;
    }
    const double e0 = core::totalEnergy(model, state);
    const double scale = e0 - lowestPotential;
    ASSERT_NEAR(scale, 9.81 * (0.25 + 0.75), 1e-9);

    core::Simulator simulator(model);
    double drift = 0.0;
    const long steps = stepsFor(10.0, model.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        simulator.step(state);
        drift = std::max(drift, std::abs(core::totalEnergy(model, state) - e0));
    }
    const double relative = drift / scale;
    RecordProperty("energy_drift_relative", sci(relative));
    std::printf("double pendulum: largest relative energy drift over 10 s: %.4g\n", relative);
    EXPECT_LT(relative, cDoublePendulumDriftBound);
}

} // namespace
} // namespace frontier::sim::test
