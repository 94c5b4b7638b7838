// tests/app/batch_inputs_test.cpp: a batch never keeps a result whose inputs changed. For each kind
// of input (the scene's text, a URDF it loads through `models:`, that URDF's mesh and the mesh's
// material file, a CSV target table), a batch is run, rerun (all skipped), the input edited and the
// batch rerun: exactly the jobs reading it run again, their results show the edit, and the output
// counts them as redone. In-process: the digest follows the program's identity, the scene text and
// the bytes read, and the loaders' reads are recorded.
#include "app_test_util.h"
#include "io/file_util.h"
#include "io/input_digest.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/stat.h>

namespace
{
using frontier::app::test::readText;
using frontier::app::test::Result;
using frontier::app::test::shellQuote;
using frontier::app::test::sourcePath;
using frontier::app::test::TestDir;
namespace fs = std::filesystem;

// A 5 kg base whose collision shape is box.obj, and a pole (poleKg) on a hinge about x above it.
std::string armUrdf(double poleKg)
{
    return R"(<robot name="arm">
  <link name="base">
    <inertial><mass value="5"/><inertia ixx="0.07" iyy="0.07" izz="0.13" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><mesh filename="box.obj"/></geometry></collision>
  </link>
  <link name="pole">
    <inertial><origin xyz="0 0 0.2"/><mass value=")" +
           std::to_string(poleKg) +
           R"("/><inertia ixx="0.007" iyy="0.007" izz="0.0001" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="hinge" type="revolute">
    <parent link="base"/><child link="pole"/><origin xyz="0 0 0.05"/><axis xyz="1 0 0"/>
    <limit lower="-3" upper="3" effort="1000" velocity="10"/>
  </joint>
</robot>
)";
}

// A 0.4 x 0.4 m box from z = bottomM to 0.05 m in the base's frame, its material in box.mtl.
std::string boxObj(double bottomM)
{
    std::ostringstream out;
    out << "mtllib box.mtl\nusemtl grey\n";
    for (const double z : {bottomM, 0.05})
    {
        out << "v -0.2 -0.2 " << z << "\nv 0.2 -0.2 " << z << "\nv 0.2 0.2 " << z << "\nv -0.2 0.2 " << z
            << "\n";
    }
    out << "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\n"
           "f 4 1 5\nf 4 5 8\n";
    return out.str();
}

// The base's frame 0.05 m up: box.obj's bottom (-0.05 m) on the floor. The hinge's servo follows
// targets.csv.
constexpr const char* cRobotScene = R"(name: arm on a floor
simulation: {dt: 0.001, duration: 0.05, gravity: [0, 0, -9.81], solver: linear}
bodies:
  - name: floor
    static: true
    shape: {type: plane, normal: [0, 0, 1], offset: 0}
models:
  - urdf: arm.urdf
    position: [0, 0, 0.05]
actuators:
  - joint: hinge
    type: position
    kp: 200
    kd: 5
    target: {csv: {file: targets.csv}}
)";

struct InputsStamp
{
    ino_t inode = 0;
    long long mtimeNs = 0;
    bool operator==(const InputsStamp&) const = default;
};

InputsStamp inputsStamp(const fs::path& path)
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

// Two scenes x two dt: jobs 0 and 1 run robot.yaml (the URDF, mesh, material and table), jobs 2
// and 3 ball.yaml.
class BatchInputs : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        dir.write("arm.urdf", armUrdf(0.5));
        dir.write("box.obj", boxObj(-0.05));
        dir.write("box.mtl", "newmtl grey\nKd 0.5 0.5 0.5\n");
        dir.write("targets.csv", "time,hinge\n0,0\n0.05,0.3\n");
        dir.write("robot.yaml", cRobotScene);
        dir.write("ball.yaml", readText(sourcePath("scenes/bouncing_ball.yaml")));
        plan = dir.write("plan.yaml", "scenes: [robot.yaml, ball.yaml]\nduration: 0.05\noutputs: [stats]\n"
                                      "vary:\n  dt: [0.001, 0.002]\n");
        const Result listed = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --list");
        ASSERT_EQ(listed.exitCode, 0) << listed.err;
        std::istringstream lines(listed.out);
        for (std::string line; std::getline(lines, line);)
        {
            ids.push_back(line.substr(0, line.find(' ')));
        }
        ASSERT_EQ(ids.size(), 4U);
        const Result first = batch();
        ASSERT_EQ(first.exitCode, 0) << first.err;
        ASSERT_NE(first.out.find(": 4 run, 0 complete before"), std::string::npos) << first.out;
        expectAllSkipped();
    }

    Result batch() const
    {
        return dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --jobs 2");
    }

    fs::path statsPath(std::size_t job) const { return fs::path(out) / "jobs" / ids.at(job) / "stats.json"; }
    nlohmann::json stats(std::size_t job) const { return nlohmann::json::parse(readText(statsPath(job))); }

    void expectAllSkipped() const
    {
        const Result again = batch();
        ASSERT_EQ(again.exitCode, 0) << again.err;
        EXPECT_NE(again.out.find(": 0 run, 4 complete before"), std::string::npos) << again.out;
        EXPECT_EQ(again.out.find("redone"), std::string::npos) << again.out;
    }

    // Writes `text` over `file` and reruns: the jobs `redone` run again (their stats written anew,
    // with another inputs digest) and are counted as redone; the others are skipped untouched. Then
    // a rerun skips them all. Returns each redone job's stats from before and after.
    std::vector<std::pair<nlohmann::json, nlohmann::json>> editAndRerun(
        const std::string& file, const std::string& text, const std::vector<std::size_t>& redone)
    {
        std::vector<InputsStamp> stamps;
        std::vector<nlohmann::json> before;
        for (std::size_t job = 0; job < ids.size(); ++job)
        {
            stamps.push_back(inputsStamp(statsPath(job)));
            before.push_back(stats(job));
        }
        dir.write(file, text);
        const Result r = batch();
        EXPECT_EQ(r.exitCode, 0) << r.err;
        const std::string counts = ": " + std::to_string(redone.size()) + " run, " +
                                   std::to_string(ids.size() - redone.size()) + " complete before";
        EXPECT_NE(r.out.find(counts), std::string::npos) << file << "\n" << r.out;
        EXPECT_NE(r.out.find("; " + std::to_string(redone.size()) + " redone because their inputs changed"),
                  std::string::npos)
            << file << "\n"
            << r.out;
        std::vector<std::pair<nlohmann::json, nlohmann::json>> changed;
        for (std::size_t job = 0; job < ids.size(); ++job)
        {
            const bool expected = std::find(redone.begin(), redone.end(), job) != redone.end();
            const nlohmann::json after = stats(job);
            EXPECT_EQ(inputsStamp(statsPath(job)) != stamps[job], expected) << file << ": job " << ids[job];
            EXPECT_EQ(after.at("inputs_digest") != before[job].at("inputs_digest"), expected)
                << file << ": job " << ids[job];
            EXPECT_EQ(r.err.find(ids[job] + ": done (redone: its inputs changed") != std::string::npos,
                      expected)
                << file << ": job " << ids[job] << "\n"
                << r.err;
            if (expected)
            {
                changed.emplace_back(before[job], after);
            }
        }
        expectAllSkipped();
        return changed;
    }

    TestDir dir;
    std::string plan;
    std::string out = dir.out("runs");
    std::vector<std::string> ids;
};

TEST_F(BatchInputs, StatsRecordTheDigestAndEveryFileRead)
{
    const nlohmann::json robot = stats(0);
    const std::string digest = robot.at("inputs_digest");
    EXPECT_EQ(digest.size(), 64U);
    EXPECT_EQ(digest.find_first_not_of("0123456789abcdef"), std::string::npos) << digest;
    std::vector<std::string> names;
    for (const nlohmann::json& file : robot.at("input_files"))
    {
        names.push_back(fs::path(file.get<std::string>()).filename().string());
    }
    for (const char* name : {"robot.yaml", "arm.urdf", "box.obj", "box.mtl", "targets.csv"})
    {
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    }
    // Jobs that differ in run settings only read the same inputs.
    EXPECT_EQ(stats(1).at("inputs_digest"), digest);
    EXPECT_NE(stats(2).at("inputs_digest"), digest);
}

TEST_F(BatchInputs, AnEditedSceneRedoesItsJobsAndTheMergeCallsThemStaleUntilThen)
{
    std::string ball = readText(sourcePath("scenes/bouncing_ball.yaml"));
    ball.replace(ball.find("mass: 0.5"), 9, "mass: 1.0");
    dir.write("ball.yaml", ball);
    const Result merged = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --merge");
    EXPECT_EQ(merged.exitCode, 1) << merged.err;
    EXPECT_NE(merged.err.find("job " + ids[2] + " stale"), std::string::npos) << merged.err;
    EXPECT_NE(readText(fs::path(out) / "summary.md")
                  .find("2 done, 0 failed, 0 missing (not run, or not "
                        "finished), 2 stale"),
              std::string::npos);
    EXPECT_NE(readText(fs::path(out) / "batch.csv").find("," + std::string("stale") + ","),
              std::string::npos);

    const auto changed = editAndRerun("ball.yaml", ball, {2, 3});
    for (const auto& [before, after] : changed) // twice the mass: twice the potential energy
    {
        EXPECT_NEAR(after.at("energy_initial_j").get<double>(),
                    2.0 * before.at("energy_initial_j").get<double>(), 1e-9);
    }
    const Result merged2 = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --merge");
    EXPECT_EQ(merged2.exitCode, 0) << merged2.err;
}

TEST_F(BatchInputs, StatsWithoutADigestAreRedone)
{
    nlohmann::ordered_json old = nlohmann::ordered_json::parse(readText(statsPath(1)));
    old.erase("inputs_digest");
    old.erase("input_files");
    std::ofstream(statsPath(1)) << old.dump(2) << "\n";
    const Result r = batch();
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find(": 1 run, 3 complete before"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("; 1 redone because their inputs changed"), std::string::npos) << r.out;
    EXPECT_EQ(stats(1).at("inputs_digest"), stats(0).at("inputs_digest"));
}

// A stats file nested 200 000 deep (in its scene or its warnings) is a damaged result: the merge
// names the file and counts the job missing, the batch runs it again; a long value is shown short.
TEST_F(BatchInputs, DeeplyNestedOrHugeStatsAreADamagedResult)
{
    const std::string deep = std::string(200000, '[') + std::string(200000, ']');
    std::ofstream(statsPath(1)) << "{\"scene\": " << deep << "}\n";
    std::string withWarnings = readText(statsPath(2));
    const std::size_t warnings = withWarnings.find("\"warnings\": []");
    ASSERT_NE(warnings, std::string::npos) << withWarnings;
    withWarnings.replace(warnings, 15, "\"warnings\": " + deep);
    std::ofstream(statsPath(2)) << withWarnings;
    std::string longSteps = readText(statsPath(3));
    const std::size_t steps = longSteps.find("\"steps\": ");
    ASSERT_NE(steps, std::string::npos) << longSteps;
    longSteps.insert(steps + 9, "\"" + std::string(100000, 'z') + "\", \"old_steps\": ");
    std::ofstream(statsPath(3)) << longSteps;

    const Result merged = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --merge");
    EXPECT_EQ(merged.exitCode, 1) << merged.err;
    for (const std::size_t job : {1U, 2U, 3U})
    {
        EXPECT_NE(merged.err.find(statsPath(job).string() + ":"), std::string::npos) << merged.err;
        EXPECT_NE(merged.err.find("job " + ids[job] + " missing"), std::string::npos) << merged.err;
    }
    EXPECT_NE(merged.err.find("error: JSON nested deeper than 64 levels"), std::string::npos) << merged.err;
    EXPECT_NE(merged.err.find("expected an integer for 'steps', got \"" + std::string(39, 'z') + "...\n"),
              std::string::npos)
        << merged.err;
    EXPECT_LT(merged.err.size(), 4000U);

    const Result r = batch();
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find(": 3 run, 1 complete before"), std::string::npos) << r.out;
    expectAllSkipped();
}

TEST_F(BatchInputs, AnEditedUrdfRedoesTheJobsOfItsScene)
{
    const auto changed = editAndRerun("arm.urdf", armUrdf(1.5), {0, 1});
    for (const auto& [before, after] : changed) // a heavier pole: more potential energy
    {
        EXPECT_GT(after.at("energy_initial_j").get<double>(),
                  before.at("energy_initial_j").get<double>() + 0.1);
    }
}

TEST_F(BatchInputs, AnEditedMeshRedoesTheJobsOfItsScene)
{
    const auto changed = editAndRerun("box.obj", boxObj(-0.08), {0, 1});
    for (const auto& [before, after] : changed) // the box's bottom now starts 3 cm into the floor
    {
        EXPECT_LT(before.at("max_penetration_m").get<double>(), 1e-3);
        EXPECT_GT(after.at("max_penetration_m").get<double>(), 0.02);
    }
}

TEST_F(BatchInputs, AnEditedMaterialFileOfTheMeshRedoesTheJobsOfItsScene)
{
    const auto changed = editAndRerun("box.mtl", "newmtl grey\nKd 0.9 0.1 0.1\n", {0, 1});
    for (const auto& [before, after] : changed) // a colour: the same motion
    {
        EXPECT_EQ(after.at("energy_final_j"), before.at("energy_final_j"));
    }
}

TEST_F(BatchInputs, AnEditedTargetTableRedoesTheJobsOfItsScene)
{
    const auto changed = editAndRerun("targets.csv", "time,hinge\n0,0\n0.05,-0.9\n", {0, 1});
    for (const auto& [before, after] : changed) // three times the target: a harder push
    {
        EXPECT_GT(after.at("max_actuator_effort").get<double>(),
                  1.5 * before.at("max_actuator_effort").get<double>());
    }
}

TEST(BatchInputsDigest, FollowsTheProgramTheSceneTextAndTheBytesRead)
{
    using frontier::io::InputFile;
    using frontier::io::inputsDigest;
    // FIPS 180-4's example: SHA-256 of "abc".
    EXPECT_EQ(frontier::io::sha256Hex("abc"),
              "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    const std::vector<InputFile> files = {{"a/scene.yaml", frontier::io::sha256Hex("scene")},
                                          {"a/arm.urdf", frontier::io::sha256Hex("urdf")}};
    const std::string digest = inputsDigest("frontier 0.1.0\nexecutable 1234", "text", files);
    EXPECT_EQ(digest, inputsDigest("frontier 0.1.0\nexecutable 1234", "text", files));
    // Another binary, another version, another scene text, other bytes: another digest.
    EXPECT_NE(digest, inputsDigest("frontier 0.1.0\nexecutable 1235", "text", files));
    EXPECT_NE(digest, inputsDigest("frontier 0.2.0\nexecutable 1234", "text", files));
    EXPECT_NE(digest, inputsDigest("frontier 0.1.0\nexecutable 1234", "text2", files));
    std::vector<InputFile> edited = files;
    edited[1].sha256 = frontier::io::sha256Hex("urdf2");
    EXPECT_NE(digest, inputsDigest("frontier 0.1.0\nexecutable 1234", "text", edited));
    // The same bytes reached by other paths: the same inputs.
    std::vector<InputFile> moved = files;
    moved[0].path = "/elsewhere/scene.yaml";
    EXPECT_EQ(digest, inputsDigest("frontier 0.1.0\nexecutable 1234", "text", moved));
    // This program: its version, then its executable's digest, the same on every call.
    const std::string& program = frontier::io::programIdentity();
    EXPECT_EQ(program.rfind(frontier::io::frontierVersion() + "\nexecutable ", 0), 0U) << program;
    EXPECT_EQ(program.find("unreadable"), std::string::npos) << program;
    EXPECT_EQ(&program, &frontier::io::programIdentity());
}

TEST(BatchInputsDigest, LogsRecordEachFileReadOnceInNestedLogs)
{
    TestDir dir;
    const std::string a = dir.write("a.txt", "first");
    const std::string b = dir.write("b.txt", "second");
    using frontier::io::detail::InputFileLog;
    using frontier::io::detail::readTextFile;
    readTextFile(a); // no log open: nothing recorded
    const InputFileLog outer;
    readTextFile(a);
    {
        const InputFileLog inner;
        readTextFile(b);
        frontier::io::detail::checkInputFile(a); // a reader opening the file itself
        ASSERT_EQ(inner.files().size(), 2U);
        EXPECT_EQ(inner.files()[0].path, b);
        EXPECT_EQ(inner.files()[1].path, a);
    }
    readTextFile(b);
    ASSERT_EQ(outer.files().size(), 2U);
    EXPECT_EQ(outer.files()[0].path, a);
    EXPECT_EQ(outer.files()[0].sha256, frontier::io::sha256Hex("first"));
    EXPECT_EQ(outer.files()[1].path, b);
    EXPECT_EQ(outer.files()[1].sha256, frontier::io::sha256Hex("second"));
}

} // namespace
