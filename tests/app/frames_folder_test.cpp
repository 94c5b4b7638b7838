// tests/app/frames_folder_test.cpp: what `frontier run --frames` leaves in its folder: only this
// run's frames (an earlier run's frame_*.png removed, other files kept), the INCOMPLETE marker on
// a run that failed, --video refused before the run when ffmpeg is missing; and the failed run's
// stats holding the gap of the joint that came apart.
#include "app_test_util.h"
#include "io/stats.h"

#include <cstdlib>
#include <gtest/gtest.h>
#include <set>

namespace frontier::app::test
{
namespace
{

std::set<std::string> namesIn(const std::string& folder)
{
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
    {
        names.insert(entry.path().filename().string());
    }
    return names;
}

TEST(FramesFolder, HoldsOnlyTheLastRunsFrames)
{
    const TestDir dir;
    const std::string frames = dir.out("frames");
    const std::string size = " --quiet --fps 100 --width 16 --height 16 --frames " + shellQuote(frames);
    ASSERT_EQ(dir.run("run scenes/pendulum.yaml --duration 0.1" + size).exitCode, 0);
    ASSERT_EQ(namesIn(frames).size(), 11u); // t = 0, 0.01, ..., 0.1
    dir.write("out/frames/notes.txt", "mine\n");
    dir.write("out/frames/frame_0001.jpg", "not one of ours\n");

    const Result second = dir.run("run scenes/pendulum.yaml --duration 0.02" + size);
    ASSERT_EQ(second.exitCode, 0) << second.err;
    EXPECT_EQ(namesIn(frames), (std::set<std::string>{"frame_00000.png", "frame_00001.png", "frame_00002.png",
                                                      "notes.txt", "frame_0001.jpg"}));
}

// The 1e6:1 heavy tip comes apart under rattle at step 51: the frames folder says it is incomplete
// and holds no frames, and the stats' largest joint error is the gap it came apart by (above the
// 1 mm at which the run stops), not the steps' before it.
TEST(FramesFolder, FailedRunLeavesItMarkedIncompleteAndReportsTheGap)
{
    const TestDir dir;
    const std::string frames = dir.out("frames");
    std::filesystem::create_directories(frames);
    dir.write("out/frames/frame_00007.png", "an earlier run's\n");
    const Result r = dir.run("run scenes/stability/heavy_tip_1e6.yaml --integrator rattle --quiet --width 16 "
                             "--height 16 --stats " +
                             shellQuote(dir.out("s.json")) + " --frames " + shellQuote(frames));
    ASSERT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("came off"), std::string::npos) << r.err;
    EXPECT_EQ(namesIn(frames), std::set<std::string>{"INCOMPLETE"});
    const io::RunStats stats = io::readStats(dir.out("s.json"));
    EXPECT_FALSE(stats.completed);
    EXPECT_GT(stats.maxJointErrorM, 1e-3);
}

TEST(FramesFolder, VideoWithoutFfmpegIsRefusedBeforeTheRun)
{
    const TestDir dir;
    const char* path = std::getenv("PATH");
    const std::string saved = path != nullptr ? path : "";
    ::setenv("PATH", dir.path().c_str(), 1); // no ffmpeg here; the shell runs frontier by its full path
    const Result r =
        dir.run("run scenes/pendulum.yaml --quiet --duration 0.1 --stats " + shellQuote(dir.out("s.json")) +
                " --frames " + shellQuote(dir.out("frames")) + " --video " + shellQuote(dir.out("v.mp4")));
    ::setenv("PATH", saved.c_str(), 1);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("ffmpeg is not installed"), std::string::npos) << r.err;
    EXPECT_TRUE(dir.outputs().empty()); // refused before anything was written
}

} // namespace
} // namespace frontier::app::test
