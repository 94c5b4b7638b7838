// tests/app/run_outputs_test.cpp: `frontier run --joints` and `--contacts` end to end: their
// comment and header lines, rows per recorded step; a resting box's contact forces against its
// weight; a pendulum's joint columns against the angle, spin and momentum computed from the
// trajectory CSV; a hanging chain's joints carrying the weight below them; batch names; outputs
// refused before the run (colliding paths, an input, links, devices, folders, empty paths, too many
// frames); the stats' limit and actuator keys, and each actuator's figures against the joints
// file; times that are whole steps of dt. (A failed run keeps them under .failed names:
// run_test.cpp.)
#include "app_test_util.h"
#include "csv_table.h"
#include "io/stats.h"
#include "io/trajectory.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <map>
#include <set>

namespace frontier::app::test
{
namespace
{

using frontier::test::CsvTable;
using frontier::test::readCsvTable;

// The key=value pairs of a "# frontier KIND:" comment line.
std::string metadataOf(const std::string& comment, const std::string& kind)
{
    const std::string prefix = "# frontier " + kind + ":";
    EXPECT_EQ(comment.rfind(prefix, 0), 0u) << comment;
    return comment.substr(std::min(prefix.size(), comment.size()));
}

// The doll (14 joints: 6 hinges, and 4 ball and 4 universal joints with no coordinate) and the
// box stack (contacts from the first step), recorded every 10 steps for 50 steps.
TEST(RunOutputs, FilesHaveTheTrajectoryCommentTheirHeaderAndARowPerCoordinateOrContact)
{
    const TestDir dir;
    const std::string traj = dir.out("doll.csv");
    const std::string joints = dir.out("doll.joints.csv");
    Result r = dir.run("run scenes/falling_doll.yaml --quiet --steps 50 --record-every 10 --trajectory " +
                       shellQuote(traj) + " --joints " + shellQuote(joints));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const CsvTable table = readCsvTable(joints);
    const CsvTable trajectory = readCsvTable(traj);
    EXPECT_EQ(metadataOf(table.comment, "joints"), metadataOf(trajectory.comment, "trajectory"));
    const std::vector<std::string> columns = {"time", "joint", "coordinate", "position", "velocity", "effort",
                                              "fx",   "fy",    "fz",         "tx",       "ty",       "tz"};
    EXPECT_EQ(table.columns, columns);
    // 6 recorded states (steps 0, 10, ..., 50) x (6 joints with one coordinate + 8 with none).
    ASSERT_EQ(table.rows.size(), 6u * 14u);
    std::set<std::string> names;
    int none = 0;
    for (std::size_t k = 0; k < table.rows.size(); ++k)
    {
        ASSERT_EQ(table.rows[k].size(), columns.size()) << "row " << k;
        EXPECT_NEAR(table.number(k, "time"), 0.01 * static_cast<double>(k / 14), 1e-12) << "row " << k;
        names.insert(table.text(k, "joint"));
        const bool coordinate = table.text(k, "coordinate") == "angle";
        none += coordinate ? 0 : 1;
        EXPECT_TRUE(coordinate || table.text(k, "coordinate") == "none") << table.text(k, "coordinate");
        EXPECT_EQ(std::isfinite(table.number(k, "position")), coordinate) << "row " << k;
        EXPECT_EQ(std::isfinite(table.number(k, "velocity")), coordinate) << "row " << k;
        EXPECT_EQ(std::isfinite(table.number(k, "fz")), k >= 14) << "row " << k << ": no step before t = 0";
        EXPECT_EQ(std::isfinite(table.number(k, "effort")), k >= 14) << "row " << k;
    }
    EXPECT_EQ(names.size(), 14u);
    EXPECT_EQ(none, 6 * 8);

    const std::string contacts = dir.out("stack.contacts.csv");
    const std::string stackTrajectory = dir.out("stack.csv");
    const std::string stats = dir.out("stack.json");
    r = dir.run("run scenes/box_stack.yaml --quiet --steps 50 --record-every 10 --contacts " +
                shellQuote(contacts) + " --stats " + shellQuote(stats) + " --trajectory " +
                shellQuote(stackTrajectory));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const CsvTable c = readCsvTable(contacts);
    EXPECT_EQ(metadataOf(c.comment, "contacts"),
              metadataOf(readCsvTable(stackTrajectory).comment, "trajectory"));
    EXPECT_EQ(c.columns, (std::vector<std::string>{"time", "body_a", "body_b", "px", "py", "pz", "nx", "ny",
                                                   "nz", "depth", "normal_force", "friction_force_x",
                                                   "friction_force_y", "friction_force_z"}));
    std::set<long> steps;
    for (std::size_t k = 0; k < c.rows.size(); ++k)
    {
        ASSERT_EQ(c.rows[k].size(), c.columns.size()) << "row " << k;
        steps.insert(std::lround(c.number(k, "time") / 0.001));
        EXPECT_GE(c.number(k, "normal_force"), 0.0) << "row " << k;
        EXPECT_NEAR(std::hypot(std::hypot(c.number(k, "nx"), c.number(k, "ny")), c.number(k, "nz")), 1.0,
                    1e-12);
    }
    EXPECT_EQ(steps, (std::set<long>{10, 20, 30, 40, 50})) << "no rows at t = 0 (no step yet)";
    // The stack's boxes touch the floor from the first step: at least its four corners each time.
    EXPECT_GE(c.rows.size(), 5u * 4u);
    EXPECT_LE(c.rows.size(), 5u * static_cast<std::size_t>(io::readStats(stats).maxContacts));
}

// scenes/pendulum.yaml: a 1 kg bob on a hinge about +y through (0, 0, 2), its body frame
// unturned at the start. The joints file's angle and its rate are the bob's rotation about y
// (2 atan2(q_y, q_w)) and its spin w_y from the trajectory, and the force the hinge passes is
// the bob's momentum change less its weight: m (v_n - v_{n-1}) / h - m g.
TEST(RunOutputs, PendulumJointColumnsAgreeWithTheTrajectory)
{
    const TestDir dir;
    const std::string traj = dir.out("t.csv");
    const std::string joints = dir.out("j.csv");
    const Result r = dir.run("run scenes/pendulum.yaml --quiet --duration 2 --trajectory " +
                             shellQuote(traj) + " --joints " + shellQuote(joints));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const io::Trajectory t = io::readTrajectory(traj);
    const CsvTable table = readCsvTable(joints);
    ASSERT_EQ(t.rows.size(), 2001u);
    ASSERT_EQ(table.rows.size(), t.rows.size());
    const double h = 0.001;
    const double m = 1.0;
    double swing = 0.0;
    for (std::size_t k = 0; k < t.rows.size(); ++k)
    {
        const core::BodyState s = t.rows[k].state();
        ASSERT_EQ(table.number(k, "time"), t.rows[k].time);
        ASSERT_EQ(table.text(k, "joint"), "pivot");
        ASSERT_EQ(table.text(k, "coordinate"), "angle");
        const double angle = 2.0 * std::atan2(s.orientation_WB.y(), s.orientation_WB.w());
        ASSERT_NEAR(table.number(k, "position"), angle, 1e-9) << "t = " << t.rows[k].time;
        ASSERT_NEAR(table.number(k, "velocity"), s.angularVelocity_W.y(), 1e-9) << "t = " << t.rows[k].time;
        swing = std::max(swing, std::abs(angle));
        if (k == 0)
        {
            continue;
        }
        const core::Vec3 force =
            m * (s.velocity_W - t.rows[k - 1].state().velocity_W) / h - m * core::Vec3(0.0, 0.0, -9.81);
        ASSERT_NEAR(table.number(k, "fx"), force.x(), 1e-9 * 9.81) << "t = " << t.rows[k].time;
        ASSERT_NEAR(table.number(k, "fy"), force.y(), 1e-9 * 9.81) << "t = " << t.rows[k].time;
        ASSERT_NEAR(table.number(k, "fz"), force.z(), 1e-9 * 9.81) << "t = " << t.rows[k].time;
        // A hinge with nothing along its axis passes no torque about it.
        ASSERT_NEAR(table.number(k, "ty"), 0.0, 1e-12) << "t = " << t.rows[k].time;
    }
    EXPECT_GT(swing, 1.0) << "released at 60 degrees, it swings through 1 rad";
}

// Three boxes hanging straight down from a nail to the world, by a ball joint and a hinge, at
// rest: each joint passes the weight below it straight up, to 1e-9, and no torque.
TEST(RunOutputs, HangingChainJointsCarryTheWeightBelow)
{
    const TestDir dir;
    const std::string scene = dir.write("chain.yaml", R"(
simulation: {dt: 0.001, gravity: [0, 0, -9.81]}
bodies:
  - {name: top, mass: 1.5, shape: {type: box, size: [0.1, 0.1, 0.3]}, position: [0, 0, 1.85]}
  - {name: middle, mass: 0.6, shape: {type: box, size: [0.1, 0.1, 0.3]}, position: [0, 0, 1.55]}
  - {name: bottom, mass: 2.4, shape: {type: box, size: [0.1, 0.1, 0.3]}, position: [0, 0, 1.25]}
joints:
  - {name: nail, type: nail, parent: world, child: top, anchor: [0, 0, 2.0]}
  - {name: ball, type: ball, parent: top, child: middle, anchor: [0, 0, 1.7]}
  - {name: hinge, type: revolute, parent: middle, child: bottom, anchor: [0, 0, 1.4], axis: [1, 0, 0]}
)");
    const std::string joints = dir.out("j.csv");
    const Result r =
        dir.run("run " + shellQuote(scene) + " --quiet --duration 0.2 --joints " + shellQuote(joints));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const CsvTable table = readCsvTable(joints);
    ASSERT_EQ(table.rows.size(), 201u * 3u);
    const double g = 9.81;
    const std::vector<std::pair<std::string, double>> below = {
        {"nail", (1.5 + 0.6 + 2.4) * g}, {"ball", (0.6 + 2.4) * g}, {"hinge", 2.4 * g}};
    for (std::size_t k = 3; k < table.rows.size(); ++k)
    {
        const auto& [name, weight] = below[k % 3];
        ASSERT_EQ(table.text(k, "joint"), name);
        EXPECT_EQ(table.text(k, "coordinate"), name == "hinge" ? "angle" : "none");
        ASSERT_NEAR(table.number(k, "fz"), weight, 1e-9 * weight) << name << ", row " << k;
        for (const char* column : {"fx", "fy", "tx", "ty", "tz"})
        {
            ASSERT_NEAR(table.number(k, column), 0.0, 1e-9 * weight)
                << name << ", " << column << ", row " << k;
        }
    }
}

// A batch writes DIR/<scene>.joints.csv and DIR/<scene>.contacts.csv, each file of its own scene.
TEST(RunOutputs, BatchWritesJointsAndContactsPerScene)
{
    const TestDir dir;
    const Result r = dir.run("run scenes/pendulum.yaml scenes/box_stack.yaml --quiet --steps 5 --joints " +
                             shellQuote(dir.out("joints")) + " --contacts " + shellQuote(dir.out("joints")) +
                             " --trajectory " + shellQuote(dir.out("joints")));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* scene : {"pendulum", "box_stack"})
    {
        for (const char* kind : {"joints", "contacts"})
        {
            const std::string path = dir.out(std::string("joints/") + scene + "." + kind + ".csv");
            ASSERT_TRUE(std::filesystem::exists(path)) << path;
            EXPECT_NE(readCsvTable(path).comment.find(std::string("scene=scenes/") + scene + ".yaml"),
                      std::string::npos)
                << path;
        }
        EXPECT_TRUE(std::filesystem::exists(dir.out(std::string("joints/") + scene + ".csv")));
    }
    EXPECT_EQ(readCsvTable(dir.out("joints/pendulum.joints.csv")).rows.size(), 6u);
    EXPECT_EQ(readCsvTable(dir.out("joints/box_stack.joints.csv")).rows.size(), 0u)
        << "the stack has no joints";
    EXPECT_TRUE(readCsvTable(dir.out("joints/pendulum.contacts.csv")).rows.empty());
    EXPECT_FALSE(readCsvTable(dir.out("joints/box_stack.contacts.csv")).rows.empty());
}

// Two outputs of one run at one path would overwrite each other: refused before the run, however
// the path is spelled, whichever two outputs they are (the frames folder too).
TEST(RunOutputs, TwoOutputsAtOnePathAreRefused)
{
    const TestDir dir;
    const std::string same = dir.out("same.csv");
    const std::pair<std::string, std::string> cases[] = {
        {" --trajectory " + shellQuote(same) + " --joints " + shellQuote(dir.out("./same.csv")),
         "--trajectory and --joints would write the same file"},
        {" --trajectory " + shellQuote(same) + " --stats " + shellQuote(same),
         "--trajectory and --stats would write the same file"},
        {" --stats " + shellQuote(same) + " --contacts " + shellQuote(dir.out("../out/same.csv")),
         "--stats and --contacts would write the same file"},
        {" --trajectory " + shellQuote(same) + " --frames " + shellQuote(same),
         "--trajectory and --frames would write the same file"},
    };
    for (const auto& [flags, message] : cases)
    {
        const Result r = dir.run("run scenes/pendulum.yaml --steps 5" + flags);
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
        EXPECT_TRUE(dir.outputs().empty());
    }
}

// An output that is one of the inputs would replace the scene being simulated: refused, and the
// scene is left as it was.
TEST(RunOutputs, AnOutputThatIsAnInputIsRefused)
{
    const TestDir dir;
    const std::string sceneText = readText(sourcePath("scenes/pendulum.yaml"));
    const std::string scene = dir.out("victim.yaml");
    std::ofstream(scene) << sceneText;
    for (const std::string flag : {"--trajectory", "--stats", "--joints"})
    {
        const Result r = dir.run("run " + shellQuote(scene) + " --steps 5 " + flag + " " +
                                 shellQuote(dir.out("../out/victim.yaml")));
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find(flag + std::string(" names the input")), std::string::npos) << r.err;
        EXPECT_EQ(readText(scene), sceneText);
    }
}

// Outputs are regular files or new paths. A symbolic link (renaming onto it would replace the
// link, not write through it), a device, a folder and an empty path are refused before the run:
// the run asked for here would take hours, so an exit 2 at once shows nothing ran first.
TEST(RunOutputs, LinksDevicesFoldersAndEmptyPathsAreRefusedBeforeTheRun)
{
    const TestDir dir;
    const std::string target = dir.write("target.csv", "keep me\n");
    const std::string link = dir.out("link.csv");
    std::filesystem::create_symlink(target, link);
    std::filesystem::create_directories(dir.out("folder"));
    const std::string longRun = "run scenes/pendulum.yaml --duration 1e6 --quiet";
    const std::pair<std::string, std::string> cases[] = {
        {" --trajectory " + shellQuote(link), "is a symbolic link"},
        {" --stats " + shellQuote(link), "is a symbolic link"},
        {" --trajectory /dev/null", "is a device"},
        {" --stats " + shellQuote(dir.out("folder")), "is a folder"},
        {" --frames " + shellQuote(target), "--frames names a folder"},
        {" --trajectory ''", "expected a path"},
        {" --stats ''", "expected a path"},
    };
    for (const auto& [flags, message] : cases)
    {
        const auto start = std::chrono::steady_clock::now();
        const Result r = dir.run(longRun + flags);
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
        EXPECT_EQ(r.exitCode, 2) << flags << "\n" << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << flags << "\n" << r.err;
    }
    // A stats file that cannot be created is reported before the run, not after it.
    const std::string blocker = dir.write("blocker", "a file, not a folder\n");
    const auto start = std::chrono::steady_clock::now();
    const Result r = dir.run(longRun + " --stats " + shellQuote(blocker + "/s.json"));
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(blocker), std::string::npos) << r.err;
    EXPECT_TRUE(std::filesystem::is_symlink(link));
    EXPECT_EQ(readText(target), "keep me\n");
    EXPECT_TRUE(std::filesystem::is_directory(dir.out("folder")));
}

// --fps up to its bound with frames: the sampler jumps over the frame times a step covers instead of
// counting them one by one (1e6 fps over 0.01 s used to take 1e4 ticks per step; 1e308, forever).
TEST(RunOutputs, HighFrameRateTakesAFramePerStep)
{
    const TestDir dir;
    const std::string frames = dir.out("frames");
    const Result r =
        dir.run("run scenes/pendulum.yaml --quiet --steps 3 --fps 1e6 --width 32 --height 32 --frames " +
                shellQuote(frames));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(frames + "/frame_00003.png"));
    EXPECT_FALSE(std::filesystem::exists(frames + "/frame_00004.png"));
    EXPECT_FALSE(std::filesystem::exists(frames + "/INCOMPLETE"));

    // More than a million frames is refused before the run.
    const Result many = dir.run("run scenes/pendulum.yaml --quiet --duration 2000 --fps 1000 --frames " +
                                shellQuote(dir.out("many")));
    EXPECT_EQ(many.exitCode, 2) << many.err;
    EXPECT_NE(many.err.find("frames; at most"), std::string::npos) << many.err;
    EXPECT_FALSE(std::filesystem::exists(dir.out("many")));
}

// geometric_stiffness_steps: the 1e6:1 heavy tip's links are stiffened once the chain is taut
// (from about step 30 of its 1 ms steps), so most of its first 0.3 s counts; the first steps
// (the tip falling freely, no tension yet) do not.
TEST(RunOutputs, StatsCountGeometricStiffnessSteps)
{
    const TestDir dir;
    const std::string tip = dir.out("tip.json");
    const Result r =
        dir.run("run scenes/stability/heavy_tip_1e6.yaml --quiet --duration 0.3 --stats " + shellQuote(tip));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const io::RunStats s = io::readStats(tip);
    EXPECT_GT(s.extra.at("geometric_stiffness_steps"), 150.0);
    EXPECT_LT(s.extra.at("geometric_stiffness_steps"), static_cast<double>(s.steps));
}

// limit_steps: the limits scene's rod and slider rest on their limits from about 1 s on, pressed
// by gravity, so every step after that pushes a limit, and the first steps (both start between
// their limits) do not; the pendulum has no limits. No actuators: both actuator keys are 0.
TEST(RunOutputs, StatsCountLimitStepsAndActuatorKeys)
{
    const TestDir dir;
    const std::string limits = dir.out("limits.json");
    const std::string pendulum = dir.out("pendulum.json");
    Result r = dir.run("run scenes/limits.yaml --quiet --duration 2 --stats " + shellQuote(limits));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = dir.run("run scenes/pendulum.yaml --quiet --duration 0.5 --stats " + shellQuote(pendulum));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const io::RunStats a = io::readStats(limits);
    const io::RunStats b = io::readStats(pendulum);
    EXPECT_GE(a.extra.at("limit_steps"), 1000.0);
    EXPECT_LT(a.extra.at("limit_steps"), static_cast<double>(a.steps));
    EXPECT_EQ(b.extra.at("limit_steps"), 0.0);
    EXPECT_EQ(a.extra.at("geometric_stiffness_steps"), 0.0); // no joint pulls hard enough
    for (const io::RunStats* s : {&a, &b})
    {
        EXPECT_EQ(s->extra.at("max_actuator_effort"), 0.0);
        EXPECT_EQ(s->extra.at("actuator_limit_steps"), 0.0);
    }
}

// second_order_steps (rattle4 only): the limits scene's limits push in most steps after about
// 1 s, and a step with a limit row is retaken as one rattle step; the pendulum, free of limits
// and contacts, never is. Euler runs have no such key.
TEST(RunOutputs, StatsCountRattle4StepsRetakenByRattle)
{
    const TestDir dir;
    const std::string limits = dir.out("limits.json");
    const std::string pendulum = dir.out("pendulum.json");
    const std::string euler = dir.out("euler.json");
    Result r = dir.run("run scenes/limits.yaml --quiet --duration 2 --integrator rattle4 --stats " +
                       shellQuote(limits));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = dir.run("run scenes/pendulum.yaml --quiet --duration 0.5 --integrator rattle4 --stats " +
                shellQuote(pendulum));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = dir.run("run scenes/pendulum.yaml --quiet --duration 0.1 --stats " + shellQuote(euler));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const io::RunStats a = io::readStats(limits);
    const io::RunStats b = io::readStats(pendulum);
    EXPECT_GE(a.extra.at("second_order_steps"), a.extra.at("limit_steps"));
    EXPECT_GE(a.extra.at("second_order_steps"), 1000.0);
    EXPECT_LE(a.extra.at("second_order_steps"), static_cast<double>(a.steps));
    EXPECT_EQ(b.extra.at("second_order_steps"), 0.0);
    EXPECT_EQ(io::readStats(euler).extra.count("second_order_steps"), 0u);
}

// A 2 kg bob on a 1 m rod, hinged about +y at (0, 0, 2) in zero gravity, driven by a commanded
// torque of 5 N m clipped to its limit of 3 N m: the joints file's effort is 3 N m at every step
// after the first, the hinge passes that torque about its axis (ty = 3, so the bob's spin rises
// by tau / I per second, I = m r^2 = 2 kg m^2 about the hinge, to 1e-6 relative: the rod's
// drift correction moves the bob by round-off each step), and the stats say the actuator
// sat at its limit in every step. A velocity motor asked for more than its limit allows against
// a clamped load does the same through its bounded row.
TEST(RunOutputs, ActuatorEffortsReachTheJointsFileAndTheStats)
{
    const TestDir dir;
    const std::string scene = dir.write("driven.yaml", R"(
simulation: {dt: 0.001, gravity: [0, 0, 0]}
bodies:
  - {name: bob, mass: 2.0, inertia: [1.0e-6, 1.0e-6, 1.0e-6], shape: {type: sphere, radius: 0.01}, position: [1, 0, 2]}
joints:
  - {name: pivot, type: revolute, parent: world, child: bob, anchor: [0, 0, 2], axis: [0, 1, 0]}
actuators:
  - {joint: pivot, type: effort, target: 5.0, effort_limit: 3.0}
)");
    const std::string joints = dir.out("j.csv");
    const std::string stats = dir.out("s.json");
    const Result r = dir.run("run " + shellQuote(scene) + " --quiet --duration 0.5 --joints " +
                             shellQuote(joints) + " --stats " + shellQuote(stats));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const CsvTable table = readCsvTable(joints);
    ASSERT_EQ(table.rows.size(), 501u);
    const double inertia = 2.0 * 1.0 + 1.0e-6; // kg m^2 about the hinge
    for (std::size_t k = 1; k < table.rows.size(); ++k)
    {
        const double t = table.number(k, "time");
        ASSERT_NEAR(table.number(k, "effort"), 3.0, 1e-12) << "t = " << t;
        ASSERT_NEAR(table.number(k, "ty"), 3.0, 1e-9) << "t = " << t;
        ASSERT_NEAR(std::abs(table.number(k, "velocity")), 3.0 / inertia * t, 1e-6 * t) << "t = " << t;
    }
    const io::RunStats s = io::readStats(stats);
    EXPECT_NEAR(s.extra.at("max_actuator_effort"), 3.0, 1e-12);
    EXPECT_EQ(s.extra.at("actuator_limit_steps"), static_cast<double>(s.steps));
}

// Three 1 kg bobs on 0.5 m rods, hinged about +y, under gravity: `shoulder` a position servo
// following a sine, `elbow` a servo stepping to 1 rad with at most 2 N m (less than the bob's
// weight needs), `wrist` a commanded 5 N m clipped to 3 N m. The stats' actuators entries agree
// with the joints file: the shoulder's tracking RMS and max are those of target(t) - position
// over the rows after t = 0, to round-off; every effort RMS and max those of the effort column;
// limit_steps the rows at the effort limit; the effort actuator has no tracking figures.
TEST(RunOutputs, ActuatorStatsAgreeWithTheJointsFile)
{
    const TestDir dir;
    const std::string scene = dir.write("servos.yaml", R"(
simulation: {dt: 0.001}
bodies:
  - {name: arm, mass: 1.0, shape: {type: sphere, radius: 0.05}, position: [0.5, 0, 2]}
  - {name: forearm, mass: 1.0, shape: {type: sphere, radius: 0.05}, position: [0.5, 2, 2]}
  - {name: hand, mass: 1.0, shape: {type: sphere, radius: 0.05}, position: [0.5, 4, 2]}
joints:
  - {name: shoulder, type: revolute, parent: world, child: arm, anchor: [0, 0, 2], axis: [0, 1, 0]}
  - {name: elbow, type: revolute, parent: world, child: forearm, anchor: [0, 2, 2], axis: [0, 1, 0]}
  - {name: wrist, type: revolute, parent: world, child: hand, anchor: [0, 4, 2], axis: [0, 1, 0]}
actuators:
  - {joint: shoulder, type: position, kp: 60, kd: 2, target: {sine: {amplitude: 0.5, frequency: 1.5, phase: 0.3, offset: -0.2}}}
  - {joint: elbow, type: position, kp: 200, kd: 5, target: 1.0, effort_limit: 2.0}
  - {joint: wrist, type: effort, target: 5.0, effort_limit: 3.0}
)");
    const std::string joints = dir.out("j.csv");
    const std::string stats = dir.out("s.json");
    const Result r = dir.run("run " + shellQuote(scene) + " --quiet --duration 1 --joints " +
                             shellQuote(joints) + " --stats " + shellQuote(stats));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const CsvTable table = readCsvTable(joints);
    ASSERT_EQ(table.rows.size(), 3u * 1001u);
    const io::RunStats s = io::readStats(stats);
    ASSERT_EQ(s.actuators.size(), 3u);
    const double limits[] = {std::numeric_limits<double>::infinity(), 2.0, 3.0}; // N m
    for (std::size_t a = 0; a < 3; ++a)
    {
        const io::ActuatorStats& stat = s.actuators[a];
        EXPECT_EQ(stat.joint, (std::vector<std::string>{"shoulder", "elbow", "wrist"})[a]);
        EXPECT_EQ(stat.coordinate, "rotation");
        EXPECT_EQ(stat.type, a < 2 ? "position" : "effort");
        double trackingSquares = 0.0, trackingMax = 0.0, effortSquares = 0.0, effortMax = 0.0;
        long atLimit = 0, steps = 0;
        for (std::size_t k = 3 + a; k < table.rows.size(); k += 3) // the rows after t = 0
        {
            ASSERT_EQ(table.text(k, "joint"), stat.joint);
            const double t = table.number(k, "time");
            const double target = a == 0 ? -0.2 + 0.5 * std::sin(2.0 * M_PI * 1.5 * t + 0.3) : 1.0; // rad
            const double tracking = target - table.number(k, "position");
            trackingSquares += tracking * tracking;
            trackingMax = std::max(trackingMax, std::abs(tracking));
            const double effort = table.number(k, "effort");
            effortSquares += effort * effort;
            effortMax = std::max(effortMax, std::abs(effort));
            atLimit += std::abs(effort) >= limits[a] * (1.0 - 1e-12) ? 1 : 0;
            ++steps;
        }
        ASSERT_EQ(steps, s.steps);
        const double n = static_cast<double>(steps);
        if (a < 2)
        {
            EXPECT_NEAR(stat.trackingRms, std::sqrt(trackingSquares / n), 1e-12 * trackingMax) << stat.joint;
            EXPECT_NEAR(stat.trackingMax, trackingMax, 1e-12 * trackingMax) << stat.joint;
            EXPECT_GT(trackingMax, 1e-3) << stat.joint << ": the servo lags its target";
        }
        else
        {
            EXPECT_TRUE(std::isnan(stat.trackingRms) && std::isnan(stat.trackingMax))
                << "an effort follows nothing";
        }
        EXPECT_NEAR(stat.effortRms, std::sqrt(effortSquares / n), 1e-12 * effortMax) << stat.joint;
        EXPECT_EQ(stat.effortMax, effortMax) << stat.joint;
        EXPECT_EQ(stat.limitSteps, atLimit) << stat.joint;
    }
    EXPECT_EQ(s.actuators[0].limitSteps, 0);
    EXPECT_GT(s.actuators[1].limitSteps, 100) << "the elbow cannot hold its bob up with 2 N m";
    EXPECT_EQ(s.actuators[2].limitSteps, s.steps);
    EXPECT_EQ(s.extra.at("max_actuator_effort"),
              std::max({s.actuators[0].effortMax, s.actuators[1].effortMax, 3.0}));
}

// A 2 kg box resting on the floor from the start. Its contacts' forces are what holds it (the
// floor is B, pushed down along the normal): at every step their vertical sum on the box is its
// weight plus its momentum change, m g + m (vz_k - vz_{k-1}) / dt from the trajectory, to
// round-off; and with the contacts solved to 1e-9 m/s (each step leaves the box's speed within
// that, so it changes by at most 2e-9 m/s a step) the normal forces add up to m g within
// m 2e-9 m/s / dt.
TEST(RunOutputs, RestingBoxContactForcesCarryItsWeight)
{
    const TestDir dir;
    const std::string scene = dir.write("resting.yaml", R"(
simulation: {dt: 0.001, gravity: [0, 0, -9.81]}
bodies:
  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1]}}
  - {name: box, mass: 2.0, shape: {type: box, size: [0.4, 0.3, 0.2]}, position: [0, 0, 0.1]}
)");
    const double m = 2.0, g = 9.81, dt = 0.001; // kg, m/s^2, s
    for (const std::string tolerance : {"3e-5", "1e-9"})
    {
        const std::string contacts = dir.out("c" + tolerance + ".csv");
        const std::string traj = dir.out("t" + tolerance + ".csv");
        const Result r =
            dir.run("run " + shellQuote(scene) + " --quiet --duration 0.3 --contact-tolerance " + tolerance +
                    " --contacts " + shellQuote(contacts) + " --trajectory " + shellQuote(traj));
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const CsvTable c = readCsvTable(contacts);
        const CsvTable t = readCsvTable(traj);
        ASSERT_EQ(t.rows.size(), 301u);
        std::map<long, double> normalByStep; // N, the sum of normal_force
        std::map<long, double> onBoxByStep;  // N, the vertical force on the box
        for (std::size_t k = 0; k < c.rows.size(); ++k)
        {
            ASSERT_EQ(c.text(k, "body_b"), "floor");
            ASSERT_NEAR(c.number(k, "nz"), -1.0, 1e-12);
            const long step = std::lround(c.number(k, "time") / dt);
            normalByStep[step] += c.number(k, "normal_force");
            onBoxByStep[step] -=
                c.number(k, "normal_force") * c.number(k, "nz") + c.number(k, "friction_force_z");
        }
        ASSERT_EQ(normalByStep.size(), 300u) << "the box touches the floor in every step";
        for (const auto& [step, onBox] : onBoxByStep)
        {
            const std::size_t k = static_cast<std::size_t>(step);
            const double momentum = m * (t.number(k, "vz") - t.number(k - 1, "vz")) / dt; // N
            ASSERT_NEAR(onBox, m * g + momentum, 1e-9 * m * g) << "step " << step;
            if (tolerance == "1e-9")
            {
                ASSERT_NEAR(normalByStep[step], m * g, m * 2e-9 / dt) << "step " << step;
            }
        }
    }
}

// Times are step * dt exactly, not a sum of dt's: after 1200 steps of 1 ms every file says 1.2
// (a sum of 1 ms steps says 1.1999999999999786), and each recorded time is k dt to the bit.
TEST(RunOutputs, RecordedTimesAreWholeStepsOfDt)
{
    const TestDir dir;
    const std::string scene = dir.write("clock.yaml", R"(
simulation: {dt: 0.001}
bodies:
  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1]}}
  - {name: box, mass: 1.0, shape: {type: box, size: [0.2, 0.2, 0.2]}, position: [0, 0, 0.1]}
  - {name: bob, mass: 1.0, shape: {type: sphere, radius: 0.05}, position: [0.5, 1, 2]}
joints:
  - {name: pivot, type: revolute, parent: world, child: bob, anchor: [0, 1, 2], axis: [0, 1, 0]}
)");
    const std::string traj = dir.out("t.csv");
    const std::string joints = dir.out("j.csv");
    const std::string contacts = dir.out("c.csv");
    const Result r =
        dir.run("run " + shellQuote(scene) + " --quiet --steps 1200 --record-every 100 --trajectory " +
                shellQuote(traj) + " --joints " + shellQuote(joints) + " --contacts " + shellQuote(contacts));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const std::string& file : {traj, joints, contacts})
    {
        const CsvTable table = readCsvTable(file);
        ASSERT_FALSE(table.rows.empty()) << file;
        EXPECT_EQ(table.text(table.rows.size() - 1, "time"), "1.2") << file;
        for (std::size_t k = 0; k < table.rows.size(); ++k)
        {
            const double t = table.number(k, "time");
            const double steps = std::round(t / 0.001);
            ASSERT_EQ(t, steps * 0.001) << file << ", row " << k << ": " << table.text(k, "time");
        }
    }
}

} // namespace
} // namespace frontier::app::test
