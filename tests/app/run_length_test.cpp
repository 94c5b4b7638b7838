// tests/app/run_length_test.cpp: how long `frontier run` simulates, said when it differs from what
// was asked: a --duration that is no whole number of steps is rounded (a note), and a load that
// starts after the run's end never acts (a warning in the summary and the stats; --strict fails).
#include "app_test_util.h"
#include "io/stats.h"

#include <gtest/gtest.h>

namespace frontier::app::test
{
namespace
{

TEST(RunLength, DurationRoundedToWholeStepsIsNoted)
{
    const TestDir dir;
    const std::string stats = shellQuote(dir.out("s.json"));
    const Result r = dir.run("run scenes/pendulum.yaml --dt 0.3 --duration 1 --stats " + stats);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("note: simulating 0.9 s instead of 1 s: 3 whole steps of 0.3 s"), std::string::npos)
        << r.err;
    EXPECT_EQ(io::readStats(dir.out("s.json")).steps, 3);

    const Result exact = dir.run("run scenes/pendulum.yaml --dt 0.25 --duration 1 --stats " + stats);
    ASSERT_EQ(exact.exitCode, 0) << exact.err;
    EXPECT_EQ(exact.err.find("note:"), std::string::npos) << exact.err;
    const Result quiet = dir.run("run scenes/pendulum.yaml --dt 0.3 --duration 1 --quiet");
    EXPECT_EQ(quiet.err.find("note:"), std::string::npos) << quiet.err;
}

TEST(RunLength, ImpulseAfterTheEndIsAWarning)
{
    const TestDir dir;
    const std::string scene = dir.write("push.yaml", R"(bodies:
  - {name: ball, mass: 1, shape: {type: sphere, radius: 0.1}}
loads:
  - {body: ball, impulse: [1, 0, 0], time: 2.0}
)");
    const std::string stats = shellQuote(dir.out("s.json"));
    const Result late = dir.run("run " + shellQuote(scene) + " --duration 1 --stats " + stats);
    ASSERT_EQ(late.exitCode, 0) << late.err;
    const std::string expected = "the impulse on body 'ball' at t = 2 s never acts: the run ends at 1 s";
    EXPECT_NE(late.out.find(expected), std::string::npos) << late.out;
    const io::RunStats s = io::readStats(dir.out("s.json"));
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find(expected), std::string::npos) << s.warnings[0];
    EXPECT_EQ(dir.run("run " + shellQuote(scene) + " --duration 1 --strict --quiet").exitCode, 1);

    const Result inTime = dir.run("run " + shellQuote(scene) + " --duration 2.5 --stats " + stats);
    ASSERT_EQ(inTime.exitCode, 0) << inTime.err;
    EXPECT_TRUE(io::readStats(dir.out("s.json")).warnings.empty());
}

} // namespace
} // namespace frontier::app::test
