// tests/cli/render_cli_test.cpp: frames from `run --frames` and `render`, batches, bad input.
#include "app_test_util.h"
#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

namespace
{
using frontier::app::test::readText;
using frontier::app::test::Result;
using frontier::app::test::spawnFrontier;
using frontier::app::test::TestDir;
using frontier::app::test::waitForExit;
using frontier::app::test::waitForHandler;
namespace fs = std::filesystem;

std::vector<std::string> listFolder(const std::string& folder)
{
    std::vector<std::string> names;
    if (!fs::is_directory(folder))
    {
        return names;
    }
    for (const auto& entry : fs::directory_iterator(folder))
    {
        names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

TEST(RenderCli, FrameCountAndNamesFollowDurationAndFps)
{
    TestDir dir;
    const Result r =
        dir.run("run scenes/pendulum.yaml --duration 1 --fps 10 --width 64 --height 48 --frames " +
                dir.out("frames"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // Frames at t = k / fps for k / fps within [0, 1 s]: floor(1 * 10) + 1 = 11.
    const std::vector<std::string> names = listFolder(dir.out("frames"));
    ASSERT_EQ(names.size(), 11u);
    for (std::size_t k = 0; k < names.size(); ++k)
    {
        char expected[32];
        std::snprintf(expected, sizeof expected, "frame_%05zu.png", k);
        EXPECT_EQ(names[k], expected);
    }
    const frontier::render::Image image = frontier::render::readPng(dir.out("frames") + "/frame_00005.png");
    EXPECT_EQ(image.width, 64);
    EXPECT_EQ(image.height, 48);
}

TEST(RenderCli, RenderFromTrajectoryEqualsRunFramesPixelForPixel)
{
    TestDir dir;
    const std::string size = " --fps 20 --width 96 --height 72";
    const Result run = dir.run("run scenes/falling_doll.yaml --duration 0.4" + size + " --frames " +
                               dir.out("from_run") + " --trajectory " + dir.out("doll.csv"));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const Result render =
        dir.run("render " + dir.out("doll.csv") + size + " --frames " + dir.out("from_csv"));
    ASSERT_EQ(render.exitCode, 0) << render.err;
    const std::vector<std::string> a = listFolder(dir.out("from_run"));
    const std::vector<std::string> b = listFolder(dir.out("from_csv"));
    ASSERT_EQ(a.size(), 9u); // t = 0, 0.05, ..., 0.4
    ASSERT_EQ(a, b);
    for (const std::string& name : a)
    {
        const frontier::render::Image x = frontier::render::readPng(dir.out("from_run") + "/" + name);
        const frontier::render::Image y = frontier::render::readPng(dir.out("from_csv") + "/" + name);
        ASSERT_EQ(x.rgba.size(), y.rgba.size());
        EXPECT_TRUE(x.rgba == y.rgba) << name << " differs";
    }
    // The frames show motion: the first and last differ.
    EXPECT_FALSE(frontier::render::readPng(dir.out("from_run") + "/" + a.front()).rgba ==
                 frontier::render::readPng(dir.out("from_run") + "/" + a.back()).rgba);
}

TEST(RenderCli, MissingTrajectoryExitsTwoNamingIt)
{
    TestDir dir;
    const Result r = dir.run("render " + dir.out("nope.csv") + " --frames " + dir.out("frames"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("nope.csv"), std::string::npos) << r.err;
    EXPECT_TRUE(listFolder(dir.out("frames")).empty());
}

TEST(RenderCli, UnreadableTrajectoryExitsTwoNamingTheLine)
{
    TestDir dir;
    const std::string path = dir.write("bad.csv", "time,body,px\n0,bob,zero\n");
    const Result r =
        dir.run("render " + path + " --scene scenes/pendulum.yaml --frames " + dir.out("frames"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("bad.csv:"), std::string::npos) << r.err;
    EXPECT_TRUE(listFolder(dir.out("frames")).empty());
}

TEST(RenderCli, TrajectoryOfAnotherSceneExitsTwoNamingTheBody)
{
    TestDir dir;
    ASSERT_EQ(dir.run("run scenes/pendulum.yaml --duration 0.1 --trajectory " + dir.out("p.csv")).exitCode,
              0);
    const Result r = dir.run("render " + dir.out("p.csv") + " --scene scenes/double_pendulum.yaml --frames " +
                             dir.out("frames"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("'bob'"), std::string::npos) << r.err;
    EXPECT_TRUE(listFolder(dir.out("frames")).empty());
}

// The scene a trajectory names is read from where frontier runs: recorded elsewhere, it is not
// there, and the message says where the path came from and what to give instead.
TEST(RenderCli, SceneNamedByTheTrajectoryButNotHereAsksForScene)
{
    TestDir dir;
    ASSERT_EQ(dir.run("run scenes/pendulum.yaml --duration 0.1 --trajectory " + dir.out("p.csv")).exitCode,
              0);
    std::string text = readText(dir.out("p.csv"));
    const std::string recorded = "scene=scenes/pendulum.yaml";
    ASSERT_NE(text.find(recorded), std::string::npos);
    text.replace(text.find(recorded), recorded.size(), "scene=elsewhere/pendulum.yaml");
    dir.write("moved.csv", text);
    const std::string moved = (dir.path() / "moved.csv").string();
    const Result r = dir.run("render " + moved + " --frames " + dir.out("frames"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("recorded from scene 'elsewhere/pendulum.yaml'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--scene"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.out("frames")));
    EXPECT_EQ(
        dir.run("render " + moved + " --scene scenes/pendulum.yaml --frames " + dir.out("frames")).exitCode,
        0);
}

TEST(RenderCli, UnwritableFolderExitsTwoAndWritesNothing)
{
    TestDir dir;
    ASSERT_EQ(dir.run("run scenes/pendulum.yaml --duration 0.1 --trajectory " + dir.out("p.csv")).exitCode,
              0);
    dir.write("out/blocker", "a file where a folder should be");
    const Result r = dir.run("render " + dir.out("p.csv") + " --frames " + dir.out("blocker/frames"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("blocker"), std::string::npos) << r.err;
    const Result run = dir.run("run scenes/pendulum.yaml --duration 0.1 --frames " +
                               dir.out("blocker/frames") + " --trajectory " + dir.out("t.csv"));
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_FALSE(fs::exists(dir.out("t.csv"))); // nothing half-written
}

TEST(RenderCli, BatchReportsTheFailingJobAndFinishesTheOthers)
{
    TestDir dir;
    ASSERT_EQ(dir.run("run scenes/pendulum.yaml --duration 0.2 --trajectory " + dir.out("good.csv")).exitCode,
              0);
    dir.write("out/broken.csv", "not a trajectory\n");
    const Result r = dir.run("render " + dir.out("good.csv") + " " + dir.out("broken.csv") +
                             " --fps 10 --width 32 --height 24 --frames " + dir.out("frames"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("broken: FAILED"), std::string::npos) << r.err;
    EXPECT_EQ(listFolder(dir.out("frames/good")).size(), 3u); // t = 0, 0.1, 0.2
    EXPECT_TRUE(listFolder(dir.out("frames/broken")).empty());
}

TEST(RenderCli, VideoIsMadeWithFfmpegOrRefusedClearly)
{
    TestDir dir;
    const bool ffmpeg = std::system("command -v ffmpeg >/dev/null 2>&1") == 0;
    const Result r =
        dir.run("run scenes/pendulum.yaml --duration 0.3 --fps 10 --width 64 --height 48 --frames " +
                dir.out("frames") + " --video " + dir.out("v.mp4"));
    if (ffmpeg)
    {
        EXPECT_EQ(r.exitCode, 0) << r.err;
        ASSERT_TRUE(fs::exists(dir.out("v.mp4")));
        EXPECT_GT(fs::file_size(dir.out("v.mp4")), 100u);
    }
    else
    {
        EXPECT_EQ(r.exitCode, 2);
        EXPECT_NE(r.err.find("ffmpeg"), std::string::npos) << r.err;
    }
}

// SIGTERM while `render` writes frames: exit 143, one line naming the signal, the frames folder
// keeps its INCOMPLETE marker and no temporary file is left.
TEST(RenderCli, SignalStopsRenderingAndMarksTheFramesIncomplete)
{
    TestDir dir;
    const Result run =
        dir.run("run scenes/pendulum.yaml --duration 30 --record-every 10 --trajectory " + dir.out("p.csv"));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const std::string frames = dir.out("frames");
    const pid_t pid = spawnFrontier(dir, {"render", dir.out("p.csv"), "--fps", "100", "--width", "64",
                                          "--height", "48", "--jobs", "1", "--quiet", "--frames", frames});
    ASSERT_GT(pid, 0);
    const auto start = std::chrono::steady_clock::now();
    while (!fs::exists(frames + "/frame_00000.png") &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 60.0)
    {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_TRUE(waitForHandler(pid, SIGTERM, 10.0));
    ::kill(pid, SIGTERM);
    EXPECT_EQ(waitForExit(pid, 60.0), 143);
    const std::string err = readText(dir.path() / "stderr.txt");
    EXPECT_NE(err.find("interrupted by SIGTERM after "), std::string::npos) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_TRUE(fs::exists(frames + "/INCOMPLETE"));
    EXPECT_FALSE(fs::exists(frames + "/frame_03000.png"));
    for (const auto& entry : fs::recursive_directory_iterator(dir.path() / "out"))
    {
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
    }
}

} // namespace
