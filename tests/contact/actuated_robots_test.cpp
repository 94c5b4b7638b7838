// tests/contact/actuated_robots_test.cpp: the robots of scenes/robots/ on their actuators, with
// contacts as `frontier run` has them. The quadruped held by --hold stands 5 s (its base drops less
// than 2 cm); crouched by servos (quadruped_stand.yaml) it stands at the height its joint angles
// give and holds it; a push of 20 N s rolls it over (quadruped_push.yaml), half of it does not;
// the arm follows its keyframes (arm6_keyframes.yaml) within 0.03 rad. No actuator ever pushes
// beyond its effort limit.
#include "collision/contacts.h"
#include "contact_harness.h"
#include "core/joints/coordinates.h"

#include <cmath>
#include <gtest/gtest.h>

namespace frontier::test
{
namespace
{

// A scene as `frontier run` loads it: links overlapping at the start never collide.
core::Model loadRobotScene(const std::string& path, const io::UrdfOptions& options = {})
{
    core::Model model = io::loadScene(path, options);
    for (const auto& [a, b] : collision::startingOverlaps(model))
    {
        model.contact.ignore.push_back({a, b});
    }
    return model;
}

// Angle (rad) between the body's z axis and the world's.
double tilt(const core::BodyState& body)
{
    return std::acos(std::clamp((body.orientation_WB * core::Vec3::UnitZ()).z(), -1.0, 1.0));
}

void expectWithinEffortLimits(const SceneRun& run, long step)
{
    for (std::size_t a = 0; a < run.model.actuators.size(); ++a)
    {
        const double limit = run.model.actuators[a].effortLimit;
        ASSERT_LE(std::abs(run.simulator.actuatorEfforts()[a].effort), limit * (1.0 + 1e-12))
            << "actuator " << a << " on joint '"
            << run.model.joints[static_cast<std::size_t>(run.model.actuators[a].joint)].name << "', step "
            << step;
    }
}

TEST(ActuatedRobots, QuadrupedHeldByHoldStandsFiveSeconds)
{
    io::UrdfOptions options;
    options.hold = true;
    SceneRun run(loadRobotScene(scenePath("robots/quadruped_description/urdf/quadruped.urdf"), options));
    EXPECT_EQ(run.model.actuators.size(), 12u); // every joint held
    const double start = run.body("base").position_W.z();
    double lowest = start;
    for (long k = 0; k < run.stepsFor(5.0); ++k)
    {
        run.step();
        expectWithinEffortLimits(run, k);
        lowest = std::min(lowest, run.body("base").position_W.z());
    }
    RecordProperty("base_drop_m", std::to_string(start - lowest));
    EXPECT_LT(start - lowest, 0.02);
    EXPECT_LT(tilt(run.body("base")), 0.02);
}

TEST(ActuatedRobots, QuadrupedCrouchesAndStandsOnItsServos)
{
    SceneRun run(loadRobotScene(scenePath("robots/quadruped_stand.yaml")));
    double low = 1e9;
    double high = -1e9;
    for (long k = 0; k < run.stepsFor(5.0); ++k)
    {
        run.step();
        expectWithinEffortLimits(run, k);
        if (run.state.time >= 1.5) // crouched: thigh 0.5 rad, knee -1.0 rad from t = 1 s
        {
            const double z = run.body("base").position_W.z();
            low = std::min(low, z);
            high = std::max(high, z);
        }
    }
    // The base (hips at its height) stands on legs of thigh 0.22 m and calf 0.2 m at those angles,
    // plus the feet's radius of 0.025 m; the servos give way by what the weight asks of them.
    const double legs = 0.025 + 0.22 * std::cos(0.5) + 0.2 * std::cos(0.5 - 1.0);
    RecordProperty("crouch_height_m", std::to_string(high));
    EXPECT_NEAR(high, legs, 0.01);
    EXPECT_LT(high - low, 0.02);
    EXPECT_LT(tilt(run.body("base")), 0.02);
}

// Tilt of the base at the end of quadruped_push.yaml with its push scaled.
double tiltAfterPush(double scale)
{
    core::Model model = loadRobotScene(scenePath("robots/quadruped_push.yaml"));
    EXPECT_EQ(model.loads.size(), 1u);
    model.loads[0].force *= scale;
    SceneRun run(std::move(model));
    for (long k = 0; k < run.stepsFor(5.0); ++k)
    {
        run.step();
        expectWithinEffortLimits(run, k);
    }
    return tilt(run.body("base"));
}

TEST(ActuatedRobots, APushKnocksTheStandingQuadrupedOver)
{
    EXPECT_GT(tiltAfterPush(1.0), 2.0); // rad: on its back
    EXPECT_LT(tiltAfterPush(0.5), 0.05);
}

TEST(ActuatedRobots, ArmFollowsItsKeyframes)
{
    SceneRun run(loadRobotScene(scenePath("robots/arm6_keyframes.yaml")));
    double worst = 0.0;
    for (long k = 0; k < run.stepsFor(6.0); ++k)
    {
        run.step();
        expectWithinEffortLimits(run, k);
        for (const core::Actuator& actuator : run.model.actuators)
        {
            const core::Joint& joint = run.model.joints[static_cast<std::size_t>(actuator.joint)];
            const double angle =
                joint.initialPosition +
                core::jointCoordinate(run.model, run.state, actuator.joint, actuator.coordinate);
            worst = std::max(worst, std::abs(angle - core::valueAt(actuator.target, run.state.time)));
        }
    }
    RecordProperty("worst_tracking_error_rad", std::to_string(worst));
    EXPECT_LT(worst, 0.03);
    EXPECT_EQ(run.simulator.lastStep().contacts, 0);
}

} // namespace
} // namespace frontier::test
