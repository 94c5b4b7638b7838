// tests/sim/free_spin_test.cpp: a free asymmetric body spinning near its intermediate principal
// axis with the first-order integrator: energy and angular momentum kept (docs/method.md §4,
// eq. (8a)), and the flip over that the intermediate-axis instability makes it do; the same
// and a top on a ball joint spinning faster than a quarter radian a step.
#include "sim_test_util.h"

#include <gtest/gtest.h>

namespace frontier::sim::test
{
namespace
{

// A 0.3 x 0.2 x 0.1 m box of 1 kg (principal moments 0.00417, 0.00833, 0.01083 kg m^2 about its
// x, y, z) in zero gravity, spinning at 20 rad/s about y, its intermediate axis, with 1% about
// the other two; `euler`, dt = 1 ms, 20 s.
const char* const cSpinningBox = R"(name: spinning box
simulation: {dt: 0.001, duration: 20.0, gravity: [0, 0, 0], solver: linear, integrator: euler}
bodies:
  - name: box
    shape: {type: box, size: [0.3, 0.2, 0.1]}
    mass: 1.0
    position: [0, 0, 0]
    angular_velocity: [0.2, 20, 0.2]
)";

// Torque-free motion keeps the kinetic energy and the world angular momentum. The euler step's
// rotation update R = exp(h w) R (w held fixed in the body over the step) would carry the box
// from its intermediate axis towards its minor one and raise the energy by tens of percent; the
// free rotation at constant angular momentum keeps it. The box must also really tumble: about
// its intermediate axis the spin reverses (w_y in the body frame changes sign) every few seconds.
TEST(FreeSpin, BoxNearItsIntermediateAxisKeepsEnergyAndMomentumWithEuler)
{
    TestDir dir;
    const core::Model model = io::loadScene(dir.write("spinning_box.yaml", cSpinningBox));
    ASSERT_EQ(model.simulation.integrator, core::IntegratorKind::Euler);
    core::State state = core::initialState(model);
    core::Simulator simulator(model);
    const double e0 = core::kineticEnergy(model, state);
    const core::Vec3 l0 = core::totalMomentum(model, state).angular;
    ASSERT_GT(e0, 1.0);
    double energyDrift = 0.0;
    double momentumDrift = 0.0;
    double lowestSpin = 20.0; // rad/s, w . y_body
    const long steps = stepsFor(model.simulation.duration, model.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        simulator.step(state);
        const core::BodyState& box = state.bodies[0];
        energyDrift = std::max(energyDrift, std::abs(core::kineticEnergy(model, state) - e0) / e0);
        momentumDrift =
            std::max(momentumDrift, (core::totalMomentum(model, state).angular - l0).norm() / l0.norm());
        lowestSpin = std::min(lowestSpin, (box.orientation_WB.conjugate() * box.angularVelocity_W).y());
    }
    std::printf(
        "spinning box, euler, 20 s: energy drift %.3g, angular momentum drift %.3g, lowest spin %.3g rad/s\n",
        energyDrift, momentumDrift, lowestSpin);
    EXPECT_LT(energyDrift, 0.01);
    EXPECT_LT(momentumDrift, 1e-8);
    EXPECT_LT(lowestSpin, -15.0); // flipped over
}

// Steps a scene and reports the largest drift of its total energy (J) and of its world angular
// momentum's z component (N m s) from their starting values.
struct SpinDrift
{
    double energy = 0.0;
    double momentumZ = 0.0;
    double jointError = 0.0; // largest joint position error (m)
};

SpinDrift runSpin(const core::Model& model)
{
    core::State state = core::initialState(model);
    core::Simulator simulator(model);
    const double e0 = core::totalEnergy(model, state);
    const double l0 = core::totalMomentum(model, state).angular.z();
    SpinDrift drift;
    const long steps = stepsFor(model.simulation.duration, model.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        simulator.step(state);
        drift.energy = std::max(drift.energy, std::abs(core::totalEnergy(model, state) - e0));
        drift.momentumZ =
            std::max(drift.momentumZ, std::abs(core::totalMomentum(model, state).angular.z() - l0));
        drift.jointError = std::max(drift.jointError, simulator.jointErrors(state).first);
    }
    return drift;
}

// The box above at 400 rad/s: 0.4 rad a step. No joint holds it, so it still takes the free
// rotation (with exp(h w) its energy doubled in 20 s; this one's swings by 0.2% as it tumbles).
TEST(FreeSpin, FastBoxKeepsEnergyAndMomentumWithEuler)
{
    std::string text = cSpinningBox;
    text.replace(text.find("[0.2, 20, 0.2]"), 14, "[4, 400, 4]");
    const core::Model model = io::loadSceneFromString(text, "fast_box.yaml");
    core::State state = core::initialState(model);
    const double e0 = core::kineticEnergy(model, state);
    const double l0 = core::totalMomentum(model, state).angular.norm();
    const SpinDrift drift = runSpin(model);
    std::printf("box at 400 rad/s, euler, 20 s: energy drift %.3g of %.4g J, angular momentum (z) drift %.3g "
                "of %.4g N m s\n",
                drift.energy, e0, drift.momentumZ, l0);
    EXPECT_LT(drift.energy, 0.01 * e0);
    EXPECT_LT(drift.momentumZ, 1e-8 * l0);
}

// A top: a 0.08 x 0.02 x 0.02 m link of 0.1 kg on a ball joint at the end of its long axis, held
// horizontal under gravity and spinning at 500 rad/s about that axis (0.5 rad a step) with 20 rad/s
// about the vertical: it precesses. Gravity's torque about the anchor is horizontal and the joint's
// force passes through the anchor, so the energy and the vertical angular momentum are kept; with
// exp(h w) for a spin this fast the energy tripled in 5 s (a 100-link chain's tip spun up this way
// and tore the chain apart).
TEST(FreeSpin, FastTopOnBallJointKeepsEnergyWithEuler)
{
    const char* const top = R"(name: top
simulation: {dt: 0.001, duration: 5.0, gravity: [0, 0, -9.81], solver: linear, integrator: euler}
bodies:
  - {name: link, shape: {type: box, size: [0.08, 0.02, 0.02]}, mass: 0.1, position: [0.05, 0, 2],
     angular_velocity: [500, 0, 20]}
joints:
  - {name: pivot, type: ball, parent: world, child: link, anchor: [0, 0, 2]}
)";
    const core::Model model = io::loadSceneFromString(top, "top.yaml");
    core::State state = core::initialState(model);
    const double spin = core::kineticEnergy(model, state); // J
    const double l0 = std::abs(core::totalMomentum(model, state).angular.z());
    const SpinDrift drift = runSpin(model);
    std::printf("top at 500 rad/s, euler, 5 s: energy drift %.3g of %.4g J kinetic, vertical angular "
                "momentum drift %.3g of %.3g N m s, joint error %.3g m\n",
                drift.energy, spin, drift.momentumZ, l0, drift.jointError);
    EXPECT_LT(drift.energy, 0.02 * spin);
    EXPECT_LT(drift.momentumZ, 1e-3 * l0);
    EXPECT_LT(drift.jointError, 1e-9);
}

} // namespace
} // namespace frontier::sim::test
