// tests/sim/rattle_test.cpp: the second-order integrator (`rattle`) against the first-order one:
// convergence orders measured by halving the time step, energy over 1000 s of a conservative
// chain, joint gaps, and momentum of a free articulated body; the fourth-order composition
// (`rattle4`, docs/method.md §11): its order, energy and momentum of a free chain, and a composition
// of one stage that is rattle itself.
#include "collision/contacts.h"
#include "core/step/step_stages.h"
#include "core/steppers/rattle4_stepper.h"
#include "sim_test_util.h"
#include "tests/soak.h"

#include <array>
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

// rattle4 (docs/method.md §11): the position of one body at `duration` for dt, dt/2, dt/4, dt/8
// against a rattle4 run at dt/32; the joints' position iteration converged to 1e-13 so that its
// tolerance does not floor the errors. Returns the three slopes log2(e(h) / e(h/2)).
std::array<double, 3> fourthOrderSlopes(const core::Model& model, std::size_t body, double dt,
                                        double duration, const char* label)
{
    core::StepOptions options;
    options.stabilizationTolerance = 1e-13;
    const auto run = [&](double h)
    {
        const core::Model m = withStep(model, core::IntegratorKind::Rattle4, h);
        core::State state = core::initialState(m);
        core::Simulator simulator(m, options);
        const long steps = stepsFor(duration, h);
        for (long k = 0; k < steps; ++k)
        {
            simulator.step(state);
            EXPECT_FALSE(simulator.lastStep().secondOrderFallback) << label << " at step " << state.step;
        }
        return state.bodies[body].position_W;
    };
    const core::Vec3 reference = run(dt / 32);
    double errors[4];
    for (int k = 0; k < 4; ++k)
    {
        errors[k] = (run(dt / (1 << k)) - reference).norm();
    }
    std::array<double, 3> slopes{};
    for (int k = 0; k < 3; ++k)
    {
        slopes[static_cast<std::size_t>(k)] = std::log2(errors[k] / errors[k + 1]);
    }
    std::printf("%s rattle4: errors %.3g %.3g %.3g %.3g m at dt %g s and halvings; slopes %.3f %.3f %.3f\n",
                label, errors[0], errors[1], errors[2], errors[3], dt, slopes[0], slopes[1], slopes[2]);
    return slopes;
}

TEST(Convergence, DoublePendulumIsFourthOrderWithRattle4)
{
    const core::Model model = loadBundled("double_pendulum.yaml");
    for (const double slope : fourthOrderSlopes(model, 1, 0.008, 1.0, "double pendulum"))
    {
        EXPECT_NEAR(slope, 4.0, 0.3);
    }
}

TEST(Convergence, TenLinkChainIsFourthOrderWithRattle4)
{
    const core::Model model = io::loadSceneFromString(chainScene(10, std::numbers::pi / 3), "chain10.yaml");
    for (const double slope : fourthOrderSlopes(model, 9, 0.002, 0.5, "10-link chain"))
    {
        EXPECT_NEAR(slope, 4.0, 0.3);
    }
}

// The 30-link chain of scenes/chain30.yaml, its tip at 1 s from dt = 0.5 ms down: fourth order
// there (at 1 ms and above the whip of its tip is not yet resolved, docs/benchmarks.md).
TEST(Convergence, Chain30IsFourthOrderWithRattle4)
{
    FRONTIER_SOAK_TEST();
    const core::Model model = loadBundled("chain30.yaml");
    for (const double slope : fourthOrderSlopes(model, model.bodies.size() - 1, 0.0005, 1.0, "chain30"))
    {
        EXPECT_NEAR(slope, 4.0, 0.3);
    }
}

// A free chain of `links` capsules on ball joints in zero gravity, straight along x, each link
// spinning at its own rate; linear velocities follow from the joints (each anchor moves alike on
// both links), so the state starts on the velocity constraints.
std::pair<core::Model, core::State> spinningFreeChain(int links)
{
    std::ostringstream yaml;
    yaml << "name: free chain\nsimulation: {dt: 0.002, duration: 1.0, gravity: [0, 0, 0]}\nbodies:\n";
    for (int k = 0; k < links; ++k)
    {
        yaml << "  - name: link" << k << "\n    shape: {type: capsule, radius: 0.01, length: 0.08}\n"
             << "    mass: 0.1\n    position: [" << 0.1 * k + 0.05 << ", 0, 0]\n"
             << "    orientation: [0.7071067811865476, 0, 0.7071067811865476, 0]\n";
    }
    yaml << "joints:\n";
    for (int k = 1; k < links; ++k)
    {
        yaml << "  - {name: j" << k << ", type: ball, parent: link" << k - 1 << ", child: link" << k
             << ", anchor: [" << 0.1 * k << ", 0, 0]}\n";
    }
    core::Model model = io::loadSceneFromString(yaml.str(), "free_chain.yaml");
    core::State state = core::initialState(model);
    for (int k = 0; k < links; ++k)
    {
        core::BodyState& s = state.bodies[static_cast<std::size_t>(k)];
        s.angularVelocity_W = core::Vec3(0.3 + 0.2 * k, 2.0 - 0.35 * k, 1.0 + 0.5 * std::sin(k));
        if (k == 0)
        {
            s.velocity_W = core::Vec3(0.1, -0.2, 0.05);
            continue;
        }
        const core::BodyState& p = state.bodies[static_cast<std::size_t>(k - 1)];
        const core::Vec3 anchor(0.1 * k, 0, 0);
        const core::Vec3 anchorVelocity = p.velocity_W + p.angularVelocity_W.cross(anchor - p.position_W);
        s.velocity_W = anchorVelocity - s.angularVelocity_W.cross(anchor - s.position_W);
    }
    return {std::move(model), std::move(state)};
}

// The free 8-link chain, rattle4 at dt = 5 ms for 2 x 20 s: symplectic, so the energy error
// oscillates without a trend (its largest value over [0, 2T] is under 1.5 times that over
// [0, T], and under 1e-6 of the kinetic energy); the joint impulses are internal, so the angular
// momentum stays to round-off; joint gaps stay under the 1e-10 m tolerance after every step.
// By hand, 1000 s of the same chain: docs/method.md §11.
TEST(Rattle4Energy, FreeChainKeepsEnergyAndAngularMomentumWithoutDrift)
{
    auto [model, state] = spinningFreeChain(8);
    model = withStep(model, core::IntegratorKind::Rattle4, 0.005);
    core::Simulator simulator(model);
    const double e0 = core::totalEnergy(model, state);
    const core::Momentum p0 = core::totalMomentum(model, state);
    ASSERT_GT(e0, 0.01);
    const long half = stepsFor(20.0, model.simulation.dt);
    double first = 0.0; // largest |E - E0| over [0, T] (J)
    double whole = 0.0; // ... over [0, 2T]
    double angular = 0.0;
    double gap = 0.0;
    double turn = 0.0; // the last link's turning, integral of |w| dt (rad)
    for (long k = 0; k < 2 * half; ++k)
    {
        simulator.step(state);
        ASSERT_FALSE(simulator.lastStep().secondOrderFallback) << "at step " << state.step;
        const double error = std::abs(core::totalEnergy(model, state) - e0);
        whole = std::max(whole, error);
        if (k < half)
        {
            first = whole;
        }
        const core::Momentum p = core::totalMomentum(model, state);
        angular = std::max(angular, (p.angular - p0.angular).norm() / p0.angular.norm());
        gap = std::max(gap, simulator.lastStep().maxJointErrorM);
        turn += model.simulation.dt * state.bodies.back().angularVelocity_W.norm();
    }
    std::printf(
        "free 8-link chain, rattle4, dt 5 ms: energy error up to %.3g J over 20 s, %.3g J over 40 s "
        "(E0 %.3g J); angular momentum %.3g (relative); joint gap up to %.3g m; last link turned %.0f rad\n",
        first, whole, e0, angular, gap, turn);
    EXPECT_GT(turn, 20.0 * std::numbers::pi); // it tumbled
    EXPECT_LT(whole, 1e-6 * e0);
    EXPECT_LT(whole, 1.5 * first);
    EXPECT_LT(angular, 1e-10);
    EXPECT_LE(gap, 1e-10);
}

// With joint limits, contacts or drives the step still runs: contact and limit rows (one-sided,
// not time-reversible) make the step one rattle step, which the statistics say.
TEST(Rattle4, StepWithContactIsOneRattleStep)
{
    core::Model model = loadBundled("bouncing_ball.yaml");
    model.simulation.integrator = core::IntegratorKind::Rattle4;
    core::State state = core::initialState(model);
    collision::ContactDetector contacts(model,
                                        collision::contactMargin(core::longestStage(model.simulation)));
    core::Simulator simulator(model, {}, &contacts);
    long composed = 0;
    long single = 0;
    for (long k = 0; k < stepsFor(2.0, model.simulation.dt); ++k)
    {
        simulator.step(state);
        (simulator.lastStep().secondOrderFallback ? single : composed)++;
    }
    std::printf("bouncing ball, rattle4: %ld composed steps, %ld single rattle steps\n", composed, single);
    EXPECT_GT(composed, 0);
    EXPECT_GT(single, 0);
    EXPECT_NEAR(state.time, 2.0, 1e-12);
}

// A step composed of one RATTLE stage of coefficient 1 (core/steppers/rattle4_stepper.h) is the
// rattle step, bit for bit: the composition adds nothing of its own but the stages.
TEST(Rattle4, CompositionOfOneStageIsRattle)
{
    const core::Model model = withStep(io::loadSceneFromString(chainScene(5, 0.7), "chain5.yaml"),
                                       core::IntegratorKind::Rattle, 0.002);
    core::State byRattle = core::initialState(model);
    core::State composed = byRattle;
    core::Simulator simulator(model);
    core::StepStages stages(model, {}, nullptr);
    core::ComposedRattleStepper stepper(stages, {1.0});
    for (int k = 0; k < 300; ++k)
    {
        simulator.step(byRattle);
        stepper.step(composed);
        stages.finishActuation();
        ASSERT_TRUE(bitIdentical(byRattle, composed)) << "step " << k;
    }
    EXPECT_EQ(stages.stats().stabilizationIterations, simulator.lastStep().stabilizationIterations);
}

} // namespace
} // namespace frontier::sim::test
