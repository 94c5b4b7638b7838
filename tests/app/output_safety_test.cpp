// tests/app/output_safety_test.cpp: what outputs may not do. No output replaces a file the load
// read (scene, URDF, meshes found through --package-path, a CSV target table; spelled through a
// link or another path), in `run`, `render`, `sweep` and `stability`; marker and lock files are
// never written through a symbolic link (run and batch frames folders, a batch job's lock);
// --video is written by ffmpeg under a temporary name, so a signal while it encodes leaves no
// video and exits 128 + N; a run removes the temporaries a run killed outright left of its own
// outputs, and nothing else.
#include "app_test_util.h"

#include <csignal>
#include <gtest/gtest.h>
#include <map>
#include <set>

namespace frontier::app::test
{
namespace
{
namespace fs = std::filesystem;

// Every regular file under `root` (links not followed) with its bytes, outputs of the commands
// (out/) and their captured stdout and stderr left out.
std::map<std::string, std::string> inputSnapshot(const fs::path& root)
{
    std::map<std::string, std::string> files;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root))
    {
        const std::string relative = fs::relative(entry.path(), root).string();
        if (entry.is_regular_file() && !entry.is_symlink() && relative.rfind("out/", 0) != 0 &&
            relative != "stdout.txt" && relative != "stderr.txt")
        {
            files[relative] = readText(entry.path());
        }
    }
    return files;
}

// A scene whose load reads files of every kind: the scene, the URDF arm.urdf (a link to
// robot/arm6.urdf), its meshes (COLLADA, STL, OBJ) found in the package folder pkg/ through
// --package-path, and two CSV target tables (target.failed.csv, named so that
// `--trajectory target.csv` would keep a failed run's rows in it, and shots/INCOMPLETE).
class InputsKept : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        const fs::path root = dir.path();
        fs::create_directories(root / "pkg");
        fs::copy(sourcePath("scenes/robots/arm6_description"), root / "pkg/arm6_description",
                 fs::copy_options::recursive);
        fs::create_directories(root / "robot");
        fs::copy_file(sourcePath("scenes/robots/arm6_description/urdf/arm6.urdf"), root / "robot/arm6.urdf");
        fs::create_symlink(root / "robot/arm6.urdf", root / "arm.urdf");
        fs::create_directories(root / "shots");
        dir.write("target.failed.csv", "time,shoulder_pan_joint\n0,0\n1,0.5\n");
        dir.write("shots/INCOMPLETE", "time,elbow_joint\n0,0\n1,0.2\n");
        dir.write("scene.yaml", "name: arm reading files\n"
                                "simulation: {dt: 0.001, duration: 0.002, gravity: [0, 0, -9.81]}\n"
                                "bodies:\n"
                                "  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1]}}\n"
                                "models:\n"
                                "  - {urdf: arm.urdf, hold: true}\n"
                                "actuators:\n"
                                "  - {joint: shoulder_pan_joint, type: position, kp: 100, kd: 10,\n"
                                "     target: {csv: {file: target.failed.csv}}}\n"
                                "  - {joint: elbow_joint, type: position, kp: 100, kd: 10,\n"
                                "     target: {csv: {file: shots/INCOMPLETE}}}\n");
    }

    std::string at(const std::string& relative) const { return (dir.path() / relative).string(); }

    Result run(const std::string& flags) const
    {
        return dir.run("run " + shellQuote(at("scene.yaml")) + " --quiet --package-path " +
                       shellQuote(at("pkg")) + flags);
    }

    TestDir dir;
};

TEST_F(InputsKept, RunRefusesEveryOutputThatWouldReplaceAnInput)
{
    fs::create_directory_symlink(dir.path(), dir.path() / "alias"); // the same folder by another name
    const std::string meshes = "pkg/arm6_description/meshes/";
    // Flags (the one refused first), then the input named in the message.
    const std::pair<std::string, std::string> cases[] = {
        {" --trajectory " + shellQuote(at("robot/arm6.urdf")), "arm.urdf"}, // reached through a link
        {" --joints " + shellQuote(at("target.failed.csv")), "target.failed.csv"},
        {" --contacts " + shellQuote(at(meshes + "upper_arm.obj")), "upper_arm.obj"},
        {" --stats " + shellQuote(at(meshes + "base.dae")), "base.dae"},
        {" --stats " + shellQuote(at("alias/./" + meshes + "base.stl")), "base.stl"},
        {" --joints " + shellQuote(at("alias/pkg/../scene.yaml")), "scene.yaml"},
        {" --trajectory " + shellQuote(at("target.csv")), "target.failed.csv"}, // its failed name
        {" --contacts " + shellQuote(at("alias/target.csv")), "target.failed.csv"},
        {" --video " + shellQuote(at(meshes + "forearm.obj")) + " --frames " + shellQuote(at("out/frames")),
         "forearm.obj"},
        {" --frames " + shellQuote(at("alias/shots")), "INCOMPLETE"}, // it would write and remove it
        {" --trajectory " + shellQuote(at("robot/./arm6.urdf")) + " --stats " + shellQuote(dir.out("s.json")),
         "arm.urdf"},
    };
    const std::map<std::string, std::string> before = inputSnapshot(dir.path());
    for (const auto& [flags, input] : cases)
    {
        const Result r = run(flags);
        EXPECT_EQ(r.exitCode, 2) << flags << "\n" << r.err;
        const std::string flag = flags.substr(1, flags.find(' ', 1) - 1);
        EXPECT_NE(r.err.find("error: " + flag + " "), std::string::npos) << flags << "\n" << r.err;
        EXPECT_NE(r.err.find("the input "), std::string::npos) << flags << "\n" << r.err;
        EXPECT_NE(r.err.find(input), std::string::npos) << flags << "\n" << r.err;
        EXPECT_EQ(inputSnapshot(dir.path()), before) << flags;
    }
    EXPECT_TRUE(fs::is_empty(dir.out(""))) << "nothing written";
    // The same outputs elsewhere: the scene runs.
    const Result r =
        run(" --trajectory " + shellQuote(dir.out("t.csv")) + " --joints " + shellQuote(dir.out("j.csv")) +
            " --contacts " + shellQuote(dir.out("c.csv")) + " --stats " + shellQuote(dir.out("s.json")));
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(inputSnapshot(dir.path()), before);
}

// `render`: its inputs are the trajectory, the scene it names and the files that scene reads.
TEST_F(InputsKept, RenderRefusesAVideoOrFramesFolderThatWouldReplaceAnInput)
{
    const std::string trajectory = dir.out("t.csv");
    ASSERT_EQ(run(" --trajectory " + shellQuote(trajectory)).exitCode, 0);
    const std::map<std::string, std::string> before = inputSnapshot(dir.path());
    const std::string render = "render " + shellQuote(trajectory) +
                               " --quiet --width 16 --height 16 --package-path " + shellQuote(at("pkg")) +
                               " --frames ";
    const std::pair<std::string, std::string> cases[] = {
        {render + shellQuote(dir.out("f")) + " --video " + shellQuote(at("target.failed.csv")),
         "target.failed.csv"},
        {render + shellQuote(dir.out("f")) + " --video " +
             shellQuote(at("pkg/arm6_description/meshes/base.dae")),
         "base.dae"},
        {render + shellQuote(at("shots")), "INCOMPLETE"},
    };
    for (const auto& [command, input] : cases)
    {
        const Result r = dir.run(command);
        EXPECT_EQ(r.exitCode, 2) << command << "\n" << r.err;
        EXPECT_NE(r.err.find(input), std::string::npos) << command << "\n" << r.err;
        EXPECT_EQ(inputSnapshot(dir.path()), before) << command;
        EXPECT_FALSE(fs::exists(dir.out("f"))) << command;
    }
}

// `sweep`: none of sweep.csv, sweep.gp, sweep.dat and sweep.png in --out may be a file it read
// (here the reference CSV).
TEST(SweepOutputs, AnOutputThatIsTheReferenceIsRefused)
{
    const TestDir dir;
    std::string rows = "t,x,y,z\n";
    for (int k = 0; k <= 10; ++k)
    {
        rows += std::to_string(0.01 * k) + ",0.8660254037844386,0,1.5\n";
    }
    for (const char* name : {"sweep.csv", "sweep.dat"})
    {
        const std::string reference = dir.write(name, rows);
        const Result r = dir.run("sweep scenes/pendulum.yaml --dt 0.01 --integrator euler --duration 0.1 "
                                 "--reference-body bob --reference-csv " +
                                 shellQuote(reference) + " --out " + shellQuote(dir.path().string()));
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find("--out names the input " + reference), std::string::npos) << r.err;
        EXPECT_EQ(readText(reference), rows);
        fs::remove(reference);
    }
}

// `stability --out`: not a file a scene read (here the URDF of a scene's models).
TEST(StabilityOutputs, AnOutputThatIsAnInputOfAScenesModelIsRefused)
{
    const TestDir dir;
    const std::string scene = (dir.path() / "doll_urdf_scene.yaml").string();
    const std::string urdf = (dir.path() / "doll.urdf").string();
    fs::copy_file(sourcePath("scenes/doll_urdf_scene.yaml"), scene);
    fs::copy_file(sourcePath("scenes/doll.urdf"), urdf);
    const std::string before = readText(urdf);
    const Result r = dir.run("stability " + shellQuote(scene) +
                             " --quiet --duration 0.002 --methods linear/euler "
                             "--out " +
                             shellQuote(dir.path().string() + "/./doll.urdf"));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--out names the input " + urdf), std::string::npos) << r.err;
    EXPECT_EQ(readText(urdf), before);
}

// A link named INCOMPLETE in the frames folder is replaced by the marker, not written through: the
// file it points to keeps its bytes.
TEST(MarkerFiles, IncompleteIsNotWrittenThroughALink)
{
    const TestDir dir;
    const std::string victim = dir.write("victim.txt", "keep me\n");
    const std::string frames = dir.out("frames");
    fs::create_directories(frames);
    const auto runThroughLink = [&](const std::string& scene)
    {
        fs::create_symlink(victim, frames + "/INCOMPLETE");
        const Result r =
            dir.run("run " + scene + " --quiet --width 16 --height 16 --frames " + shellQuote(frames));
        EXPECT_EQ(readText(victim), "keep me\n") << scene;
        return r.exitCode;
    };
    EXPECT_EQ(runThroughLink("scenes/pendulum.yaml --duration 0.02 --fps 100"), 0);
    EXPECT_FALSE(fs::exists(fs::symlink_status(frames + "/INCOMPLETE")));
    // A failed run leaves the marker: a file of its own.
    EXPECT_EQ(runThroughLink("scenes/stability/heavy_tip_1e6.yaml --integrator rattle"), 1);
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(frames + "/INCOMPLETE")));
}

// The same in a batch job's frames folder; and a link named .lock in a job's folder is refused
// (the job fails naming it) instead of creating or locking the file it points to.
TEST(MarkerFiles, BatchJobsWriteNeitherMarkerNorLockThroughALink)
{
    const TestDir dir;
    const std::string plan = dir.write("plan.yaml", "scenes: [" + sourcePath("scenes/pendulum.yaml") +
                                                        "]\nduration: 0.02\nfps: 100\nwidth: 16\nheight: 16\n"
                                                        "outputs: [stats, frames]\n");
    const std::string out = dir.out("b");
    const Result listed = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --list");
    ASSERT_EQ(listed.exitCode, 0) << listed.err;
    const std::string id = listed.out.substr(0, listed.out.find(' '));
    ASSERT_FALSE(id.empty()) << listed.out;
    const fs::path job = fs::path(out) / "jobs" / id;
    fs::create_directories(job / "frames");
    const std::string victim = dir.write("victim.txt", "keep me\n");
    fs::create_symlink(victim, job / "frames/INCOMPLETE");
    const Result ran = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --quiet");
    EXPECT_EQ(ran.exitCode, 0) << ran.err;
    EXPECT_EQ(readText(victim), "keep me\n");
    EXPECT_TRUE(fs::exists(job / "frames/frame_00002.png"));

    fs::remove_all(job);
    fs::create_directories(job);
    const fs::path elsewhere = dir.path() / "elsewhere.lock";
    fs::create_symlink(elsewhere, job / ".lock");
    const Result locked = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --quiet");
    EXPECT_EQ(locked.exitCode, 1) << locked.err;
    EXPECT_NE(locked.err.find(".lock: cannot open the job's lock"), std::string::npos) << locked.err;
    EXPECT_FALSE(fs::exists(fs::symlink_status(elsewhere)));
}

// A stand-in for ffmpeg on the PATH: writes a few bytes to the file it is told to write (its last
// argument, after "file:"), then does what `then` says (sleep: waits to be stopped).
void writeFakeFfmpeg(const TestDir& dir, const std::string& then)
{
    const fs::path bin = dir.path() / "bin";
    fs::create_directories(bin);
    const std::string script = "#!/bin/sh\n"
                               "for a in \"$@\"; do out=\"$a\"; done\n"
                               "out=\"${out#file:}\"\n"
                               "printf 'a partial video file of 48 bytes, not playable' > \"$out\"\n"
                               "touch " +
                               shellQuote((dir.path() / "encoding").string()) + "\n" + then + "\n";
    dir.write("bin/ffmpeg", script);
    fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
}

// The entries of `folder` whose name holds ".tmp-".
std::vector<std::string> temporariesIn(const std::string& folder)
{
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    {
        if (entry.path().filename().string().find(".tmp-") != std::string::npos)
        {
            names.push_back(entry.path().filename().string());
        }
    }
    return names;
}

// SIGTERM while ffmpeg encodes: frontier passes it on, exits 143 and leaves no file under the
// video's name nor a temporary one.
TEST(VideoOutput, SignalWhileEncodingLeavesNoVideoAndExits143)
{
    const TestDir dir;
    writeFakeFfmpeg(dir, "exec sleep 30");
    const std::string video = dir.out("v.mp4");
    pid_t pid = 0;
    {
        const ScopedPath path((dir.path() / "bin").string() + ":" + std::getenv("PATH"));
        pid = spawnFrontier(dir, {"run", "scenes/pendulum.yaml", "--quiet", "--duration", "0.02", "--fps",
                                  "100", "--width", "16", "--height", "16", "--frames", dir.out("frames"),
                                  "--video", video});
    }
    ASSERT_GT(pid, 0);
    const auto start = std::chrono::steady_clock::now();
    while (!fs::exists(dir.path() / "encoding") &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 60.0)
    {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_TRUE(fs::exists(dir.path() / "encoding")) << readText(dir.path() / "stderr.txt");
    ::kill(pid, SIGTERM);
    EXPECT_EQ(waitForExit(pid, 20.0), 143) << readText(dir.path() / "stderr.txt");
    EXPECT_NE(readText(dir.path() / "stderr.txt").find("SIGTERM"), std::string::npos);
    EXPECT_FALSE(fs::exists(video));
    EXPECT_TRUE(temporariesIn(dir.out("")).empty());
}

// ffmpeg failing: exit 2 naming it, no file under the video's name nor a temporary one.
TEST(VideoOutput, FailedEncodingLeavesNoVideo)
{
    const TestDir dir;
    writeFakeFfmpeg(dir, "exit 1");
    const ScopedPath path((dir.path() / "bin").string() + ":" + std::getenv("PATH"));
    const std::string video = dir.out("v.mp4");
    const Result r =
        dir.run("run scenes/pendulum.yaml --quiet --duration 0.02 --fps 100 --width 16 --height 16 "
                "--frames " +
                shellQuote(dir.out("frames")) + " --video " + shellQuote(video));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("ffmpeg failed"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(video));
    EXPECT_TRUE(temporariesIn(dir.out("")).empty());
}

// Temporaries a run killed outright (SIGKILL) left of this run's outputs are removed when it starts;
// other names, however alike, are kept.
TEST(StaleTemporaries, RunRemovesThoseOfItsOwnOutputsOnly)
{
    const TestDir dir;
    const std::string frames = dir.out("frames");
    fs::create_directories(frames);
    const std::vector<std::string> stale = {"t.csv.tmp-Ab3dEf", "s.json.tmp-000000", "j.csv.tmp-zzzzzz",
                                            "frames/frame_00003.png.tmp-Qw12Er"};
    const std::vector<std::string> kept = {"t.csv.tmp-Ab3dEfG",
                                           "t.csv.tmp-Ab3dE",
                                           "x.t.csv.tmp-Ab3dEf",
                                           "other.csv.tmp-Ab3dEf",
                                           "t.tmp-Ab3dEf",
                                           "frames/notes.txt.tmp-Qw12Er",
                                           "frames/frame_00003.jpg.tmp-Qw12Er",
                                           "t.failed.csv"};
    for (const std::string& name : stale)
    {
        dir.write("out/" + name, "left by a killed run\n");
    }
    for (const std::string& name : kept)
    {
        dir.write("out/" + name, "someone else's\n");
    }
    const Result r =
        dir.run("run scenes/pendulum.yaml --quiet --duration 0.02 --fps 100 --width 16 --height 16 "
                "--trajectory " +
                shellQuote(dir.out("t.csv")) + " --stats " + shellQuote(dir.out("s.json")) + " --joints " +
                shellQuote(dir.out("j.csv")) + " --frames " + shellQuote(frames));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const std::string& name : stale)
    {
        EXPECT_FALSE(fs::exists(dir.out(name))) << name;
    }
    for (const std::string& name : kept)
    {
        EXPECT_EQ(readText(dir.out(name)), "someone else's\n") << name;
    }
}

// `render` and `sweep` do the same for theirs.
TEST(StaleTemporaries, RenderAndSweepRemoveThoseOfTheirOutputs)
{
    const TestDir dir;
    ASSERT_EQ(dir.run("run scenes/pendulum.yaml --quiet --duration 0.02 --trajectory " +
                      shellQuote(dir.out("p.csv")))
                  .exitCode,
              0);
    fs::create_directories(dir.out("frames"));
    dir.write("out/frames/frame_00000.png.tmp-aaaaaa", "x");
    dir.write("out/frames/keep.png.tmp-aaaaaa", "x");
    const Result render =
        dir.run("render " + shellQuote(dir.out("p.csv")) +
                " --quiet --width 16 --height 16 --fps 100 --frames " + shellQuote(dir.out("frames")));
    ASSERT_EQ(render.exitCode, 0) << render.err;
    EXPECT_EQ(temporariesIn(dir.out("frames")), std::vector<std::string>{"keep.png.tmp-aaaaaa"});

    fs::create_directories(dir.out("sweep"));
    for (const char* name :
         {"sweep.csv.tmp-aaaaaa", "sweep.gp.tmp-bbbbbb", "sweep.dat.tmp-cccccc", "mine.tmp-dddddd"})
    {
        dir.write(std::string("out/sweep/") + name, "x");
    }
    const Result sweep =
        dir.run("sweep scenes/pendulum.yaml --dt 0.01 --integrator euler --duration 0.05 --out " +
                shellQuote(dir.out("sweep")));
    ASSERT_EQ(sweep.exitCode, 0) << sweep.err;
    EXPECT_EQ(temporariesIn(dir.out("sweep")), std::vector<std::string>{"mine.tmp-dddddd"});
}

} // namespace
} // namespace frontier::app::test
