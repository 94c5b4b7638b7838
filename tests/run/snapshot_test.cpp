// tests/run/snapshot_test.cpp: run::Simulation::snapshot() and restore() rewind a rollout bit for
// bit. Scenes of contact piles, stacks, a doll and servo-driven robots (one with servos at their
// effort limits), each integrator (and pgs), stepped until contacts, warm starts and kept parts of
// the Delassus matrix are live; the steps after a snapshot, taken again after restoring it into
// the same Simulation and into a fresh one, give every double of every State equal bit for bit.
// The State alone does not: the simulator's memory is needed, which these tests show can fail.
#include "core/time_function.h"
#include "run/scene_loading.h"
#include "run/simulation.h"

#include <cstring>
#include <gtest/gtest.h>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using namespace frontier;

constexpr long cSnapshotAfter = 200; // steps before the snapshot: contacts and warm starts live
constexpr long cRolloutSteps = 100;  // steps recorded after it

std::string bundledScene(const std::string& file)
{
    return std::string(FRONTIER_SOURCE_DIR) + "/scenes/" + file;
}

// The arm of arm6_keyframes.yaml with two servos following sines beyond what their effort limits
// (N m) allow: they leave their joints' blocks for bounded rows and come back (core/actuation.h).
run::LoadedScene armAtItsLimits()
{
    const std::string yaml =
        "simulation: {dt: 0.001, duration: 1.0, gravity: [0, 0, -9.81], solver: linear}\n"
        "bodies:\n"
        "  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1], offset: 0}}\n"
        "models:\n"
        "  - {urdf: " +
        bundledScene("robots/arm6_description/urdf/arm6.urdf") +
        ", hold: true}\n"
        "actuators:\n"
        "  - {joint: shoulder_lift_joint, type: position, kp: 2000, kd: 100,"
        " target: {sine: {amplitude: 0.8, frequency: 2}}, effort_limit: 150}\n"
        "  - {joint: elbow_joint, type: position, kp: 2000, kd: 100,"
        " target: {sine: {amplitude: 1.0, frequency: 3}}, effort_limit: 60}\n";
    return run::loadSceneText(yaml, bundledScene("robots/arm_at_its_limits.yaml"));
}

template <class T> bool sameBits(const std::vector<T>& a, const std::vector<T>& b)
{
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool sameBits(const double* a, const double* b, std::size_t n)
{
    return std::memcmp(a, b, n * sizeof(double)) == 0;
}

// The first field in which two states differ bit for bit, "" when none does.
std::string bitDifference(const core::State& a, const core::State& b)
{
    static_assert(sizeof(Eigen::Matrix<double, 6, 1>) == 6 * sizeof(double));
    if (!sameBits(&a.time, &b.time, 1) || a.step != b.step)
    {
        return "time or step";
    }
    if (a.bodies.size() != b.bodies.size())
    {
        return "body count";
    }
    for (std::size_t i = 0; i < a.bodies.size(); ++i)
    {
        const core::BodyState& x = a.bodies[i];
        const core::BodyState& y = b.bodies[i];
        if (!sameBits(x.position_W.data(), y.position_W.data(), 3) ||
            !sameBits(x.orientation_WB.coeffs().data(), y.orientation_WB.coeffs().data(), 4) ||
            !sameBits(x.velocity_W.data(), y.velocity_W.data(), 3) ||
            !sameBits(x.angularVelocity_W.data(), y.angularVelocity_W.data(), 3))
        {
            return "body " + std::to_string(i);
        }
    }
    if (!sameBits(a.jointAngles, b.jointAngles))
    {
        return "jointAngles";
    }
    if (!sameBits(a.jointDrift, b.jointDrift) || !sameBits(a.jointDriftLast, b.jointDriftLast))
    {
        return "jointDrift";
    }
    return sameBits(a.jointLoads, b.jointLoads) ? "" : "jointLoads";
}

// The first step of two rollouts whose states differ, and where: "" when all agree bit for bit.
std::string firstDifference(const std::vector<core::State>& a, const std::vector<core::State>& b)
{
    if (a.size() != b.size())
    {
        return "rollouts of different lengths";
    }
    for (std::size_t k = 0; k < a.size(); ++k)
    {
        const std::string field = bitDifference(a[k], b[k]);
        if (!field.empty())
        {
            return "step " + std::to_string(k + 1) + " after the snapshot: " + field;
        }
    }
    return "";
}

// What a rollout met: steps with contact rows, with impulses carried from the last step, with
// parts of G kept from a recent one, with an actuator at its effort limit.
struct Liveliness
{
    int contactSteps = 0;
    int carriedOrReused = 0;
    int atLimit = 0;      // actuator-steps at the effort limit
    int limitChanges = 0; // actuator-steps at it after one not, or not after one at it
};

std::vector<core::State> rollout(run::Simulation& simulation, long steps, Liveliness* seen = nullptr)
{
    std::vector<core::State> states;
    std::vector<bool> wasAtLimit(simulation.model().actuators.size(), false);
    for (long k = 0; k < steps; ++k)
    {
        simulation.step();
        states.push_back(simulation.state());
        if (seen != nullptr)
        {
            const core::StepStats& stats = simulation.simulator().lastStep();
            seen->contactSteps += stats.extraRows > 0 ? 1 : 0;
            seen->carriedOrReused += stats.contactRoute == core::ContactRoute::Carried ||
                                             stats.contactRoute == core::ContactRoute::Reused
                                         ? 1
                                         : 0;
            const std::span<const core::ActuatorEffort> efforts = simulation.simulator().actuatorEfforts();
            for (std::size_t a = 0; a < efforts.size(); ++a)
            {
                seen->atLimit += efforts[a].atLimit ? 1 : 0;
                seen->limitChanges += k > 0 && efforts[a].atLimit != wasAtLimit[a] ? 1 : 0;
                wasAtLimit[a] = efforts[a].atLimit;
            }
        }
    }
    return states;
}

struct Case
{
    std::string name;
    core::IntegratorKind integrator;
    core::SolverKind solver = core::SolverKind::Linear;
};

std::vector<Case> integrators(const std::string& name)
{
    return {{name + " euler", core::IntegratorKind::Euler},
            {name + " rattle", core::IntegratorKind::Rattle},
            {name + " rattle4", core::IntegratorKind::Rattle4}};
}

// Steps cSnapshotAfter, snapshots, records cRolloutSteps (A); restores into the same Simulation
// (B) and into a fresh one of the same model (C): A, B and C agree bit for bit.
Liveliness expectRewinds(core::Model model, const Case& c)
{
    model.simulation.integrator = c.integrator;
    model.simulation.solver = c.solver;
    run::Simulation simulation(model);
    simulation.step(cSnapshotAfter);
    const run::Simulation::Snapshot snapshot = simulation.snapshot();
    Liveliness seen;
    const std::vector<core::State> a = rollout(simulation, cRolloutSteps, &seen);
    simulation.restore(snapshot);
    EXPECT_EQ(bitDifference(simulation.state(), snapshot.state), "") << c.name;
    const std::vector<core::State> b = rollout(simulation, cRolloutSteps);
    run::Simulation fresh(model);
    fresh.restore(snapshot);
    const std::vector<core::State> other = rollout(fresh, cRolloutSteps);
    EXPECT_EQ(firstDifference(a, b), "") << c.name << ": restored into the same simulation";
    EXPECT_EQ(firstDifference(a, other), "") << c.name << ": restored into a fresh simulation";
    return seen;
}

TEST(Snapshot, RewindsAContactPileBitForBit)
{
    const core::Model model = run::loadScene(bundledScene("pileup44.yaml")).model;
    std::vector<Case> cases = integrators("pileup44");
    cases.push_back({"pileup44 euler pgs", core::IntegratorKind::Euler, core::SolverKind::Pgs});
    for (const Case& c : cases)
    {
        const Liveliness seen = expectRewinds(model, c);
        EXPECT_EQ(seen.contactSteps, cRolloutSteps) << c.name;
        EXPECT_GT(seen.carriedOrReused, 0) << c.name << ": warm starts and kept parts in use";
    }
}

TEST(Snapshot, RewindsABoxStackAndAFallingDollBitForBit)
{
    for (const std::string scene : {"box_stack.yaml", "falling_doll.yaml"})
    {
        const core::Model model = run::loadScene(bundledScene(scene)).model;
        for (const Case& c : integrators(scene))
        {
            const Liveliness seen = expectRewinds(model, c);
            EXPECT_GT(seen.contactSteps, 0) << c.name;
        }
    }
}

TEST(Snapshot, RewindsServoDrivenRobotsBitForBit)
{
    for (const std::string scene : {"robots/quadruped_stand.yaml", "robots/arm6_keyframes.yaml"})
    {
        const core::Model model = run::loadScene(bundledScene(scene)).model;
        for (const Case& c : integrators(scene))
        {
            expectRewinds(model, c);
        }
    }
}

TEST(Snapshot, RewindsServosAtTheirEffortLimitsBitForBit)
{
    const core::Model model = armAtItsLimits().model;
    for (const Case& c : integrators("arm at its limits"))
    {
        const Liveliness seen = expectRewinds(model, c);
        // Both sides of the limit within the rollout: actuators leave their blocks and come back.
        EXPECT_GT(seen.atLimit, 0) << c.name;
        EXPECT_GT(seen.limitChanges, 0) << c.name;
    }
}

// The State alone does not rewind a rollout: without the simulator's memory (warm starts, kept
// parts of G, actuators out of their blocks) the steps differ, so the tests above can fail.
TEST(Snapshot, TheStateAloneDoesNotRewindARollout)
{
    const core::Model pile = run::loadScene(bundledScene("pileup44.yaml")).model;
    const core::Model arm = armAtItsLimits().model;
    for (const core::Model* model : {&pile, &arm})
    {
        run::Simulation simulation(*model);
        simulation.step(cSnapshotAfter);
        const core::State start = simulation.state();
        const std::vector<core::State> a = rollout(simulation, cRolloutSteps);
        run::Simulation fresh(*model);
        fresh.state() = start;
        EXPECT_NE(firstDifference(a, rollout(fresh, cRolloutSteps)), "") << model->name;
    }
}

TEST(Snapshot, RestoreUndoesATargetSetAfterTheSnapshot)
{
    const core::Model model = run::loadScene(bundledScene("robots/arm6_keyframes.yaml")).model;
    run::Simulation simulation(model);
    simulation.simulator().setActuatorTarget(1, 0.3); // rad: a target given before the snapshot
    simulation.step(cSnapshotAfter);
    const run::Simulation::Snapshot snapshot = simulation.snapshot();
    const std::vector<core::State> a = rollout(simulation, cRolloutSteps);
    simulation.restore(snapshot);
    simulation.simulator().setActuatorTarget(0, 1.0); // rad
    simulation.simulator().setActuatorTarget(1, core::sineFunction(0.5, 1.0, 0.0, 0.0));
    EXPECT_NE(firstDifference(a, rollout(simulation, cRolloutSteps)), "") << "the new targets move the arm";
    simulation.restore(snapshot);
    EXPECT_EQ(firstDifference(a, rollout(simulation, cRolloutSteps)), "");
}

// A wrench given before the snapshot acts again after restoring it; one given after is undone.
TEST(Snapshot, HoldsTheWrenchesWaitingForTheNextStep)
{
    const core::Model model = run::loadScene(bundledScene("box_stack.yaml")).model;
    run::Simulation simulation(model);
    simulation.step(cSnapshotAfter);
    simulation.simulator().applyWrench(3, core::Vec3(5.0, 0.0, 0.0), core::Vec3(0.0, 0.0, 0.5));
    const run::Simulation::Snapshot snapshot = simulation.snapshot();
    const std::vector<core::State> a = rollout(simulation, cRolloutSteps);
    simulation.restore(snapshot);
    EXPECT_EQ(firstDifference(a, rollout(simulation, cRolloutSteps)), "");
    simulation.restore(snapshot);
    simulation.simulator().applyWrench(2, core::Vec3(0.0, 5.0, 0.0), core::Vec3::Zero());
    simulation.restore(snapshot);
    EXPECT_EQ(firstDifference(a, rollout(simulation, cRolloutSteps)), "");
}

TEST(Snapshot, RefusesASnapshotOfAnotherModel)
{
    const core::Model stack = run::loadScene(bundledScene("box_stack.yaml")).model;
    const core::Model pile = run::loadScene(bundledScene("pileup44.yaml")).model;
    run::Simulation stackSimulation(stack);
    stackSimulation.step(10);
    run::Simulation pileSimulation(pile);
    pileSimulation.step(10);
    const core::State before = pileSimulation.state();
    EXPECT_THROW(pileSimulation.restore(stackSimulation.snapshot()), std::invalid_argument);
    run::Simulation::Snapshot mixed = pileSimulation.snapshot();
    mixed.memory = stackSimulation.snapshot().memory; // the state fits, the memory does not
    EXPECT_THROW(pileSimulation.restore(mixed), std::invalid_argument);
    EXPECT_THROW(pileSimulation.restore({pileSimulation.state(), core::StepMemory()}), std::invalid_argument);
    EXPECT_EQ(bitDifference(pileSimulation.state(), before), "") << "a refused snapshot changes nothing";
}

} // namespace
