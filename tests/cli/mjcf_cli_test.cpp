// tests/cli/mjcf_cli_test.cpp: an MJCF file used as a new user would: `frontier run model.xml
// --keyframe NAME`, `info`, `check` of its trajectory (the keyframe read back from the header) and
// `render`; bad files and misused flags exit 2 naming the file and line.
#include "app_test_util.h"

#include <filesystem>
#include <gtest/gtest.h>
#include <string>

namespace
{
using frontier::app::test::readText;
using frontier::app::test::Result;
using frontier::app::test::shellQuote;
using frontier::app::test::TestDir;

// A pendulum over a floor, with two keyframes: hanging and raised 1 rad.
const char* const cCliPendulum = R"(<mujoco model="swing">
  <compiler angle="radian"/>
  <option timestep="0.001"/>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 1"/>
    <body name="bob" pos="0 0 1">
      <joint name="pivot" type="hinge" axis="0 1 0" range="-2 2"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.5" size="0.05"/>
    </body>
  </worldbody>
  <keyframe>
    <key name="hanging" qpos="0"/>
    <key name="raised" qpos="1"/>
  </keyframe>
</mujoco>
)";

// The joints CSV's first row of a joint: "0,NAME,angle,POSITION,..."; the position (rad).
double firstJointPosition(const std::string& joints, const std::string& name)
{
    const std::string row = "\n0," + name + ",angle,";
    const std::size_t at = joints.find(row);
    return at == std::string::npos ? 1e9 : std::stod(joints.substr(at + row.size()));
}

TEST(MjcfCli, RunInfoCheckAndRenderAModelInAKeyframe)
{
    const TestDir dir;
    const std::string model = dir.write("swing.xml", cCliPendulum);
    const std::string trajectory = dir.out("swing.csv");
    const Result run =
        dir.run("run " + shellQuote(model) + " --keyframe raised --duration 0.2 --trajectory " +
                shellQuote(trajectory) + " --joints " + shellQuote(dir.out("joints.csv")));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_DOUBLE_EQ(firstJointPosition(readText(dir.out("joints.csv")), "pivot"), 1.0);
    EXPECT_NE(readText(trajectory).find("keyframe=raised"), std::string::npos) << "header names the keyframe";

    const Result info = dir.run("info " + shellQuote(model) + " --keyframe raised");
    ASSERT_EQ(info.exitCode, 0) << info.err;
    EXPECT_NE(info.out.find("bob"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("pivot"), std::string::npos) << info.out;

    // check loads the model in the header's keyframe: the same run, error 0.
    const Result check = dir.run("check " + shellQuote(model) + " --reference " + shellQuote(trajectory));
    EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
    EXPECT_NE(check.out.find("largest position error 0 m"), std::string::npos) << check.out;

    const Result render = dir.run("render " + shellQuote(trajectory) + " --frames " +
                                  shellQuote(dir.out("frames")) + " --fps 10 --width 64 --height 48");
    ASSERT_EQ(render.exitCode, 0) << render.err;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir.out("frames/frame_00002.png"))) << render.err;
}

TEST(MjcfCli, BadFilesExitTwoNamingFileAndLine)
{
    const TestDir dir;
    const std::string malformed = dir.write(
        "malformed.xml", "<mujoco>\n  <worldbody>\n    <body name=\"a\">\n  </worldbody>\n</mujoco>\n");
    const Result m = dir.run("run " + shellQuote(malformed));
    EXPECT_EQ(m.exitCode, 2) << m.err;
    // The <body> opened on line 3 is closed by </worldbody>: the XML parser names its line.
    EXPECT_NE(m.err.find(malformed + ":3:"), std::string::npos) << m.err;
    EXPECT_NE(m.err.find("MISMATCHED_ELEMENT"), std::string::npos) << m.err;

    const std::string typo =
        dir.write("typo.xml", "<mujoco>\n  <worldbody>\n    <body name=\"a\">\n      "
                              "<freejoint/>\n      <geom type=\"sphere\" radius=\"1\"/>\n"
                              "    </body>\n  </worldbody>\n</mujoco>\n");
    const Result t = dir.run("info " + shellQuote(typo));
    EXPECT_EQ(t.exitCode, 2) << t.err;
    EXPECT_NE(t.err.find(typo + ":5:"), std::string::npos) << t.err;
    EXPECT_NE(t.err.find("radius"), std::string::npos) << t.err;
}

TEST(MjcfCli, MisusedFlagsExitTwoSayingWhy)
{
    const TestDir dir;
    const std::string model = dir.write("swing.xml", cCliPendulum);
    const Result unknown = dir.run("run " + shellQuote(model) + " --keyframe raise");
    EXPECT_EQ(unknown.exitCode, 2) << unknown.err;
    EXPECT_NE(unknown.err.find("no keyframe 'raise'"), std::string::npos) << unknown.err;
    EXPECT_NE(unknown.err.find("raised"), std::string::npos) << unknown.err;

    const std::string yaml =
        dir.write("scene.yaml", "bodies:\n  - {name: ball, shape: {type: sphere, radius: 0.1}}\n");
    const Result scene = dir.run("run " + shellQuote(yaml) + " --keyframe raised");
    EXPECT_EQ(scene.exitCode, 2) << scene.err;
    EXPECT_NE(scene.err.find("--keyframe"), std::string::npos) << scene.err;

    const Result fixed = dir.run("run " + shellQuote(model) + " --fixed-base");
    EXPECT_EQ(fixed.exitCode, 2) << fixed.err;
    EXPECT_NE(fixed.err.find("--fixed-base"), std::string::npos) << fixed.err;
}

} // namespace
