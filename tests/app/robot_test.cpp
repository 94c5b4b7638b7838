// tests/app/robot_test.cpp: the robot flags end to end: links overlapping at the start excluded
// from collision, --self-collision, --fixed-base and --hold recorded in the trajectory so that
// `check` and `render` load the robot as the run did, and --height pointing to --drop-height.
#include "app_test_util.h"
#include "info_test_util.h"

#include <Eigen/Core>
#include <algorithm>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

namespace frontier::app::test
{
namespace
{

// base, then `upper` on a hinge, then `tip` on a hinge; tip's collision box reaches back into the
// base (they overlap in this pose without being joined), upper and base are joined (never collide).
const char* const cFoldedArm = R"(<?xml version="1.0"?>
<robot name="folded">
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial>
    <collision><geometry><box size="0.3 0.3 0.1"/></geometry></collision>
  </link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 0.05"/>
    <axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <link name="upper">
    <inertial><origin xyz="0 0 0.1"/><mass value="1"/><inertia ixx="0.004" ixy="0" ixz="0" iyy="0.004" iyz="0" izz="0.001"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.04 0.04 0.2"/></geometry></collision>
  </link>
  <joint name="j2" type="revolute"><parent link="upper"/><child link="tip"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="tip">
    <inertial><origin xyz="0.08 0 -0.1"/><mass value="0.5"/><inertia ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.0005"/></inertial>
    <collision><origin xyz="0.08 0 -0.1"/><geometry><box size="0.04 0.04 0.22"/></geometry></collision>
  </link>
</robot>
)";

TEST(Robot, LinksOverlappingAtTheStartNeverCollide)
{
    const TestDir dir;
    const std::string urdf = dir.write("folded.urdf", cFoldedArm);
    const Result r = dir.run("info " + shellQuote(urdf) + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json info = nlohmann::json::parse(r.out);
    ASSERT_EQ(info["robots"].size(), 1u);
    const nlohmann::json& robot = info["robots"][0];
    EXPECT_EQ(robot["excluded_pairs"].size(), 1u) << robot.dump(2);
    EXPECT_TRUE(hasPair(robot["excluded_pairs"], "base", "tip")) << robot.dump(2);
    EXPECT_FALSE(hasPair(info["collision_pairs"], "base", "tip"));
    EXPECT_FALSE(hasPair(info["collision_pairs"], "base", "upper")); // joined
    EXPECT_TRUE(hasPair(info["collision_pairs"], "tip", "floor"));
    // A run from this pose does not push the overlapping links apart: no joint error, no energy gain.
    const Result run = dir.run("run " + shellQuote(urdf) + " --duration 0.5 --quiet --stats " +
                               shellQuote(dir.out("s.json")));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json stats = nlohmann::json::parse(readText(dir.out("s.json")));
    EXPECT_LE(stats["max_joint_error_m"].get<double>(), 1e-6);
    EXPECT_LE(stats["energy_max_j"].get<double>(), stats["energy_initial_j"].get<double>() + 1e-9);
}

TEST(Robot, SelfCollisionOffPutsTheLinksInOneGroup)
{
    const TestDir dir;
    const std::string urdf = dir.write("folded.urdf", cFoldedArm);
    const Result r = dir.run("info " + shellQuote(urdf) + " --json --self-collision off");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json info = nlohmann::json::parse(r.out);
    for (const nlohmann::json& pair : info["collision_pairs"])
    {
        EXPECT_TRUE(pair[0] == "floor" || pair[1] == "floor") << pair.dump();
    }
    EXPECT_TRUE(info["robots"][0]["excluded_pairs"].empty());
    EXPECT_EQ(dir.run("info " + shellQuote(urdf) + " --self-collision maybe").exitCode, 2);
}

TEST(Robot, FixedBaseIsRecordedSoCheckAndRenderLoadTheSameRobot)
{
    const TestDir dir;
    const std::string urdf = dir.write("folded.urdf", cFoldedArm);
    const std::string csv = dir.out("arm.csv");
    const Result run = dir.run("run " + shellQuote(urdf) +
                               " --fixed-base --duration 0.3 --quiet --trajectory " + shellQuote(csv));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const std::string text = readText(csv);
    EXPECT_NE(text.substr(0, text.find('\n')).find(" fixed_base=1"), std::string::npos)
        << text.substr(0, 300);
    EXPECT_EQ(text.find(",base,"), std::string::npos) << "the welded base is static: no rows";
    const Result check = dir.run("check " + shellQuote(urdf) + " --quiet --reference " + shellQuote(csv));
    EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
    // The same file run free-floating is another robot: check says so.
    const std::string free = dir.out("free.csv");
    ASSERT_EQ(dir.run("run " + shellQuote(urdf) + " --duration 0.3 --quiet --trajectory " + shellQuote(free))
                  .exitCode,
              0);
    EXPECT_NE(readText(free), text);
}

// Position (m) of `body` in the first and the last row of a trajectory CSV.
std::pair<Eigen::Vector3d, Eigen::Vector3d> firstAndLast(const std::string& csv, const std::string& body)
{
    std::istringstream in(csv);
    std::string line;
    std::vector<Eigen::Vector3d> rows;
    while (std::getline(in, line))
    {
        std::vector<std::string> fields;
        std::istringstream cells(line);
        for (std::string cell; std::getline(cells, cell, ',');)
        {
            fields.push_back(cell);
        }
        if (fields.size() > 4 && fields[1] == body)
        {
            rows.emplace_back(std::stod(fields[2]), std::stod(fields[3]), std::stod(fields[4]));
        }
    }
    return rows.empty() ? std::pair<Eigen::Vector3d, Eigen::Vector3d>{}
                        : std::pair{rows.front(), rows.back()};
}

TEST(Robot, HoldKeepsTheArmUpAndIsRecordedForCheck)
{
    const TestDir dir;
    const std::string urdf = dir.write("folded.urdf", cFoldedArm);
    const std::string held = dir.out("held.csv");
    const std::string limp = dir.out("limp.csv");
    const std::string flags = " --fixed-base --self-collision off --duration 1 --quiet --trajectory ";
    ASSERT_EQ(dir.run("run " + shellQuote(urdf) + " --hold" + flags + shellQuote(held)).exitCode, 0);
    ASSERT_EQ(dir.run("run " + shellQuote(urdf) + flags + shellQuote(limp)).exitCode, 0);
    const std::string text = readText(held);
    EXPECT_NE(text.substr(0, text.find('\n')).find(" hold=1"), std::string::npos) << text.substr(0, 300);
    const auto [start, end] = firstAndLast(text, "tip");
    const auto [limpStart, limpEnd] = firstAndLast(readText(limp), "tip");
    EXPECT_LT((end - start).norm(), 0.01);         // m: held (its effort limits of 1 N m suffice)
    EXPECT_GT((limpEnd - limpStart).norm(), 0.05); // m: without servos the arm folds down
    const Result check = dir.run("check " + shellQuote(urdf) + " --quiet --reference " + shellQuote(held));
    EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
    // `info` shows the servos --hold chose, with the URDF's effort limits.
    const Result info = dir.run("info " + shellQuote(urdf) + " --fixed-base --hold --json");
    ASSERT_EQ(info.exitCode, 0) << info.err;
    const nlohmann::json actuators = nlohmann::json::parse(info.out)["actuators"];
    ASSERT_EQ(actuators.size(), 2u) << actuators.dump(2);
    EXPECT_EQ(actuators[0]["joint"], "j1");
    EXPECT_EQ(actuators[0]["type"], "position");
    EXPECT_EQ(actuators[0]["effort_limit"].get<double>(), 1.0);
    EXPECT_GT(actuators[0]["kp"].get<double>(), 0.0);
}

TEST(Robot, HeightInMetresPointsToDropHeight)
{
    const TestDir dir;
    const std::string urdf = dir.write("folded.urdf", cFoldedArm);
    const Result r = dir.run("run " + shellQuote(urdf) + " --height 0.3");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("--drop-height"), std::string::npos) << r.err;
    const Result lifted = dir.run("info " + shellQuote(urdf) + " --json --drop-height 0.3");
    ASSERT_EQ(lifted.exitCode, 0) << lifted.err;
    const std::string placement = nlohmann::json::parse(lifted.out)["robots"][0]["placement"];
    EXPECT_NE(placement.find("0.3 m above the floor"), std::string::npos) << placement;
}

} // namespace
} // namespace frontier::app::test
