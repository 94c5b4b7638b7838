// tests/app/batch_test.cpp: `frontier batch` end to end: the plan's expansion and ids, bad plans
// (exit 2, file:line), scene paths and seeds that change the physics as asked, resume after a
// SIGTERM without redoing finished jobs, after a SIGKILL without its temporary files, locks,
// shards, the merge of sharded runs equal to a single machine's, its columns per actuator, and the
// Slurm script's tasks.
#include "app_test_util.h"
#include "csv_table.h"
#include "io/stats.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <sys/file.h>
#include <sys/stat.h>

namespace
{
using frontier::app::test::readText;
using frontier::app::test::Result;
using frontier::app::test::shellQuote;
using frontier::app::test::spawnFrontier;
using frontier::app::test::TestDir;
using frontier::app::test::waitForExit;
using frontier::app::test::waitForHandler;
using frontier::test::readCsvTable;
namespace fs = std::filesystem;

std::vector<std::string> lines(const std::string& text)
{
    std::vector<std::string> out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
    {
        out.push_back(line);
    }
    return out;
}

// The ids of `--list` lines ("ID  SCENE  VARIATION").
std::vector<std::string> ids(const std::string& listing)
{
    std::vector<std::string> out;
    for (const std::string& line : lines(listing))
    {
        out.push_back(line.substr(0, line.find(' ')));
    }
    return out;
}

// A plan in the test folder naming the bundled scenes by absolute path (globs too).
std::string scenesDir()
{
    return frontier::app::test::sourcePath("scenes");
}

// 2 scenes x 2 dt x 2 solvers: 8 jobs of 0.1 s.
std::string smallPlan()
{
    return "scenes: [" + scenesDir() + "/bouncing_ball.yaml, " + scenesDir() +
           "/pendulum.yaml]\n"
           "duration: 0.1\n"
           "outputs: [stats, trajectory]\n"
           "vary:\n"
           "  dt: [0.001, 0.002]\n"
           "  solver: [linear, pgs]\n";
}

struct FileStamp
{
    ino_t inode = 0;
    long long mtimeNs = 0;
    bool operator==(const FileStamp&) const = default;
};

FileStamp stamp(const fs::path& path)
{
    struct stat info
    {
    };
    if (::stat(path.c_str(), &info) != 0)
    {
        return {};
    }
    return {info.st_ino, static_cast<long long>(info.st_mtim.tv_sec) * 1000000000LL + info.st_mtim.tv_nsec};
}

bool completedStats(const fs::path& stats)
{
    const std::string text = readText(stats);
    return text.find("\"completed\": true") != std::string::npos;
}

// batch.csv without its wall-clock columns (those named wall_*).
std::string withoutWallClock(const std::string& csvPath)
{
    std::string out;
    std::vector<bool> keep;
    for (const std::string& line : lines(readText(csvPath)))
    {
        if (!line.empty() && line.front() == '#')
        {
            out += line + "\n";
            continue;
        }
        const std::vector<std::string> fields = frontier::test::splitCsvLine(line);
        if (keep.empty())
        {
            for (const std::string& name : fields)
            {
                keep.push_back(name.rfind("wall_", 0) != 0);
            }
        }
        for (std::size_t k = 0; k < fields.size(); ++k)
        {
            if (keep.at(k))
            {
                out += fields[k] + ",";
            }
        }
        out += "\n";
    }
    return out;
}

TEST(Batch, ListExpandsTheGridWithStableDistinctIds)
{
    TestDir dir;
    const std::string plan = dir.write("plan.yaml", smallPlan());
    const Result first =
        dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(dir.out("b")) + " --list");
    ASSERT_EQ(first.exitCode, 0) << first.err;
    const std::vector<std::string> listed = lines(first.out);
    ASSERT_EQ(listed.size(), 8U);
    // Scenes outer, the last vary key fastest.
    EXPECT_NE(listed[0].find("bouncing_ball.yaml  dt=0.001 solver=linear"), std::string::npos) << listed[0];
    EXPECT_NE(listed[1].find("dt=0.001 solver=pgs"), std::string::npos) << listed[1];
    EXPECT_NE(listed[7].find("pendulum.yaml  dt=0.002 solver=pgs"), std::string::npos) << listed[7];
    const std::vector<std::string> a = ids(first.out);
    EXPECT_EQ(std::set<std::string>(a.begin(), a.end()).size(), 8U);
    EXPECT_EQ(a[0].substr(0, 5), "0000-");
    // Read again: the same ids. A value added to an axis: the jobs that were there keep their hash.
    EXPECT_EQ(
        ids(dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(dir.out("b")) + " --list").out), a);
    std::string widened = smallPlan();
    widened.replace(widened.find("[linear, pgs]"), 13, "[linear, dense, pgs]");
    const std::string plan2 = dir.write("plan2.yaml", widened);
    const std::vector<std::string> b =
        ids(dir.run("batch " + shellQuote(plan2) + " --out " + shellQuote(dir.out("b")) + " --list").out);
    ASSERT_EQ(b.size(), 12U);
    auto hash = [](const std::string& id) { return id.substr(id.rfind('-')); };
    std::set<std::string> hashes;
    for (const std::string& id : b)
    {
        hashes.insert(hash(id));
    }
    for (const std::string& id : a)
    {
        EXPECT_EQ(hashes.count(hash(id)), 1U) << id;
    }
    // Nothing ran.
    EXPECT_FALSE(fs::exists(dir.out("b")));
}

// For each case (a plan's text, written as plan.yaml, and a message): `batch plan.yaml --out b
// ARGS` exits with `exitCode` and its stderr holds `prefix` and the message.
void expectBatchMessages(const TestDir& dir, const std::vector<std::pair<std::string, std::string>>& cases,
                         const std::string& args, int exitCode, const std::string& prefix)
{
    for (const auto& [text, expected] : cases)
    {
        const std::string plan = dir.write("plan.yaml", text);
        const Result r =
            dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(dir.out("b")) + " " + args);
        EXPECT_EQ(r.exitCode, exitCode) << text << r.err;
        EXPECT_NE(r.err.find(prefix + expected), std::string::npos) << text << "\n" << r.err;
        fs::remove_all(dir.out("b"));
    }
}

TEST(Batch, BadPlansExit2WithFileLineAndWhatWasExpected)
{
    TestDir dir;
    dir.write("ball.yaml", readText(scenesDir() + "/bouncing_ball.yaml"));
    const std::vector<std::pair<std::string, std::string>> cases = {
        // plan text, expected message part (line 3 in each)
        {"scenes: [ball.yaml]\nduration: 0.1\nvery: {dt: [0.001]}\n", ":3:1: error: unknown key 'very'"},
        {"scenes: [ball.yaml]\nvary:\n  solver: [linear, fast]\n", ":3:20: error: unknown solver 'fast'"},
        {"scenes: [ball.yaml]\nvary:\n  dt: [0.001, -1]\n", ":3:15: error: expected a positive number"},
        {"scenes: [ball.yaml]\nvary:\n  bodies.nope.mass: [1, 2]\n",
         ":3:22: error: 'bodies.nope.mass' does not fit ball.yaml: no entry named 'nope'"},
        {"scenes: [ball.yaml]\nvary:\n  colour: [1]\n",
         ":3:3: error: unknown key 'colour' in 'vary'; expected dt"},
        {"duration: 1\nvary: {dt: [0.001]}\nscenes: [missing.yaml, '*.nothing']\n",
         ":3:10: error: no scene file"},
        {"duration: 1\nvary: {dt: [0.001]}\nscenes: ['*.nothing']\n",
         ":3:10: error: the glob '*.nothing' matches no file"},
        // A time step that is no normal double, or too small for the duration.
        {"scenes: [ball.yaml]\nduration: 0.1\ndt: 5e-324\n",
         ":3:5: error: expected a number from 2.2250738585072014e-308 to 1e+06 for 'dt' (s), got '5e-324'"},
        {"scenes: [ball.yaml]\nduration: 1\ndt: 1e-300\n",
         ":3:5: error: 'dt' 1e-300 is too small: duration 1 s at dt 1e-300 s makes 1e+300 steps"},
        {"scenes: [ball.yaml]\nvary: {duration: [1, 1e9]}\ndt: 1e-4\n",
         ":3:5: error: 'dt' 1e-4 is too small: duration 1e+09 s at dt 0.0001 s makes 1e+13 steps"},
        // Tags other than the standard ones of the value's type.
        {"scenes: [ball.yaml]\nduration: 0.1\ndt: !!str 0.001\n",
         ":3:5: error: expected a number for 'dt' (s), got one tagged 'tag:yaml.org,2002:str'"},
        {"scenes: [ball.yaml]\nduration: 0.1\nseed: !!float 2.5\n",
         ":3:7: error: expected an integer for 'seed', got '2.5'"},
        // Values of a vary key are compared as what they are: 1e-3 is 0.001.
        {"scenes: [ball.yaml]\nvary:\n  dt: [0.001, 1e-3]\n",
         ":3:15: error: the value 1e-3 is given twice for 'dt' in 'vary' (equal to the one at line 3, "
         "column 8)"},
        {"scenes: [ball.yaml]\nvary:\n  bodies.ball.position: [[0, 0, 1], [0.0, 0, 1.0]]\n",
         ":3:37: error: the value [0.0, 0, 1.0] is given twice for 'bodies.ball.position' in 'vary'"},
        {"scenes: [ball.yaml]\nvary:\n  seed: [!!int 7, 7]\n",
         ":3:19: error: the value 7 is given twice for 'seed' in 'vary'"},
    };
    expectBatchMessages(dir, cases, "--list", 2, "plan.yaml");
}

// An MJCF model is a batch's scene like a URDF: its run settings vary, its paths are no YAML.
TEST(Batch, MjcfModelsRunAndTheirPathsAreRefused)
{
    TestDir dir;
    dir.write("pendulum.xml",
              "<mujoco><worldbody><body pos=\"0 0 1\"><joint type=\"hinge\" axis=\"0 1 0\"/>"
              "<geom type=\"sphere\" size=\"0.1\" pos=\"0.5 0 0\"/></body></worldbody></mujoco>\n");
    const std::string plan =
        dir.write("plan.yaml", "scenes: [pendulum.xml]\nduration: 0.01\nvary: {dt: [0.001, 0.002]}\n");
    const Result ran = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(dir.out("b")));
    EXPECT_EQ(ran.exitCode, 0) << ran.err;
    expectBatchMessages(
        dir,
        {{"scenes: [pendulum.xml]\nduration: 0.01\nvary:\n  contact.friction: [0.1, 0.2]\n",
          ":4:22: error: 'contact.friction' is a scene path, and pendulum.xml is a model file (.xml), not a "
          "YAML scene"}},
        "--list", 2, "plan.yaml");
}

// Standard YAML tags on a plan's values (!!float, !!int, !!str where the value is of that type)
// are the values without them: the same jobs (ids) as the plain plan, run with those settings.
TEST(Batch, TaggedValuesAreThePlainValues)
{
    TestDir dir;
    dir.write("ball.yaml", readText(scenesDir() + "/bouncing_ball.yaml"));
    const std::string tagged =
        dir.write("tagged.yaml", "scenes: [ball.yaml]\nduration: !!float 0.01\ndt: !!float 0.001\n"
                                 "pgs_iterations: !!int 5\nsolver: !!str pgs\n"
                                 "vary: {seed: [!!int 3, 4], integrator: [!!str euler, rattle]}\n");
    const std::string plain = dir.write("plain.yaml", "scenes: [ball.yaml]\nduration: 0.01\ndt: 0.001\n"
                                                      "pgs_iterations: 5\nsolver: pgs\n"
                                                      "vary: {seed: [3, 4], integrator: [euler, rattle]}\n");
    const Result listed = dir.run("batch " + shellQuote(tagged) + " --out x --list");
    ASSERT_EQ(listed.exitCode, 0) << listed.err;
    EXPECT_EQ(listed.out, dir.run("batch " + shellQuote(plain) + " --out x --list").out);
    EXPECT_NE(listed.out.find("seed=3 integrator=euler"), std::string::npos) << listed.out;

    const std::string out = dir.out("t");
    const Result r = dir.run("batch " + shellQuote(tagged) + " --out " + shellQuote(out) + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<std::string> jobs = ids(listed.out);
    ASSERT_EQ(jobs.size(), 4U);
    for (const std::string& id : jobs)
    {
        const std::string stats = readText(fs::path(out) / "jobs" / id / "stats.json");
        EXPECT_NE(stats.find("\"completed\": true"), std::string::npos) << id << "\n" << stats;
        EXPECT_NE(stats.find("\"solver\": \"pgs\""), std::string::npos) << stats;
        EXPECT_NE(stats.find("\"pgs_iterations\": 5,"), std::string::npos) << stats;
        EXPECT_NE(stats.find("\"steps\": 10,"), std::string::npos) << stats;
    }

    // A tagged scene path's value reaches the scene as tagged (the scene loader reads its tags).
    const std::string scenePath = dir.write(
        "scene_path.yaml", "scenes: [ball.yaml]\nduration: 0.01\nset: {bodies.ball.mass: !!float 2}\n");
    const Result set = dir.run("batch " + shellQuote(scenePath) + " --out " + shellQuote(dir.out("s")));
    EXPECT_EQ(set.exitCode, 0) << set.err;
}

// Errors of the scene loader in a job with scene paths name the user's files: a line of the scene
// file where the scene gives the value, the plan's value where the plan sets it (also for a key the
// plan adds), never a line of the scene as written after setting the paths.
TEST(Batch, ScenePathJobErrorsNameTheUsersFiles)
{
    TestDir dir;
    std::string ball = readText(scenesDir() + "/bouncing_ball.yaml");
    dir.write("ball.yaml", ball);
    ball.replace(ball.find("mass: 0.5"), 9, "mass: -1 ");
    dir.write("bad_ball.yaml", ball); // line 15: "    mass: -1 ..."
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"scenes: [bad_ball.yaml]\nduration: 0.01\nset: {bodies.ball.position: [0, 0, 2]}\n",
         "bad_ball.yaml:15:11: error: expected a positive number for 'mass' in body 'ball'"},
        {"scenes: [ball.yaml]\nduration: 0.01\nvary:\n  bodies.ball.mass: [1, -2]\n",
         "plan.yaml:4:25: error: 'bodies.ball.mass' set for ball.yaml: expected a positive number for "
         "'mass' in body 'ball'"},
        {"scenes: [ball.yaml]\nduration: 0.01\nset: {bodies.ball.colour: [1, 0, 0]}\n",
         "plan.yaml:3:27: error: 'bodies.ball.colour' set for ball.yaml: unknown key 'colour'"},
    };
    expectBatchMessages(dir, cases, "--quiet", 1, "");
}

// --shard "" is no shard (not every job), and a shard index of -1 in the environment is refused,
// not read as missing.
TEST(Batch, AnEmptyShardOrANegativeTaskIdIsRefused)
{
    TestDir dir;
    const std::string plan = dir.write("plan.yaml", smallPlan());
    const Result empty = dir.run("batch " + shellQuote(plan) + " --out x --list --shard ''");
    EXPECT_EQ(empty.exitCode, 2) << empty.out;
    EXPECT_NE(empty.err.find("--shard: error: expected I/N with 0 <= I < N (shard I of N), got ''"),
              std::string::npos)
        << empty.err;
    ::setenv("SLURM_ARRAY_TASK_ID", "-1", 1);
    const Result negative = dir.run("batch " + shellQuote(plan) + " --out x --list --shard-from-env");
    ::unsetenv("SLURM_ARRAY_TASK_ID");
    EXPECT_EQ(negative.exitCode, 2) << negative.out;
    EXPECT_NE(negative.err.find("expected a whole number from 0 to 1000000000 in the environment variable "
                                "SLURM_ARRAY_TASK_ID, got '-1'"),
              std::string::npos)
        << negative.err;
}

// A plan of `scene` (a box on a 20 degree incline) at contact.friction 0.5 and 0.1 for 0.5 s: the
// box sticks at 0.5 and slides at 0.1 (a = g (sin 20 - 0.1 cos 20) = 2.43 m/s^2: 0.30 m in 0.5 s).
void expectStickThenSlide(const TestDir& dir, const std::string& scene)
{
    const std::string plan = dir.write("incline_plan.yaml", "scenes: [" + scene +
                                                                "]\n"
                                                                "duration: 0.5\n"
                                                                "outputs: [trajectory]\n"
                                                                "vary:\n"
                                                                "  contact.friction: [0.5, 0.1]\n");
    const std::string out = dir.out("incline");
    const Result r = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<std::string> jobs =
        ids(dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --list").out);
    ASSERT_EQ(jobs.size(), 2U);
    auto travel = [&](const std::string& id)
    {
        const auto t = readCsvTable(out + "/jobs/" + id + "/trajectory.csv");
        const std::size_t last = t.rows.size() - 1;
        return std::hypot(t.number(last, "px") - t.number(0, "px"), t.number(last, "pz") - t.number(0, "pz"));
    };
    EXPECT_LT(travel(jobs[0]), 1e-3);
    EXPECT_NEAR(travel(jobs[1]), 0.30, 0.05);
}

// A scene without `contact:` takes `contact.friction` (the settings map is made, with its
// defaults): the incline's box, its contact line removed, still sticks at 0.5 and slides at 0.1.
// A first key that is no settings map stays an error of the plan.
TEST(Batch, ASettingsMapTheSceneLacksIsMade)
{
    TestDir dir;
    std::string scene = readText(scenesDir() + "/box_incline.yaml");
    const std::size_t line = scene.find("contact: {friction: 0.5, restitution: 0.0}\n");
    ASSERT_NE(line, std::string::npos);
    scene.erase(line, scene.find('\n', line) + 1 - line);
    ASSERT_EQ(scene.find("contact:"), std::string::npos);
    dir.write("incline.yaml", scene);
    expectStickThenSlide(dir, "incline.yaml");

    const std::string typo =
        dir.write("typo.yaml", "scenes: [incline.yaml]\nvary:\n  contcat.friction: [0.5]\n");
    const Result bad =
        dir.run("batch " + shellQuote(typo) + " --out " + shellQuote(dir.out("t")) + " --list");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("'contcat.friction' does not fit incline.yaml: no key 'contcat'"),
              std::string::npos)
        << bad.err;
}

// The contact solve's tolerances are scene paths of a plan (contact.tolerance,
// contact.relative_tolerance): each job's trajectory is, row for row, that of `frontier run` with
// --contact-tolerance of the same value, and the two values give different runs.
TEST(Batch, ContactTolerancesVaryAsRunsFlags)
{
    TestDir dir;
    const std::string plan = dir.write("tolerance_plan.yaml", "scenes: [" + scenesDir() +
                                                                  "/box_stack.yaml]\n"
                                                                  "duration: 0.3\n"
                                                                  "outputs: [trajectory]\n"
                                                                  "vary:\n"
                                                                  "  contact.tolerance: [3e-5, 0.01]\n");
    const std::string out = dir.out("tolerance");
    const Result r = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<std::string> jobs =
        ids(dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --list").out);
    ASSERT_EQ(jobs.size(), 2U);
    const auto rows = [](const std::string& path)
    {
        const std::string text = readText(path);
        return text.substr(text.find('\n') + 1); // without the header line that names the files
    };
    const std::vector<std::string> values = {"3e-5", "0.01"};
    for (std::size_t k = 0; k < jobs.size(); ++k)
    {
        const std::string single = dir.out("run" + std::to_string(k) + ".csv");
        const Result run =
            dir.run("run " + scenesDir() + "/box_stack.yaml --duration 0.3 --contact-tolerance " + values[k] +
                    " --trajectory " + shellQuote(single) + " --quiet");
        ASSERT_EQ(run.exitCode, 0) << run.err;
        EXPECT_EQ(rows(out + "/jobs/" + jobs[k] + "/trajectory.csv"), rows(single)) << values[k];
    }
    EXPECT_NE(rows(out + "/jobs/" + jobs[0] + "/trajectory.csv"),
              rows(out + "/jobs/" + jobs[1] + "/trajectory.csv"));
}

// The scene paths reach the physics: a box on a 20 degree incline sticks at friction 0.5 and
// slides at 0.1 (expectStickThenSlide); the ball starts where
// its position says; a seed moves the free ball by at most `perturb.position` per axis, the same
// seed the same way.
TEST(Batch, ScenePathsAndSeedsChangeTheInitialStateAsAsked)
{
    TestDir dir;
    expectStickThenSlide(dir, scenesDir() + "/box_incline.yaml");

    const std::string seeds = dir.write("seeds.yaml", "scenes: [" + scenesDir() +
                                                          "/bouncing_ball.yaml]\n"
                                                          "duration: 0.01\n"
                                                          "outputs: [trajectory]\n"
                                                          "perturb: {position: 0.05}\n"
                                                          "set: {bodies.ball.position: [0, 0, 2]}\n"
                                                          "vary:\n"
                                                          "  seed: [1, 2]\n");
    const std::string out2 = dir.out("s");
    const std::string out3 = dir.out("s2");
    ASSERT_EQ(dir.run("batch " + shellQuote(seeds) + " --out " + shellQuote(out2) + " --quiet").exitCode, 0);
    ASSERT_EQ(dir.run("batch " + shellQuote(seeds) + " --out " + shellQuote(out3) + " --quiet").exitCode, 0);
    const std::vector<std::string> seeded =
        ids(dir.run("batch " + shellQuote(seeds) + " --out " + shellQuote(out2) + " --list").out);
    ASSERT_EQ(seeded.size(), 2U);
    std::vector<std::array<double, 3>> starts;
    for (const std::string& id : seeded)
    {
        const auto t = readCsvTable(out2 + "/jobs/" + id + "/trajectory.csv");
        const std::array<double, 3> p = {t.number(0, "px"), t.number(0, "py"), t.number(0, "pz")};
        EXPECT_LE(std::abs(p[0]), 0.05);
        EXPECT_LE(std::abs(p[1]), 0.05);
        EXPECT_LE(std::abs(p[2] - 2.0), 0.05);
        EXPECT_GT(std::abs(p[0]) + std::abs(p[1]) + std::abs(p[2] - 2.0), 1e-6);
        starts.push_back(p);
        EXPECT_EQ(readText(out2 + "/jobs/" + id + "/trajectory.csv"),
                  readText(out3 + "/jobs/" + id + "/trajectory.csv"));
    }
    EXPECT_NE(starts[0], starts[1]);

    // A body hinged to the world is not moved by a seed (a move would open its joint); a free one
    // gets a velocity change of at most perturb.velocity per axis.
    const std::string jointed =
        dir.write("jointed.yaml", "scenes: [" + scenesDir() + "/pendulum.yaml, " + scenesDir() +
                                      "/bouncing_ball.yaml]\n"
                                      "duration: 0.01\n"
                                      "outputs: [trajectory]\n"
                                      "perturb: {position: 0.05, velocity: 0.1}\n"
                                      "seed: 3\n");
    const std::string out4 = dir.out("j");
    ASSERT_EQ(dir.run("batch " + shellQuote(jointed) + " --out " + shellQuote(out4) + " --quiet").exitCode,
              0);
    const std::vector<std::string> two =
        ids(dir.run("batch " + shellQuote(jointed) + " --out " + shellQuote(out4) + " --list").out);
    ASSERT_EQ(two.size(), 2U);
    const auto pendulum = readCsvTable(out4 + "/jobs/" + two[0] + "/trajectory.csv");
    EXPECT_EQ(pendulum.number(0, "px"), 0.8660254037844386);
    EXPECT_EQ(pendulum.number(0, "pz"), 1.5);
    EXPECT_EQ(pendulum.number(0, "vx"), 0.0);
    const auto ball = readCsvTable(out4 + "/jobs/" + two[1] + "/trajectory.csv");
    const double vx = ball.number(0, "vx"), vy = ball.number(0, "vy");
    EXPECT_GT(std::abs(vx) + std::abs(vy), 1e-6);
    EXPECT_LE(std::abs(vx), 0.1);
    EXPECT_LE(std::abs(vy), 0.1);
}

// A batch over one servo's stiffness: batch.csv has five columns per actuator, after the stats'
// and before `failure`, named by the joint (and by the coordinate for the cylindrical joint's
// two), each equal to the job's stats; the shoulder's tracking error falls as its kp rises; the
// effort actuator's tracking columns are empty.
TEST(Batch, MergeHasColumnsPerActuator)
{
    TestDir dir;
    const std::string scene = dir.write("arm.yaml", R"(
simulation: {dt: 0.001}
bodies:
  - {name: arm, mass: 1.0, shape: {type: sphere, radius: 0.05}, position: [0.5, 0, 2]}
  - {name: hand, mass: 1.0, shape: {type: sphere, radius: 0.05}, position: [0.5, 2, 2]}
  - {name: sleeve, mass: 1.0, shape: {type: box, size: [0.1, 0.1, 0.1]}, position: [0, 4, 2]}
joints:
  - {name: shoulder, type: revolute, parent: world, child: arm, anchor: [0, 0, 2], axis: [0, 1, 0]}
  - {name: wrist, type: revolute, parent: world, child: hand, anchor: [0, 2, 2], axis: [0, 1, 0]}
  - {name: slider, type: cylindrical, parent: world, child: sleeve, anchor: [0, 4, 2], axis: [1, 0, 0]}
actuators:
  - {joint: shoulder, type: position, kp: 20, kd: 1, target: {sine: {amplitude: 0.5, frequency: 1}}}
  - {joint: wrist, type: effort, target: 1.0}
  - {joint: slider, coordinate: slide, type: position, kp: 100, kd: 10, target: 0.1}
  - {joint: slider, coordinate: rotation, type: velocity, kd: 1, target: 2.0}
)");
    const std::string plan = dir.write("gains.yaml", "scenes: [arm.yaml]\n"
                                                     "duration: 0.5\n"
                                                     "vary:\n"
                                                     "  actuators.0.kp: [20, 200, 2000]\n");
    const std::string out = dir.out("gains");
    Result r = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --merge");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto table = readCsvTable(out + "/batch.csv");
    const std::vector<std::string> figures = {"tracking_rms", "tracking_max", "effort_rms", "effort_max",
                                              "limit_steps"};
    const std::vector<std::string> prefixes = {"actuator.shoulder", "actuator.wrist", "actuator.slider.slide",
                                               "actuator.slider.rotation"};
    const auto failure = std::find(table.columns.begin(), table.columns.end(), "failure");
    ASSERT_NE(failure, table.columns.end());
    std::vector<std::string> expected;
    for (const std::string& prefix : prefixes)
    {
        for (const std::string& figure : figures)
        {
            expected.push_back(prefix + "." + figure);
        }
    }
    ASSERT_GE(failure - table.columns.begin(), static_cast<long>(expected.size()));
    EXPECT_EQ(std::vector<std::string>(failure - static_cast<long>(expected.size()), failure), expected);
    ASSERT_EQ(table.rows.size(), 3u);
    const std::vector<std::string> jobs =
        ids(dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --list").out);
    ASSERT_EQ(jobs.size(), 3u);
    double lastTracking = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < 3; ++j)
    {
        EXPECT_EQ(table.text(j, "status"), "done");
        const frontier::io::RunStats s = frontier::io::readStats(out + "/jobs/" + jobs[j] + "/stats.json");
        ASSERT_EQ(s.actuators.size(), 4u);
        for (std::size_t a = 0; a < 4; ++a)
        {
            const frontier::io::ActuatorStats& stat = s.actuators[a];
            const std::string& p = prefixes[a];
            if (stat.type == "effort")
            {
                EXPECT_EQ(table.text(j, p + ".tracking_rms"), "");
                EXPECT_EQ(table.text(j, p + ".tracking_max"), "");
            }
            else
            {
                EXPECT_EQ(table.number(j, p + ".tracking_rms"), stat.trackingRms) << p;
                EXPECT_EQ(table.number(j, p + ".tracking_max"), stat.trackingMax) << p;
            }
            EXPECT_EQ(table.number(j, p + ".effort_rms"), stat.effortRms) << p;
            EXPECT_EQ(table.number(j, p + ".effort_max"), stat.effortMax) << p;
            EXPECT_EQ(table.number(j, p + ".limit_steps"), static_cast<double>(stat.limitSteps)) << p;
        }
        const double tracking = table.number(j, "actuator.shoulder.tracking_rms"); // rad
        EXPECT_LT(tracking, 0.5 * lastTracking) << "kp " << table.text(j, "actuators.0.kp");
        lastTracking = tracking;
    }
}

// SIGTERM after the first of six jobs is complete: exit 143; the rerun leaves the finished jobs'
// files alone (same inode and mtime) and does the rest.
TEST(Batch, ResumesAfterSigtermWithoutRedoingFinishedJobs)
{
    TestDir dir;
    const std::string plan =
        dir.write("plan.yaml", "scenes: [" + scenesDir() +
                                   "/pendulum.yaml]\n"
                                   "duration: 5\n"
                                   "outputs: [stats, trajectory]\n"
                                   "vary:\n"
                                   "  dt: [0.0005, 0.00051, 0.00052, 0.00053, 0.00054, 0.00055]\n");
    const std::string out = dir.out("b");
    const std::vector<std::string> jobs =
        ids(dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --list").out);
    ASSERT_EQ(jobs.size(), 6U);
    const pid_t pid = spawnFrontier(dir, {"batch", plan, "--out", out, "--jobs", "1"});
    ASSERT_TRUE(waitForHandler(pid, SIGTERM, 20.0));
    const fs::path firstStats = fs::path(out) / "jobs" / jobs[0] / "stats.json";
    const auto start = std::chrono::steady_clock::now();
    while (!completedStats(firstStats) && std::chrono::steady_clock::now() - start < std::chrono::seconds(30))
    {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_TRUE(completedStats(firstStats));
    ::kill(pid, SIGTERM);
    EXPECT_EQ(waitForExit(pid, 30.0), 143);
    std::map<std::string, std::pair<FileStamp, FileStamp>> finished;
    for (const std::string& id : jobs)
    {
        const fs::path folder = fs::path(out) / "jobs" / id;
        if (completedStats(folder / "stats.json"))
        {
            finished[id] = {stamp(folder / "stats.json"), stamp(folder / "trajectory.csv")};
        }
    }
    ASSERT_GE(finished.size(), 1U);
    ASSERT_LT(finished.size(), jobs.size()) << "the batch ended before the signal; make its jobs longer";

    const Result again = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --jobs 2");
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_NE(again.out.find(std::to_string(finished.size()) + " complete before"), std::string::npos)
        << again.out;
    for (const std::string& id : jobs)
    {
        const fs::path folder = fs::path(out) / "jobs" / id;
        EXPECT_TRUE(completedStats(folder / "stats.json")) << id;
        EXPECT_TRUE(fs::exists(folder / "trajectory.csv")) << id;
        EXPECT_FALSE(fs::exists(folder / "trajectory.failed.csv"))
            << id << ": the interrupted attempt's rows remain";
        if (const auto it = finished.find(id); it != finished.end())
        {
            EXPECT_EQ(stamp(folder / "stats.json"), it->second.first) << id << " was redone";
            EXPECT_EQ(stamp(folder / "trajectory.csv"), it->second.second) << id << " was redone";
        }
    }
}

// The temporary files (NAME.tmp-XXXXXX) of files being written when the batch was killed outright
// (SIGKILL: nothing could remove them) go when the rerun takes the job, which then completes.
TEST(Batch, RerunRemovesTemporariesOfAKilledAttempt)
{
    TestDir dir;
    const std::string plan = dir.write("plan.yaml", "scenes: [" + scenesDir() +
                                                        "/pendulum.yaml]\n"
                                                        "duration: 5\n"
                                                        "outputs: [stats, trajectory]\n"
                                                        "vary:\n"
                                                        "  dt: [0.0005, 0.00051]\n");
    const std::string out = dir.out("b");
    auto temporaries = [&]()
    {
        std::vector<std::string> found;
        std::error_code error;
        for (const auto& entry : fs::recursive_directory_iterator(out, error))
        {
            if (entry.path().filename().string().find(".tmp-") != std::string::npos)
            {
                found.push_back(entry.path().string());
            }
        }
        return found;
    };
    const pid_t pid = spawnFrontier(dir, {"batch", plan, "--out", out, "--jobs", "1"});
    const auto start = std::chrono::steady_clock::now();
    while (temporaries().empty() && std::chrono::steady_clock::now() - start < std::chrono::seconds(30))
    {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ::kill(pid, SIGKILL);
    EXPECT_EQ(waitForExit(pid, 30.0), -1); // ended by the signal: no exit code
    const std::vector<std::string> left = temporaries();
    ASSERT_FALSE(left.empty()) << "no temporary file was open when the batch was killed";

    const Result again = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --jobs 2");
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_EQ(temporaries(), std::vector<std::string>{});
    for (const std::string& temporary : left)
    {
        const fs::path folder = fs::path(temporary).parent_path();
        EXPECT_TRUE(completedStats(folder / "stats.json")) << folder;
        EXPECT_TRUE(fs::exists(folder / "trajectory.csv")) << folder;
    }
}

// A job whose lock another process holds is skipped; a job that fails records why, the batch
// exits 1 naming it, and the merge lists it.
TEST(Batch, LockedJobsAreSkippedAndFailuresRecorded)
{
    TestDir dir;
    const std::string plan = dir.write("plan.yaml", "scenes: [" + scenesDir() +
                                                        "/bouncing_ball.yaml]\n"
                                                        "duration: 0.05\n"
                                                        "vary:\n"
                                                        "  bodies.ball.mass: [0.5, -1, 2]\n");
    const std::string out = dir.out("b");
    const std::vector<std::string> jobs =
        ids(dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --list").out);
    ASSERT_EQ(jobs.size(), 3U);
    const fs::path lockedFolder = fs::path(out) / "jobs" / jobs[2];
    fs::create_directories(lockedFolder);
    const int fd = ::open((lockedFolder / ".lock").c_str(), O_RDWR | O_CREAT, 0644);
    ASSERT_EQ(::flock(fd, LOCK_EX), 0);
    const Result r = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out));
    ::close(fd);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find(jobs[2] + ": running elsewhere"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("job " + jobs[1] + " (" + scenesDir() +
                         "/bouncing_ball.yaml bodies.ball.mass=-1) failed: "),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(completedStats(fs::path(out) / "jobs" / jobs[0] / "stats.json"));
    EXPECT_FALSE(fs::exists(lockedFolder / "stats.json"));
    const std::string failed = readText(fs::path(out) / "jobs" / jobs[1] / "stats.json");
    EXPECT_NE(failed.find("\"completed\": false"), std::string::npos) << failed;
    EXPECT_NE(failed.find("mass"), std::string::npos) << failed;

    const Result merged = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --merge");
    EXPECT_EQ(merged.exitCode, 1);
    const auto table = readCsvTable(out + "/batch.csv");
    ASSERT_EQ(table.rows.size(), 3U);
    EXPECT_EQ(table.text(0, "status"), "done");
    EXPECT_EQ(table.text(1, "status"), "failed");
    EXPECT_EQ(table.text(2, "status"), "missing");
    EXPECT_EQ(table.text(1, "bodies.ball.mass"), "-1");
    const std::string summary = readText(out + "/summary.md");
    EXPECT_NE(summary.find("3 jobs: 1 done, 1 failed, 1 missing"), std::string::npos) << summary;
    EXPECT_NE(summary.find("| " + jobs[1] + " |"), std::string::npos) << summary;
}

// Three shards: disjoint, their union every job, by index mod 3; from the environment as Slurm and
// Kubernetes give it. Run as three processes, their merge is the single machine's, byte for byte
// apart from the wall-clock columns; each row's steps are duration / dt.
TEST(Batch, ShardsPartitionTheJobsAndMergeLikeOneMachine)
{
    TestDir dir;
    const std::string plan = dir.write("plan.yaml", smallPlan());
    const std::string one = dir.out("one");
    const std::string three = dir.out("three");
    const std::vector<std::string> all =
        ids(dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(one) + " --list").out);
    ASSERT_EQ(all.size(), 8U);
    std::set<std::string> seen;
    for (int i = 0; i < 3; ++i)
    {
        const std::string shard = std::to_string(i) + "/3";
        const std::vector<std::string> part = ids(
            dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(three) + " --list --shard " + shard)
                .out);
        for (const std::string& id : part)
        {
            EXPECT_TRUE(seen.insert(id).second) << id << " is in two shards";
            EXPECT_EQ(std::stoi(id.substr(0, 4)) % 3, i) << id;
        }
        const std::string env = "SLURM_ARRAY_TASK_ID=" + std::to_string(i + 5) +
                                " SLURM_ARRAY_TASK_MIN=5 SLURM_ARRAY_TASK_MAX=7 ";
        const std::string binary = std::string(FRONTIER_BINARY_DIR) + "/app/frontier";
        const Result slurm = dir.run("batch " + shellQuote(plan) + " --out x --list --shard-from-env");
        EXPECT_EQ(slurm.exitCode, 2); // no shard in the environment
        const std::string listSlurm = "cd " + shellQuote(FRONTIER_SOURCE_DIR) + " && env " + env +
                                      shellQuote(binary) + " batch " + shellQuote(plan) +
                                      " --out x --list --shard-from-env > " +
                                      shellQuote((dir.path() / "slurm.txt").string());
        ASSERT_EQ(std::system(listSlurm.c_str()), 0);
        EXPECT_EQ(ids(readText(dir.path() / "slurm.txt")), part);
        const std::string listK8s =
            "cd " + shellQuote(FRONTIER_SOURCE_DIR) + " && env JOB_COMPLETION_INDEX=" + std::to_string(i) +
            " " + shellQuote(binary) + " batch " + shellQuote(plan) +
            " --out x --list --shards 3 --shard-from-env > " + shellQuote((dir.path() / "k8s.txt").string());
        ASSERT_EQ(std::system(listK8s.c_str()), 0);
        EXPECT_EQ(ids(readText(dir.path() / "k8s.txt")), part);
    }
    EXPECT_EQ(seen, std::set<std::string>(all.begin(), all.end()));

    ASSERT_EQ(
        dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(one) + " --jobs 2 --quiet").exitCode, 0);
    ASSERT_EQ(dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(one) + " --merge").exitCode, 0);
    // The chart of one column against another, drawn as the sweep's (gnuplot); a column that is not
    // there is bad input.
    const Result chart =
        dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(one) + " --merge --chart dt,steps");
    EXPECT_EQ(chart.exitCode, 0) << chart.err;
    EXPECT_NE(readText(one + "/chart.dat").find("0.002 50 "), std::string::npos);
    if (std::system("command -v gnuplot >/dev/null 2>&1") == 0)
    {
        EXPECT_TRUE(fs::exists(one + "/chart.png"));
    }
    const Result badChart =
        dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(one) + " --merge --chart dt,speed");
    EXPECT_EQ(badChart.exitCode, 2);
    EXPECT_NE(badChart.err.find("no column 'speed' in batch.csv"), std::string::npos) << badChart.err;
    for (int i = 0; i < 3; ++i)
    {
        const Result r = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(three) +
                                 " --quiet --shard " + std::to_string(i) + "/3");
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    ASSERT_EQ(dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(three) + " --merge").exitCode, 0);
    EXPECT_EQ(withoutWallClock(one + "/batch.csv"), withoutWallClock(three + "/batch.csv"));
    const auto table = readCsvTable(one + "/batch.csv");
    ASSERT_EQ(table.rows.size(), 8U);
    for (std::size_t row = 0; row < table.rows.size(); ++row)
    {
        EXPECT_EQ(table.text(row, "job"), all[row]);
        EXPECT_EQ(table.text(row, "status"), "done");
        EXPECT_EQ(table.number(row, "steps"), std::round(0.1 / table.number(row, "dt")));
        EXPECT_EQ(table.text(row, "solver"), row % 2 == 0 ? "linear" : "pgs");
    }
    // Wall-clock columns come last.
    const std::vector<std::string>& columns = table.columns;
    const auto firstWall = std::find_if(columns.begin(), columns.end(),
                                        [](const std::string& c) { return c.rfind("wall_", 0) == 0; });
    ASSERT_NE(firstWall, columns.end());
    EXPECT_TRUE(
        std::all_of(firstWall, columns.end(), [](const std::string& c) { return c.rfind("wall_", 0) == 0; }));
}

// --slurm without --submit: batch.sbatch is an array of one task per shard, merge.sbatch merges.
// A task submitted alone (`sbatch --array=1 batch.sbatch`, whose environment says task 1 of an
// array of one) runs shard 1 of 3, not the whole plan.
TEST(Batch, SlurmScriptTaskRunsItsShardAlsoWhenSubmittedAlone)
{
    TestDir dir;
    const std::string plan = dir.write("plan.yaml", smallPlan());
    const std::string out = dir.out("s");
    const Result written =
        dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --slurm --shards 3");
    ASSERT_EQ(written.exitCode, 0) << written.err;
    EXPECT_NE(written.out.find("sbatch --parsable " + shellQuote(out + "/slurm/batch.sbatch")),
              std::string::npos)
        << written.out;
    const std::string script = readText(out + "/slurm/batch.sbatch");
    EXPECT_NE(script.find("#SBATCH --array=0-2\n"), std::string::npos) << script;
    EXPECT_NE(script.find("#SBATCH " + shellQuote("--output=" + out + "/slurm/shard-%a.out") + "\n"),
              std::string::npos)
        << script;
    EXPECT_NE(readText(out + "/slurm/merge.sbatch").find(" --merge"), std::string::npos);

    const std::string log = (dir.path() / "task.txt").string();
    const std::string task = "env SLURM_ARRAY_JOB_ID=7 SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_MIN=1 "
                             "SLURM_ARRAY_TASK_MAX=1 SLURM_ARRAY_TASK_COUNT=1 bash " +
                             shellQuote(out + "/slurm/batch.sbatch") + " > " + shellQuote(log) + " 2>&1";
    ASSERT_EQ(std::system(task.c_str()), 0) << readText(log);
    EXPECT_NE(readText(log).find("(shard 1 of 3)"), std::string::npos) << readText(log);
    const std::vector<std::string> all =
        ids(dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --list").out);
    ASSERT_EQ(all.size(), 8U);
    for (std::size_t k = 0; k < all.size(); ++k)
    {
        EXPECT_EQ(completedStats(fs::path(out) / "jobs" / all[k] / "stats.json"), k % 3 == 1) << all[k];
    }
}

} // namespace
