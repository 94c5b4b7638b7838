// tests/run/external_forces_test.cpp: what a library user pushes a Simulation with between steps.
// core::Simulator::applyWrench acts over the next step only, with the impulse F dt and T dt for
// every integrator (euler, rattle's two half kicks, rattle4's three stages with the backward one),
// adds up when given twice, and conserves momentum through joints; a force at a point adds the
// torque of its lever. Gravity changed on the model between steps is the next step's.
#include "run/scene_loading.h"
#include "run/simulation.h"

#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <stdexcept>
#include <string>

namespace
{
using namespace frontier;

constexpr core::IntegratorKind cAllIntegrators[] = {core::IntegratorKind::Euler, core::IntegratorKind::Rattle,
                                                    core::IntegratorKind::Rattle4};

// A floor, a free 2 kg box `a` turned about z and a 3 kg box `b`, in zero gravity, b joined to a
// by a ball joint when `chain`; integrator by name.
core::Model boxes(core::IntegratorKind integrator, bool chain)
{
    std::string yaml =
        "simulation: {dt: 0.001, duration: 1.0, gravity: [0, 0, 0], integrator: " +
        std::string(core::integratorName(integrator)) +
        "}\n"
        "bodies:\n"
        "  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1], offset: 0}}\n"
        "  - {name: a, shape: {type: box, size: [0.3, 0.2, 0.1]}, mass: 2.0, position: [0, 0, 1],"
        " orientation: [0.9238795325, 0, 0, 0.3826834324]}\n"
        "  - {name: b, shape: {type: box, size: [0.2, 0.2, 0.2]}, mass: 3.0, position: [0.5, 0, 1]}\n";
    if (chain)
    {
        yaml += "joints:\n  - {name: link, type: ball, parent: a, child: b, anchor: [0.3, 0, 1]}\n";
    }
    return run::loadSceneText(yaml, "boxes.yaml").model;
}

constexpr int cA = 1; // body indices of boxes()
constexpr int cB = 2;

TEST(ExternalForces, AForceForOneStepGivesItsImpulseAndNothingAfter)
{
    const core::Vec3 force(3.0, -2.0, 1.5); // N
    for (const core::IntegratorKind integrator : cAllIntegrators)
    {
        const core::Model model = boxes(integrator, false);
        run::Simulation simulation(model);
        const double dt = model.simulation.dt;
        simulation.step(5);
        simulation.simulator().applyWrench(cA, force, core::Vec3::Zero());
        simulation.step();
        const core::Vec3 expected = force * dt / 2.0; // m/s
        const core::BodyState& a = simulation.state().bodies[cA];
        EXPECT_LT((a.velocity_W - expected).norm(), 1e-15) << core::integratorName(integrator);
        EXPECT_LT(a.angularVelocity_W.norm(), 1e-15) << core::integratorName(integrator);
        EXPECT_EQ(simulation.state().bodies[cB].velocity_W, core::Vec3::Zero());
        simulation.step();
        EXPECT_LT((simulation.state().bodies[cA].velocity_W - expected).norm(), 1e-15)
            << core::integratorName(integrator) << ": the wrench is gone after its step";
    }
}

TEST(ExternalForces, ATorqueGivesItsAngularImpulse)
{
    const core::Vec3 torque(0.4, 0.3, -0.2); // N m
    for (const core::IntegratorKind integrator : cAllIntegrators)
    {
        const core::Model model = boxes(integrator, false);
        run::Simulation simulation(model);
        const double dt = model.simulation.dt;
        simulation.simulator().applyWrench(cA, core::Vec3::Zero(), torque);
        simulation.step();
        const auto angularMomentum = [&]()
        {
            const core::BodyState& a = simulation.state().bodies[cA];
            return core::Vec3(core::worldInertia(model.bodies[cA], a) * a.angularVelocity_W);
        };
        EXPECT_LT((angularMomentum() - torque * dt).norm(), 1e-15) << core::integratorName(integrator);
        EXPECT_LT(simulation.state().bodies[cA].velocity_W.norm(), 1e-15);
        simulation.step(3);
        EXPECT_LT((angularMomentum() - torque * dt).norm(), 1e-15)
            << core::integratorName(integrator) << ": a free body keeps it";
    }
}

// Two wrenches on one body before a step add up; one given through applyForceAtPoint adds the
// torque (p - x) x F of its point p about the centre of mass x.
TEST(ExternalForces, WrenchesAddUpAndAForceAtAPointTurns)
{
    const core::Vec3 force(0.0, 2.0, 0.0);  // N
    const core::Vec3 point(0.1, 0.0, 1.05); // m, world
    const core::Model model = boxes(core::IntegratorKind::Euler, false);
    run::Simulation simulation(model);
    const double dt = model.simulation.dt;
    simulation.simulator().applyWrench(cA, force, core::Vec3::Zero());
    simulation.simulator().applyForceAtPoint(simulation.state(), cA, force, point);
    const core::Vec3 lever = point - simulation.state().bodies[cA].position_W;
    simulation.step();
    const core::BodyState& a = simulation.state().bodies[cA];
    EXPECT_LT((a.velocity_W - 2.0 * force * dt / 2.0).norm(), 1e-15);
    const core::Vec3 angularMomentum = core::worldInertia(model.bodies[cA], a) * a.angularVelocity_W;
    EXPECT_LT((angularMomentum - lever.cross(force) * dt).norm(), 1e-15);
}

// Through a ball joint: the total momentum of the two boxes changes by the force's impulse, with
// every integrator, and stays after the step; the angular momentum about the origin by p x F dt.
TEST(ExternalForces, ThroughAJointTheImpulseIsTheChangeOfTotalMomentum)
{
    const core::Vec3 force(1.0, 4.0, -2.0); // N
    for (const core::IntegratorKind integrator : cAllIntegrators)
    {
        const core::Model model = boxes(integrator, true);
        run::Simulation simulation(model);
        const double dt = model.simulation.dt;
        const core::Vec3 point = simulation.state().bodies[cB].position_W + core::Vec3(0.1, 0.0, 0.1);
        simulation.simulator().applyForceAtPoint(simulation.state(), cB, force, point);
        simulation.step();
        const core::Momentum after = core::totalMomentum(model, simulation.state());
        EXPECT_LT((after.linear - force * dt).norm(), 1e-14) << core::integratorName(integrator);
        EXPECT_LT((after.angular - point.cross(force) * dt).norm(), 1e-9) << core::integratorName(integrator);
        EXPECT_GT(simulation.state().bodies[cA].velocity_W.norm(), 0.0) << "the joint passes it on";
        simulation.step(20);
        EXPECT_LT((core::totalMomentum(model, simulation.state()).linear - force * dt).norm(), 1e-14)
            << core::integratorName(integrator);
    }
}

TEST(ExternalForces, RefusesAStaticBodyAnUnknownIndexAndValuesNotFinite)
{
    const core::Model model = boxes(core::IntegratorKind::Euler, false);
    run::Simulation simulation(model);
    core::Simulator& simulator = simulation.simulator();
    const core::Vec3 force(1.0, 0.0, 0.0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(simulator.applyWrench(0, force, core::Vec3::Zero()), std::invalid_argument); // the floor
    EXPECT_THROW(simulator.applyWrench(3, force, core::Vec3::Zero()), std::out_of_range);
    EXPECT_THROW(simulator.applyWrench(-1, force, core::Vec3::Zero()), std::out_of_range);
    EXPECT_THROW(simulator.applyForceAtPoint(simulation.state(), 7, force, core::Vec3::Zero()),
                 std::out_of_range);
    EXPECT_THROW(simulator.applyWrench(cA, core::Vec3(nan, 0.0, 0.0), core::Vec3::Zero()),
                 std::invalid_argument);
    EXPECT_THROW(simulator.applyForceAtPoint(simulation.state(), cA, force, core::Vec3(0.0, nan, 0.0)),
                 std::invalid_argument);
    simulation.step();
    EXPECT_EQ(simulation.state().bodies[cA].velocity_W, core::Vec3::Zero()) << "refused wrenches do nothing";
}

// The model's gravity changed between steps (nothing caches it): the next step's free fall follows.
TEST(ExternalForces, GravityChangedBetweenStepsIsTheNextSteps)
{
    for (const core::IntegratorKind integrator : cAllIntegrators)
    {
        core::Model model = boxes(integrator, false);
        model.simulation.gravity = core::Vec3(0.0, 0.0, -9.81);
        run::Simulation simulation(model);
        const double dt = model.simulation.dt;
        simulation.step(10);
        const core::Vec3 before = simulation.state().bodies[cA].velocity_W;
        EXPECT_LT((before - 10.0 * dt * model.simulation.gravity).norm(), 1e-14);
        const core::Vec3 moon(0.5, 0.0, -1.62); // m/s^2
        model.simulation.gravity = moon;
        simulation.step();
        EXPECT_LT((simulation.state().bodies[cA].velocity_W - before - moon * dt).norm(), 1e-15)
            << core::integratorName(integrator);
    }
}

} // namespace
