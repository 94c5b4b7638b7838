// tests/stability/stability_criteria_test.cpp: the suite's scenes with criteria of their own
// (`stability:` in scenes/stability/stiff_servo.yaml, robot_in_floor.yaml, limit_beyond_pi.yaml),
// each checked against the simulator stepped directly (independently of the suite's watch), each
// criterion shown to fail when tightened below what the run does, and the largest-dt search
// checked against single runs at its step and at twice its step.
#include "core/joints/coordinates.h"
#include "core/simulator.h"
#include "core/state.h"
#include "core/time_function.h"
#include "io/scene.h"
#include "run/run_loop.h"
#include "run/scene_loading.h"
#include "study/stability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>
#include <string>

namespace frontier::study::test
{
using run::parseMethod;
namespace
{

struct Scene
{
    core::Model model;
    io::SceneStabilityCriteria criteria;
};

// As `frontier stability` loads it (the links of a robot that overlap at the start never collide).
Scene load(const std::string& name)
{
    run::LoadedScene loaded =
        run::loadScene(std::string(FRONTIER_SOURCE_DIR) + "/scenes/stability/" + name + ".yaml", {});
    EXPECT_TRUE(loaded.report.stability.has_value()) << name << " has no 'stability:' criteria";
    Scene scene;
    scene.model = std::move(loaded.model);
    scene.criteria = loaded.report.stability.value_or(io::SceneStabilityCriteria{});
    return scene;
}

StabilityCell run(const Scene& scene, const std::string& name, std::optional<double> duration = std::nullopt,
                  const std::string& method = "linear/euler")
{
    StabilityLimits limits;
    limits.duration = duration;
    const StabilityCell cell =
        runStabilityCell(scene.model, name, *run::parseMethod(method), limits, scene.criteria);
    std::printf(
        "%s %s: %s; %ld of %ld steps; energy %+.4g J (max rise); speed %.3g m/s ('%s'); angles %s .. %s "
        "rad; tracking %s rad\n",
        name.c_str(), method.c_str(), cell.survived() ? "survived" : cell.note.c_str(), cell.stepsRun,
        cell.steps, cell.energyMaxJ - cell.energyInitialJ, cell.maxSpeedMps, cell.fastestBody.c_str(),
        cell.angleLowRad ? std::to_string(*cell.angleLowRad).c_str() : "-",
        cell.angleHighRad ? std::to_string(*cell.angleHighRad).c_str() : "-",
        cell.maxTrackingErrorRad ? std::to_string(*cell.maxTrackingErrorRad).c_str() : "-");
    return cell;
}

int jointIndex(const core::Model& model, const std::string& name)
{
    for (std::size_t j = 0; j < model.joints.size(); ++j)
    {
        if (model.joints[j].name == name)
        {
            return static_cast<int>(j);
        }
    }
    ADD_FAILURE() << "no joint " << name;
    return 0;
}

// The stiff servos: omega dt = 10 and 1000 (the scene's gains, recomputed here from a bar's
// inertia). Stepped directly for 3 s, each bar follows its sine target to 1e-3 rad (a continuous
// servo's error is about (I A (2 pi f)^2 + m g L/2) / kp = 5e-7 rad at omega dt = 10; the steps add
// a lag) and the energy stays within the motion's: per bar, potential m g (L/2) sin(1) = 1.65 J,
// kinetic at most I pi^2 / 2 = 0.26 J.
TEST(StabilityCriteria, StiffServoFollowsItsTarget)
{
    const Scene scene = load("stiff_servo");
    const core::Model& model = scene.model;
    ASSERT_EQ(model.actuators.size(), 2u);
    const double inertia = 1.0 * (0.4 * 0.4 + 0.04 * 0.04) / 12.0 + 1.0 * 0.2 * 0.2; // kg m^2 about the hinge
    EXPECT_NEAR(std::sqrt(model.actuators[0].kp / inertia) * model.simulation.dt, 10.0, 1e-4);
    EXPECT_NEAR(std::sqrt(model.actuators[1].kp / inertia) * model.simulation.dt, 1000.0, 1e-2);

    core::Simulator simulator(model);
    core::State state = core::initialState(model);
    const double e0 = core::totalEnergy(model, state);
    double worst = 0.0;
    double rise = 0.0;
    for (long k = 0; k < 3000; ++k)
    {
        simulator.step(state);
        for (const core::Actuator& servo : model.actuators)
        {
            const double angle = core::jointCoordinate(model, state, servo.joint);
            worst = std::max(worst, std::abs(angle - core::valueAt(servo.target, state.time)));
        }
        rise = std::max(rise, core::totalEnergy(model, state) - e0);
    }
    std::printf("stiff servo stepped: tracking error %.3g rad, energy rise %.3g J\n", worst, rise);
    EXPECT_LT(worst, 1e-3);
    EXPECT_LT(rise, 2.0 * (1.65 + 0.26) + 0.1);

    // The suite's cell agrees (its own count of turns), and holds the scene's bounds.
    const StabilityCell cell = run(scene, "stiff_servo");
    EXPECT_TRUE(cell.survived()) << cell.note;
    ASSERT_TRUE(cell.maxTrackingErrorRad.has_value());
    EXPECT_NEAR(*cell.maxTrackingErrorRad, worst, 1e-9);

    // The bound fails a run that does not meet it.
    Scene tight = scene;
    tight.criteria.joints.at(0).maxTrackingError = 1e-9;
    const StabilityCell failed = run(tight, "stiff_servo", 0.5);
    EXPECT_FALSE(failed.survived());
    EXPECT_NE(failed.note.find("joint 'bar_hinge'"), std::string::npos) << failed.note;
    EXPECT_NE(failed.note.find("off its target"), std::string::npos) << failed.note;
}

// The KR5 started 3 cm inside the floor, 1 s: pushed out (its base ends 2.5 to 5 cm higher than it
// started (measured 3.9 cm: the held arm settles a little higher than it lay), measured on the states stepped
// here), nothing faster than 0.5 m/s, energy up by less than 8 J (lifting its 24.85 kg out of 3 cm is 7.3 J).
TEST(StabilityCriteria, RobotStartedInTheFloorIsPushedOut)
{
    const Scene scene = load("robot_in_floor");
    const core::Model& model = scene.model;
    const int base = 1; // the first body after the floor: the root link
    ASSERT_FALSE(model.bodies[base].isStatic);
    // Stepped by the run loop of `frontier run` (with its contact detector), every state seen here.
    double z0 = 0.0;
    double zEnd = 0.0;
    double fastest = 0.0;
    run::RunSettings settings;
    settings.steps = 1000;
    const run::RunSummary summary =
        run::runSimulation(model, settings,
                           [&](const core::State& state, const core::Simulator* lastStep)
                           {
                               (lastStep == nullptr ? z0 : zEnd) = state.bodies[base].position_W.z();
                               for (std::size_t i = 0; i < model.bodies.size(); ++i)
                               {
                                   fastest = std::max(fastest, state.bodies[i].velocity_W.norm());
                               }
                           });
    ASSERT_TRUE(summary.completed) << summary.failure;
    const double lift = zEnd - z0;
    std::printf("robot in floor: base lifted %.4g m, fastest %.3g m/s\n", lift, fastest);
    EXPECT_GT(lift, 0.025);
    EXPECT_LT(lift, 0.05);
    EXPECT_LT(fastest, 0.5);

    const StabilityCell cell = run(scene, "robot_in_floor", 1.0);
    EXPECT_TRUE(cell.survived()) << cell.note;
    EXPECT_NEAR(cell.maxSpeedMps, fastest, 1e-9);
    EXPECT_LT(cell.energyMaxJ - cell.energyInitialJ, 8.0);

    Scene tight = scene;
    tight.criteria.maxSpeed = 0.5 * fastest;
    const StabilityCell failed = run(tight, "robot_in_floor", 1.0);
    EXPECT_FALSE(failed.survived());
    EXPECT_NE(failed.note.find("too fast"), std::string::npos) << failed.note;
}

// Hinges limited to [-4, 4] rad, 3 s: the swung rod passes pi and stops at its upper limit, the
// driven one is pressed into its lower limit by its motor; stepped directly, the angles continued
// by the simulator stay within 0.05 rad of the limits and end there (the driven rod at -4 rad,
// held against 15 N m).
TEST(StabilityCriteria, LimitBeyondPiHoldsWithoutWrapping)
{
    const Scene scene = load("limit_beyond_pi");
    const core::Model& model = scene.model;
    const int swung = jointIndex(model, "swung_hinge");
    const int driven = jointIndex(model, "driven_hinge");
    core::Simulator simulator(model);
    core::State state = core::initialState(model);
    double high = 0.0;
    double low = 0.0;
    for (long k = 0; k < 3000; ++k)
    {
        simulator.step(state);
        high = std::max(high, core::jointCoordinate(model, state, swung));
        low = std::min(low, core::jointCoordinate(model, state, driven));
    }
    std::printf("limits: swung up to %.4g rad, driven down to %.4g rad, ends at %.4g rad\n", high, low,
                core::jointCoordinate(model, state, driven));
    EXPECT_GT(high, std::numbers::pi + 0.5);
    EXPECT_LT(high, 4.05);
    EXPECT_LT(low, -std::numbers::pi - 0.5);
    EXPECT_GT(low, -4.05);
    EXPECT_NEAR(core::jointCoordinate(model, state, driven), -4.0, 0.05);

    const StabilityCell cell = run(scene, "limit_beyond_pi");
    EXPECT_TRUE(cell.survived()) << cell.note;
    ASSERT_TRUE(cell.angleHighRad && cell.angleLowRad);
    EXPECT_NEAR(*cell.angleHighRad, high, 1e-9);
    EXPECT_NEAR(*cell.angleLowRad, low, 1e-9);

    Scene narrow = scene; // a range the joints leave
    narrow.criteria.joints.at(0).range = std::array<double, 2>{-3.0, 3.0};
    const StabilityCell outside = run(narrow, "limit_beyond_pi");
    EXPECT_FALSE(outside.survived());
    EXPECT_NE(outside.note.find("outside [-3, 3]"), std::string::npos) << outside.note;
    Scene far = scene; // a reach they do not get to
    far.criteria.joints.at(1).range.reset();
    far.criteria.joints.at(0).reach = 4.5;
    const StabilityCell short_ = run(far, "limit_beyond_pi");
    EXPECT_FALSE(short_.survived());
    EXPECT_NE(short_.note.find("reached only"), std::string::npos) << short_.note;
}

// The search on a scene that fails at 1/30 s (the swung rod, at 10 rad/s, overshoots its limit by
// up to a step's travel): the step it gives holds and twice that step fails (single runs of the
// same length), and it tried every halving above it.
TEST(StabilityCriteria, LargestDtIsTheFirstHalvingThatHolds)
{
    const Scene scene = load("limit_beyond_pi");
    const run::Method method = *run::parseMethod("linear/euler");
    StabilityLimits limits;
    LargestDtOptions options;
    options.duration = 1.0;
    const LargestDtCell found =
        largestHoldingDt(scene.model, "limit_beyond_pi", method, limits, scene.criteria, options);
    std::printf("largest dt: %s after %d runs (%s)\n", found.dt ? std::to_string(*found.dt).c_str() : "none",
                found.runs, found.note.c_str());
    ASSERT_TRUE(found.dt.has_value()) << found.note;
    EXPECT_GT(found.runs, 1); // it fails at 1/30 s
    EXPECT_DOUBLE_EQ(*found.dt, options.start / std::pow(2.0, found.runs - 1));
    EXPECT_DOUBLE_EQ(found.duration, 1.0);
    StabilityLimits at = limits;
    at.duration = 1.0;
    at.dt = *found.dt;
    EXPECT_TRUE(runStabilityCell(scene.model, "x", method, at, scene.criteria).survived());
    at.dt = 2.0 * *found.dt;
    EXPECT_FALSE(runStabilityCell(scene.model, "x", method, at, scene.criteria).survived());

    // Dense beyond the row limit is skipped, not searched.
    limits.maxDenseRows = 1;
    const LargestDtCell skipped = largestHoldingDt(
        scene.model, "limit_beyond_pi", *run::parseMethod("dense/euler"), limits, scene.criteria, options);
    EXPECT_EQ(skipped.outcome, StabilityOutcome::Skipped);
    EXPECT_EQ(skipped.runs, 0);
}

// Bad `stability:` maps are refused with the file, line and what was expected.
TEST(StabilityCriteria, BadCriteriaAreNamedWithTheirLine)
{
    const std::string head =
        "bodies:\n"
        "  - {name: rod, mass: 1, shape: {type: sphere, radius: 0.1}, position: [0, 0, -1]}\n"
        "joints:\n"
        "  - {name: hinge, type: revolute, parent: world, child: rod, anchor: [0, 0, 0], "
        "axis: [0, 1, 0]}\n"
        "  - {name: ball, type: ball, parent: rod, child: rod2, anchor: [0, 0, -1]}\n";
    const std::string rod2 =
        "  - {name: rod2, mass: 1, shape: {type: sphere, radius: 0.1}, position: [0, 0, -2]}\n";
    const std::string bodies =
        head.substr(0, head.find("joints:")) + rod2 + head.substr(head.find("joints:"));
    const struct
    {
        std::string criteria;
        std::string message;
    } cases[] = {
        {"stability: {joints: [{joint: hinje, range: [-1, 1]}]}", "unknown joint 'hinje'"},
        {"stability: {joints: [{joint: ball, range: [-1, 1]}]}",
         "a stability check watches the angle of a revolute"},
        {"stability: {joints: [{joint: hinge, max_tracking_error: 0.1}]}", "has no position actuator"},
        {"stability: {joints: [{joint: hinge, range: [1, -1]}]}", "expected lower <= upper"},
        {"stability: {joints: [{joint: hinge}]}", "checks nothing"},
        {"stability: {max_sped: 1}", "max_sped"},
        {"stability: {max_speed: -1}", "max_speed"},
    };
    for (const auto& c : cases)
    {
        try
        {
            io::loadSceneFromString(bodies + c.criteria + "\n", "bad.yaml");
            ADD_FAILURE() << "accepted: " << c.criteria;
        }
        catch (const io::InputError& e)
        {
            const std::string what = e.what();
            EXPECT_NE(what.find("bad.yaml:7:"), std::string::npos) << what;
            EXPECT_NE(what.find(c.message), std::string::npos) << what;
        }
    }
}

} // namespace
} // namespace frontier::study::test
