// tests/sim/load_test.cpp: external loads (core::Load, core/actuation.h) against mechanics. A
// force over [from, to) gives the momentum F (to - from) whatever the time step; the work of a
// constant force on a pendulum equals the change of its energy; an impulse at a point off the
// centre of mass gives v = p / m and the angular momentum r x p in the one step holding its instant; a
// force in the body frame turns with the body.
#include "joint_models.h"
#include "sim_test_util.h"

#include <cmath>
#include <gtest/gtest.h>

namespace frontier::sim::test
{
namespace
{

using core::IntegratorKind;

// A free 2 kg box in zero gravity.
core::Model freeBox(IntegratorKind integrator, double dt)
{
    core::Model model = emptyTestModel(core::Vec3::Zero(), integrator, dt);
    model.bodies.push_back(jointTestBox("box", 2.0, core::Vec3(0.3, 0.2, 0.1), core::Vec3(0.0, 0.0, 1.0)));
    return model;
}

TEST(Loads, AForceOverAWindowGivesItsImpulseWhateverTheStep)
{
    const core::Vec3 force(2.0, -1.0, 0.5); // N
    constexpr double from = 0.00025;        // s: windows that do not fall on step boundaries
    constexpr double to = 0.10075;
    for (const IntegratorKind integrator : cIntegrators)
    {
        for (const double dt : {1e-3, 7e-4})
        {
            core::Model model = freeBox(integrator, dt);
            core::Load load;
            load.body = 0;
            load.force = force;
            load.from = from;
            load.to = to;
            model.loads.push_back(load);
            core::Simulator simulator(model);
            core::State state = core::initialState(model);
            for (long k = 0; k < stepsFor(0.2, dt); ++k)
            {
                simulator.step(state);
            }
            const core::Vec3 momentum = model.bodies[0].mass * state.bodies[0].velocity_W;
            EXPECT_LT((momentum - force * (to - from)).norm(), 1e-13)
                << core::integratorName(integrator) << " dt " << dt;
            EXPECT_LT(state.bodies[0].angularVelocity_W.norm(), 1e-15);
        }
    }
}

// The rod of hingedRod hanging from its hinge, pushed at its centre of mass by a constant world
// force during [0.1, 0.6): the energy it gains (kinetic + gravitational) is the force's work,
// F . (x(0.6) - x(0.1)), to first order in dt.
TEST(Loads, WorkOfAConstantForceIsTheChangeOfEnergy)
{
    const core::Vec3 force(3.0, 0.0, 1.0); // N
    constexpr double dt = 1e-4;
    for (const IntegratorKind integrator : cIntegrators)
    {
        core::Model model = hingedRod(0.0, std::nullopt, core::Vec3(0.0, 0.0, -9.81), integrator, dt);
        core::Load load;
        load.body = 0;
        load.force = force;
        load.from = 0.1;
        load.to = 0.6;
        model.loads.push_back(load);
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        double energyBefore = 0.0;
        core::Vec3 before = core::Vec3::Zero();
        for (long k = 0; k < stepsFor(0.6, dt); ++k)
        {
            if (k == stepsFor(0.1, dt))
            {
                energyBefore = core::totalEnergy(model, state);
                before = state.bodies[0].position_W;
            }
            simulator.step(state);
        }
        const double work = force.dot(state.bodies[0].position_W - before);
        const double gained = core::totalEnergy(model, state) - energyBefore;
        RecordProperty(std::string("work_j_") + core::integratorName(integrator), sci(work));
        EXPECT_GT(std::abs(work), 0.1);
        EXPECT_NEAR(gained, work, 2e-3 * std::abs(work)) << core::integratorName(integrator);
    }
}

TEST(Loads, AnImpulseAtAPointLandsInTheStepHoldingItsInstant)
{
    const core::Vec3 impulse(0.0, 4.0, 0.0); // N s
    const core::Vec3 point(0.15, 0.0, 0.05); // m, body frame (from the centre of mass)
    for (const IntegratorKind integrator : cIntegrators)
    {
        core::Model model = freeBox(integrator, 1e-3);
        core::Load load;
        load.body = 0;
        load.frame = core::LoadFrame::Body;
        load.force = impulse;
        load.point = point;
        load.instant = 0.0503;
        model.loads.push_back(load);
        const core::Body& box = model.bodies[0];
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        for (int k = 0; k < 100; ++k)
        {
            const double t0 = state.time;
            simulator.step(state);
            const bool after = t0 + model.simulation.dt > 0.0503;
            const core::Vec3 velocity = after ? core::Vec3(impulse / box.mass) : core::Vec3::Zero();
            ASSERT_LT((state.bodies[0].velocity_W - velocity).norm(), 1e-13) << "step " << k;
            // Angular momentum about the centre of mass: r x p from the instant on (the box had not
            // turned then: its body frame was the world's), kept by the free rotation after it.
            const core::Vec3 momentum =
                core::worldInertia(box, state.bodies[0]) * state.bodies[0].angularVelocity_W;
            const core::Vec3 expected = after ? core::Vec3(point.cross(impulse)) : core::Vec3::Zero();
            ASSERT_LT((momentum - expected).norm(), 1e-13)
                << core::integratorName(integrator) << ", step " << k;
        }
    }
}

TEST(Loads, ABodyFrameForceTurnsWithTheBody)
{
    // A box spinning about z at w, pushed along its own x: the force averages out over a turn,
    // while a world-frame force would not.
    core::Model model = freeBox(IntegratorKind::Euler, 1e-4);
    const double w = 2.0 * 3.14159265358979323846; // one turn per second
    model.bodies[0].angularVelocity_W = core::Vec3(0.0, 0.0, w);
    core::Load load;
    load.body = 0;
    load.frame = core::LoadFrame::Body;
    load.force = core::Vec3(1.0, 0.0, 0.0);
    load.to = 1.0;
    model.loads.push_back(load);
    core::Simulator simulator(model);
    core::State state = core::initialState(model);
    for (long k = 0; k < stepsFor(1.0, 1e-4); ++k)
    {
        simulator.step(state);
    }
    EXPECT_LT(state.bodies[0].velocity_W.norm(), 1e-3); // 0.5 m/s had the force stayed along x
}

} // namespace
} // namespace frontier::sim::test
