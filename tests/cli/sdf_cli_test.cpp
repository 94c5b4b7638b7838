// tests/cli/sdf_cli_test.cpp: an SDF world through `frontier run`, `info`, `check` and `render`, and a
// bad SDF file's exit status and message.
#include "app_test_util.h"
#include "io/sdf_model.h"

#include <gtest/gtest.h>

namespace
{
using frontier::app::test::Result;
using frontier::app::test::TestDir;

const char* const cSdfWorld = R"(<?xml version="1.0"?>
<sdf version="1.7">
  <world name="yard">
    <model name="ground">
      <static>true</static>
      <link name="link">
        <collision name="c"><geometry><plane><normal>0 0 1</normal></plane></geometry></collision>
      </link>
    </model>
    <model name="pend">
      <pose>0 0 1.5 0 0 0</pose>
      <link name="rod">
        <pose>0.2 0 -0.5 0 0 0</pose>
        <inertial><mass>1</mass><inertia><ixx>0.02</ixx><iyy>0.02</iyy><izz>0.02</izz></inertia></inertial>
        <collision name="c"><geometry><capsule><radius>0.05</radius><length>0.8</length></capsule></geometry></collision>
      </link>
      <joint name="hinge" type="revolute">
        <parent>world</parent><child>rod</child>
        <pose>0 0 0.5 0 0 0</pose>
        <axis><xyz>0 1 0</xyz></axis>
      </joint>
    </model>
  </world>
</sdf>
)";

TEST(SdfCli, RunInfoCheckAndRenderTakeAnSdfWorld)
{
    if (!frontier::io::detail::sdfSupported())
    {
        GTEST_SKIP() << "built without libsdformat";
    }
    const TestDir dir;
    const std::string world = dir.write("yard.world", cSdfWorld);
    const Result run = dir.run("run " + world + " --duration 0.2 --quiet --trajectory " + dir.out("t.csv"));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const Result info = dir.run("info " + world);
    ASSERT_EQ(info.exitCode, 0) << info.err;
    EXPECT_NE(info.out.find("pend::rod"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("pend::hinge  revolute"), std::string::npos) << info.out;
    const Result check = dir.run("check " + world + " --reference " + dir.out("t.csv"));
    EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
    const Result render = dir.run("render " + dir.out("t.csv") +
                                  " --fps 10 --width 64 --height 48 --frames " + dir.out("frames"));
    ASSERT_EQ(render.exitCode, 0) << render.err;
    EXPECT_TRUE(std::filesystem::exists(dir.out("frames") + "/frame_00002.png"));
}

TEST(SdfCli, AnUnsupportedJointExitsTwoNamingFileAndLine)
{
    if (!frontier::io::detail::sdfSupported())
    {
        GTEST_SKIP() << "built without libsdformat";
    }
    const TestDir dir;
    const std::string file = dir.write("screw.sdf", R"(<?xml version="1.0"?>
<sdf version="1.7">
  <model name="m">
    <link name="a"><inertial><mass>1</mass></inertial></link>
    <link name="b"><inertial><mass>1</mass></inertial></link>
    <joint name="s" type="screw"><parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz></axis></joint>
  </model>
</sdf>
)");
    const Result r = dir.run("run " + file + " --duration 0.1 --quiet --trajectory " + dir.out("t.csv"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("screw.sdf:6: error: joint 's' has type screw"), std::string::npos) << r.err;
    EXPECT_TRUE(dir.outputs().empty()); // nothing that looks complete is left behind
}

} // namespace
