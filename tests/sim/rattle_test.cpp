// tests/sim/rattle_test.cpp: the second-order integrator (`rattle`) against the first-order one:
// convergence orders measured by halving the time step, energy over 1000 s of a conservative
// chain, joint gaps, and momentum of a free articulated body.
#include "sim_test_util.h"
#include "tests/soak.h"

#include <cmath>
#include <gtest/gtest.h>
#include <sstream>

namespace frontier::sim::test
{
namespace
{

// A chain of `links` capsules (0.1 m, 0.1 kg) on ball joints hanging from the world at (0, 0, 2),
// released straight at `angle` (rad) from the downward vertical. No floor: a conservative system.
std::string chainScene(int links, double angle)
{
    const double length = 0.1; // m
    const core::Vec3 along(std::sin(angle), 0.0, -std::cos(angle));
    const core::Quat q = core::Quat::FromTwoVectors(core::Vec3::UnitZ(), along);
    std::ostringstream yaml;
    yaml.precision(17);
    yaml << "name: chain\nsimulation: {dt: 0.001, duration: 1.0, gravity: [0, 0, -9.81]}\nbodies:\n";
    for (int k = 0; k < links; ++k)
    {
        const core::Vec3 c = core::Vec3(0, 0, 2) + (k + 0.5) * length * along;
        yaml << "  - name: link" << k << "\n    shape: {type: capsule, radius: 0.01, length: 0.08}\n"
             << "    mass: 0.1\n    position: [" << c.x() << ", " << c.y() << ", " << c.z() << "]\n"
             << "    orientation: [" << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << "]\n";
    }
    yaml << "joints:\n";
    for (int k = 0; k < links; ++k)
    {
        const core::Vec3 a = core::Vec3(0, 0, 2) + k * length * along;
        yaml << "  - {name: j" << k
             << ", type: ball, parent: " << (k == 0 ? std::string("world") : "link" + std::to_string(k - 1))
             << ", child: link" << k << ", anchor: [" << a.x() << ", " << a.y() << ", " << a.z() << "]}\n";
    }
    return yaml.str();
}

core::Model withStep(core::Model model, core::IntegratorKind integrator, double dt)
{
    model.simulation.integrator = integrator;
    model.simulation.dt = dt;
    return model;
}

core::State simulate(const core::Model& model, double duration)
{
    core::State state = core::initialState(model);
    core::Simulator simulator(model);
    const long steps = stepsFor(duration, model.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        simulator.step(state);
    }
    return state;
}

// Largest centre-of-mass distance between two states (m).
double positionError(const core::State& a, const core::State& b)
{
    double e = 0.0;
    for (std::size_t i = 0; i < a.bodies.size(); ++i)
    {
        e = std::max(e, (a.bodies[i].position_W - b.bodies[i].position_W).norm());
    }
    return e;
}

// Errors at `duration` for dt, dt/2, dt/4 against a rattle run at dt/32; returns the two
// measured slopes log2(e(h) / e(h/2)).
std::pair<double, double> measuredOrder(const core::Model& model, core::IntegratorKind integrator, double dt,
                                        double duration, const char* label)
{
    const core::State reference = simulate(withStep(model, core::IntegratorKind::Rattle, dt / 32), duration);
    double errors[3];
    for (int k = 0; k < 3; ++k)
    {
        const double h = dt / (1 << k);
        errors[k] = positionError(simulate(withStep(model, integrator, h), duration), reference);
    }
    const double slope1 = std::log2(errors[0] / errors[1]);
    const double slope2 = std::log2(errors[1] / errors[2]);
    std::printf("%s %s: errors %.3g %.3g %.3g m at dt %g %g %g s; slopes %.3f %.3f\n", label,
                core::integratorName(integrator), errors[0], errors[1], errors[2], dt, dt / 2, dt / 4, slope1,
                slope2);
    return {slope1, slope2};
}

TEST(Convergence, DoublePendulumIsFirstOrderWithEulerAndSecondOrderWithRattle)
{
    const core::Model model = loadBundled("double_pendulum.yaml");
    const auto [e1, e2] = measuredOrder(model, core::IntegratorKind::Euler, 0.002, 1.0, "double pendulum");
    EXPECT_NEAR(e1, 1.0, 0.2);
    EXPECT_NEAR(e2, 1.0, 0.2);
    const auto [r1, r2] = measuredOrder(model, core::IntegratorKind::Rattle, 0.002, 1.0, "double pendulum");
    EXPECT_NEAR(r1, 2.0, 0.2);
    EXPECT_NEAR(r2, 2.0, 0.2);
}

TEST(Convergence, TenLinkChainIsFirstOrderWithEulerAndSecondOrderWithRattle)
{
    const core::Model model = io::loadSceneFromString(chainScene(10, std::numbers::pi / 3), "chain10.yaml");
    const auto [e1, e2] = measuredOrder(model, core::IntegratorKind::Euler, 0.001, 0.5, "10-link chain");
    EXPECT_NEAR(e1, 1.0, 0.2);
    EXPECT_NEAR(e2, 1.0, 0.2);
    const auto [r1, r2] = measuredOrder(model, core::IntegratorKind::Rattle, 0.001, 0.5, "10-link chain");
    EXPECT_NEAR(r1, 2.0, 0.2);
    EXPECT_NEAR(r2, 2.0, 0.2);
}

// 1000 s of the conservative 10-link chain released at 0.5 rad, rattle at dt = 2.5 ms.
// Bound (docs/method.md §9): the energy error stays under 1e-5 of the chain's m g L (9.81 J)
// and does not drift: its largest value over the last 100 s is at most twice that over the
// first 100 s (a symplectic scheme's error oscillates; a drifting one would grow tenfold from the
// first to the tenth 100 s). Joint gaps under 1e-9 m after every step.
TEST(RattleEnergy, TenLinkChainKeepsEnergyWithoutDriftForAThousandSeconds)
{
    FRONTIER_SOAK_TEST();
    const core::Model model = withStep(io::loadSceneFromString(chainScene(10, 0.5), "chain10.yaml"),
                                       core::IntegratorKind::Rattle, 0.0025);
    core::State state = core::initialState(model);
    core::Simulator simulator(model);
    const double e0 = core::totalEnergy(model, state);
    const double scale = 10 * 0.1 * 9.81 * 1.0; // J: m g L of the whole chain
    const long steps = stepsFor(1000.0, model.simulation.dt);
    const long window = stepsFor(100.0, model.simulation.dt);
    double first = 0.0; // largest |E - E0| over the first 100 s (J)
    double last = 0.0;  // ... over the last 100 s
    double worst = 0.0;
    double gap = 0.0;
    for (long k = 0; k < steps; ++k)
    {
        simulator.step(state);
        const double error = std::abs(core::totalEnergy(model, state) - e0);
        worst = std::max(worst, error);
        if (k < window)
        {
            first = std::max(first, error);
        }
        if (k >= steps - window)
        {
            last = std::max(last, error);
        }
        gap = std::max(gap, simulator.lastStep().maxJointErrorM);
        ASSERT_LT(simulator.lastStep().maxJointErrorM, 1e-9) << "at step " << state.step;
    }
    RecordProperty("energy_error_relative", sci(worst / scale));
    std::printf(
        "10-link chain, rattle, dt 2.5 ms, 1000 s: energy error up to %.3g J (%.3g of m g L), first 100 s "
        "%.3g J, last 100 s %.3g J; joint gap up to %.3g m\n",
        worst, worst / scale, first, last, gap);
    EXPECT_LT(worst, 1e-5 * scale);
    EXPECT_LT(last, 2.0 * first);
}

} // namespace
} // namespace frontier::sim::test
