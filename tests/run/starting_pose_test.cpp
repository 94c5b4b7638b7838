// tests/run/starting_pose_test.cpp: a robot starts where its scene puts it: joint positions in the
// URDF's convention, a free model on the floor, look-ups by name, and the warning for bodies that
// start inside each other.
#include "core/time_function.h"
#include "run/names.h"
#include "run/scene_loading.h"
#include "run/simulation.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <string>

namespace
{
using namespace frontier;

const std::string cQuadruped =
    std::string(FRONTIER_SOURCE_DIR) + "/scenes/robots/quadruped_description/urdf/quadruped.urdf";

// A scene file in the test's own folder (removed with it).
class StartingPose : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        mDir = std::filesystem::path(FRONTIER_BINARY_DIR) / "test-tmp" /
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
        std::filesystem::remove_all(mDir);
        std::filesystem::create_directories(mDir);
    }
    void TearDown() override { std::filesystem::remove_all(mDir); }

    std::string scene(const std::string& modelEntry, const std::string& extra = "")
    {
        const std::string path = (mDir / "scene.yaml").string();
        std::ofstream(path)
            << "simulation: {dt: 0.001, duration: 1}\n"
               "bodies:\n"
               "  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1], offset: 0}}\n"
            << extra << "models:\n  - {urdf: " << cQuadruped << ", " << modelEntry << "}\n";
        return path;
    }

    std::filesystem::path mDir;
};

// Lowest point of the moving bodies' collision shapes along z (m), from the shapes' support points.
double lowestMovingPoint(const core::Model& model)
{
    double lowest = std::numeric_limits<double>::infinity();
    for (const core::Body& body : model.bodies)
    {
        for (const core::Shape& shape : body.isStatic ? std::vector<core::Shape>{} : body.shapes)
        {
            lowest = std::min(lowest, -core::shapeSupportWorld(shape, body.position_W, body.orientation_WB,
                                                               -core::Vec3::UnitZ()));
        }
    }
    return lowest;
}

TEST_F(StartingPose, JointPositionsAreTheStartingPoseInTheUrdfsConvention)
{
    const run::LoadedScene loaded =
        run::loadScene(scene("joint_positions: {FL_thigh_joint: 0.5, FL_calf_joint: -1.0}, hold: true"));
    const core::Model& model = loaded.model;
    run::Simulation simulation(model);
    EXPECT_DOUBLE_EQ(run::jointPosition(model, simulation.state(), "FL_thigh_joint"), 0.5);
    EXPECT_DOUBLE_EQ(run::jointPosition(model, simulation.state(), "FL_calf_joint"), -1.0);
    EXPECT_DOUBLE_EQ(run::jointPosition(model, simulation.state(), "FR_calf_joint"), 0.0);
    // The knee is bent: the calf's frame is turned by 1.5 rad about the hip's pitch axis from the
    // other leg's, whose joints are at 0 (the thigh's 0.5 and the calf's -1.0 add up to -0.5 on a
    // common axis; the angle between the two calves' orientations is their difference: 0.5 rad).
    const core::Quat fl =
        model.bodies[static_cast<std::size_t>(run::bodyIndex(model, "FL_calf"))].orientation_WB;
    const core::Quat fr =
        model.bodies[static_cast<std::size_t>(run::bodyIndex(model, "FR_calf"))].orientation_WB;
    EXPECT_NEAR(fl.angularDistance(fr), 0.5, 1e-9);
    // Held by the hold servos where it started: 0.5 s later the joints are still there.
    simulation.step(500);
    EXPECT_NEAR(run::jointPosition(model, simulation.state(), "FL_calf_joint"), -1.0, 0.02);
    EXPECT_NEAR(run::jointPosition(model, simulation.state(), "FL_thigh_joint"), 0.5, 0.02);
    // The servos' targets are in the same convention: the calf's servo holds -1.0 rad.
    const int servo = run::actuatorIndex(model, "FL_calf_joint");
    EXPECT_DOUBLE_EQ(core::valueAt(model.actuators[static_cast<std::size_t>(servo)].target, 0.0), -1.0);
}

TEST_F(StartingPose, BadJointPositionsNameTheEntryAndTheNearestJoint)
{
    try
    {
        run::loadScene(scene("joint_positions: {FL_calf: -1.0}"));
        FAIL() << "an unknown joint was accepted";
    }
    catch (const io::InputError& e)
    {
        EXPECT_EQ(e.line(), 5) << e.what(); // the model's entry
        EXPECT_NE(std::string(e.what()).find("did you mean 'FL_calf_joint'"), std::string::npos) << e.what();
    }
    try
    {
        run::loadScene(scene("joint_positions: {FL_calf_joint: 1.0}"));
        FAIL() << "a position outside the limits was accepted";
    }
    catch (const io::InputError& e)
    {
        EXPECT_NE(std::string(e.what()).find("expected a position in [-2.6, 0] rad"), std::string::npos)
            << e.what();
    }
}

// Without `position` a free model rests its lowest collision point on z = 0 (or drop_height above);
// before, its root link frame went to the origin and the legs started 0.33 m inside the floor.
TEST_F(StartingPose, AFreeModelWithoutPositionRestsOnTheFloor)
{
    const run::LoadedScene onFloor = run::loadScene(scene("hold: true"));
    EXPECT_NEAR(lowestMovingPoint(onFloor.model), 0.0, 1e-12);
    EXPECT_FALSE(onFloor.startPenetration);
    const run::LoadedScene dropped = run::loadScene(scene("drop_height: 0.3"));
    EXPECT_NEAR(lowestMovingPoint(dropped.model), 0.3, 1e-12);
    // A position places the root link frame where it says.
    const run::LoadedScene placed = run::loadScene(scene("position: [0, 0, 0.445]"));
    const core::Body& base =
        placed.model.bodies[static_cast<std::size_t>(run::bodyIndex(placed.model, "base"))];
    EXPECT_NEAR(base.position_W.z(), 0.445, 0.05);
    EXPECT_THROW(run::loadScene(scene("position: [0, 0, 1], drop_height: 0.3")), io::InputError);
}

// A model put inside the floor is a warning that names the bodies and the depth.
TEST_F(StartingPose, AStartInsideTheFloorIsAWarningWithTheDepth)
{
    const run::LoadedScene loaded = run::loadScene(scene("position: [0, 0, 0.2]"));
    ASSERT_TRUE(loaded.startPenetration);
    const double depth = loaded.startPenetration->depth;
    EXPECT_NEAR(depth, 0.445 - 0.2, 0.01); // the straight legs reach 0.445 m below the root frame
    const std::string text = run::startPenetrationText(loaded);
    EXPECT_NE(text.find("'floor'"), std::string::npos) << text;
    EXPECT_TRUE(std::any_of(loaded.report.warnings.begin(), loaded.report.warnings.end(),
                            [&](const std::string& w) { return w.find(text) != std::string::npos; }));
    // A scene may allow a deeper start.
    EXPECT_FALSE(run::loadScene(scene("position: [0, 0, 0.2]", "contact: {start_penetration: 0.5}\n"))
                     .startPenetration);
}

TEST(Names, LookUpsThrowWithTheNearestName)
{
    const core::Model model = run::loadScene(cQuadruped).model;
    EXPECT_EQ(model.joints[static_cast<std::size_t>(run::jointIndex(model, "RR_hip_joint"))].name,
              "RR_hip_joint");
    EXPECT_EQ(model.bodies[static_cast<std::size_t>(run::bodyIndex(model, "RR_calf"))].name, "RR_calf");
    try
    {
        run::jointIndex(model, "RR_hip_jiont");
        FAIL();
    }
    catch (const run::NameError& e)
    {
        EXPECT_STREQ(e.what(), "no joint 'RR_hip_jiont' in the model; did you mean 'RR_hip_joint'?");
    }
    EXPECT_THROW(run::bodyIndex(model, "nose"), run::NameError);
    EXPECT_THROW(run::actuatorIndex(model, "RR_hip_joint"), run::NameError); // no --hold: no actuators
}

} // namespace
