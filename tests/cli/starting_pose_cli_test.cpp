// tests/cli/starting_pose_cli_test.cpp: `frontier run ROBOT.urdf --joint-position NAME=POSITION`
// starts the robot there and records it for `check`; `--strict` refuses a start inside the floor.
#include "app_test_util.h"

#include <gtest/gtest.h>
#include <string>

namespace
{
using frontier::app::test::readText;
using frontier::app::test::Result;
using frontier::app::test::sourcePath;
using frontier::app::test::TestDir;

const char* const cQuadruped = "scenes/robots/quadruped_description/urdf/quadruped.urdf";

// The joints CSV's first row of a joint: "0,NAME,angle,POSITION,..."; the position (rad).
double startPosition(const std::string& joints, const std::string& name)
{
    const std::string row = "\n0," + name + ",angle,";
    const std::size_t at = joints.find(row);
    return at == std::string::npos ? 1e9 : std::stod(joints.substr(at + row.size()));
}

TEST(StartingPoseCli, JointPositionFlagStartsThereAndCheckReadsItBack)
{
    TestDir dir;
    const std::string trajectory = dir.out("t.csv");
    const std::string joints = dir.out("j.csv");
    const Result r = dir.run(std::string("run ") + cQuadruped +
                             " --hold --duration 0.05 --joint-position FL_calf_joint=-1.2 "
                             "--joint-position FL_thigh_joint=0.6 --trajectory " +
                             trajectory + " --joints " + joints);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_DOUBLE_EQ(startPosition(readText(joints), "FL_calf_joint"), -1.2);
    EXPECT_DOUBLE_EQ(startPosition(readText(joints), "FL_thigh_joint"), 0.6);
    EXPECT_DOUBLE_EQ(startPosition(readText(joints), "FR_calf_joint"), 0.0);
    // check loads the robot from the header's joint_positions: the same run, error 0.
    const Result c = dir.run(std::string("check ") + cQuadruped + " --reference " + trajectory);
    EXPECT_EQ(c.exitCode, 0) << c.out << c.err;
    EXPECT_NE(c.out.find("largest position error 0 m"), std::string::npos) << c.out;
}

TEST(StartingPoseCli, BadJointPositionsExitTwoNamingTheFlag)
{
    TestDir dir;
    const Result unknown = dir.run(std::string("run ") + cQuadruped + " --joint-position FL_calf=-1");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("--joint-position FL_calf: the URDF has no joint 'FL_calf'; did you mean "
                               "'FL_calf_joint'?"),
              std::string::npos)
        << unknown.err;
    const Result outside = dir.run(std::string("run ") + cQuadruped + " --joint-position FL_calf_joint=1");
    EXPECT_EQ(outside.exitCode, 2);
    EXPECT_NE(outside.err.find("expected a position in [-2.6, 0] rad"), std::string::npos) << outside.err;
    const Result malformed = dir.run(std::string("run ") + cQuadruped + " --joint-position FL_calf_joint");
    EXPECT_EQ(malformed.exitCode, 2) << malformed.err;
    const Result scene = dir.run("run scenes/robots/quadruped_stand.yaml --joint-position FL_calf_joint=-1");
    EXPECT_EQ(scene.exitCode, 2);
    EXPECT_NE(scene.err.find("'joint_positions'"), std::string::npos) << scene.err;
}

// A robot put 0.245 m into the floor: a warning naming the bodies and the depth; --strict: exit 2.
TEST(StartingPoseCli, StrictRefusesAStartInsideTheFloor)
{
    TestDir dir;
    std::string text = readText(sourcePath("scenes/robots/quadruped_stand.yaml"));
    const std::string position = "position: [0, 0, 0.445]";
    ASSERT_NE(text.find(position), std::string::npos);
    text.replace(text.find(position), position.size(), "position: [0, 0, 0.2]");
    const std::string urdf = "urdf: quadruped_description";
    ASSERT_NE(text.find(urdf), std::string::npos);
    text.replace(text.find(urdf), urdf.size(), "urdf: " + sourcePath("scenes/robots/quadruped_description"));
    const std::string scene = dir.write("sunk.yaml", text);
    const Result warned = dir.run("run " + scene + " --duration 0.01");
    EXPECT_EQ(warned.exitCode, 0) << warned.err;
    EXPECT_NE(warned.err.find("start inside each other by 0.24"), std::string::npos) << warned.err;
    const Result strict = dir.run("run " + scene + " --duration 0.01 --strict");
    EXPECT_EQ(strict.exitCode, 2) << strict.err;
    EXPECT_NE(strict.err.find("--strict: bodies '"), std::string::npos) << strict.err;
}

} // namespace
