// tests/cli/contact_tolerance_cli_test.cpp: --contact-tolerance and --contact-relative-tolerance of
// `frontier run`: what they change, that they equal the scene's `contact:` keys, that `check`
// re-solves with them from the trajectory's header, and their errors.
#include "app_test_util.h"

#include <gtest/gtest.h>
#include <regex>
#include <string>
#include <vector>

namespace
{
using frontier::app::test::readText;
using frontier::app::test::Result;
using frontier::app::test::sourcePath;
using frontier::app::test::TestDir;

// The "max penetration X m" of a run's summary (m); NaN when absent.
double maxPenetration(const std::string& summary)
{
    std::smatch m;
    return std::regex_search(summary, m, std::regex("max penetration ([0-9.eE+-]+) m")) ? std::stod(m[1])
                                                                                        : std::nan("");
}

// The trajectory's rows without its header line (the line that names the settings).
std::string rows(const std::string& trajectory)
{
    return trajectory.substr(trajectory.find('\n') + 1);
}

// scenes/box_stack.yaml (five boxes settling on a floor): the looser the contact velocity tolerance,
// the deeper the boxes sink into each other before the solve stops: 1 s at 3e-5, 1e-2 and 1 m/s.
TEST(ContactToleranceCli, LooserToleranceLetsTheStackSinkDeeper)
{
    TestDir dir;
    double previous = 0.0;
    for (const char* tolerance : {"3e-5", "1e-2", "1"})
    {
        const Result r =
            dir.run(std::string("run scenes/box_stack.yaml --duration 1 --contact-tolerance ") + tolerance);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const double depth = maxPenetration(r.out);
        EXPECT_GT(depth, previous) << "tolerance " << tolerance << ": " << r.out;
        previous = depth;
    }
}

// The flags give the run of a scene whose `contact:` asks the same values, bit for bit; the header
// records them, `check` re-solves with them (position error 0), and a header that asks the scene's
// own tolerance instead makes `check` fail.
TEST(ContactToleranceCli, FlagsEqualTheSceneKeysAndCheckReadsThemFromTheHeader)
{
    TestDir dir;
    std::string scene = readText(sourcePath("scenes/box_stack.yaml"));
    const std::string contact = "contact: {friction: 0.6, restitution: 0.0}";
    ASSERT_NE(scene.find(contact), std::string::npos);
    scene.replace(scene.find(contact), contact.size(),
                  "contact: {friction: 0.6, restitution: 0.0, tolerance: 0.01, relative_tolerance: 0.1}");
    const std::string loose = dir.write("loose.yaml", scene);

    const Result flags = dir.run("run scenes/box_stack.yaml --duration 0.5 --contact-tolerance 0.01 "
                                 "--contact-relative-tolerance 0.1 --trajectory " +
                                 dir.out("flags.csv"));
    ASSERT_EQ(flags.exitCode, 0) << flags.err;
    const Result keys = dir.run("run " + loose + " --duration 0.5 --trajectory " + dir.out("keys.csv"));
    ASSERT_EQ(keys.exitCode, 0) << keys.err;
    const Result plain =
        dir.run("run scenes/box_stack.yaml --duration 0.5 --trajectory " + dir.out("plain.csv"));
    ASSERT_EQ(plain.exitCode, 0) << plain.err;

    const std::string withFlags = readText(dir.out("flags.csv"));
    EXPECT_EQ(rows(withFlags), rows(readText(dir.out("keys.csv"))));
    EXPECT_NE(rows(withFlags), rows(readText(dir.out("plain.csv"))));
    const std::string header = withFlags.substr(0, withFlags.find('\n'));
    EXPECT_NE(header.find(" contact_tolerance=0.01"), std::string::npos) << header;
    EXPECT_NE(header.find(" contact_relative_tolerance=0.10000000000000001"), std::string::npos) << header;

    const Result same = dir.run("check scenes/box_stack.yaml --reference " + dir.out("flags.csv"));
    EXPECT_EQ(same.exitCode, 0) << same.out << same.err;
    EXPECT_NE(same.out.find("largest position error 0 m"), std::string::npos) << same.out;

    std::string tight = withFlags;
    tight.replace(tight.find("contact_tolerance=0.01"), 22, "contact_tolerance=3e-5");
    tight.replace(tight.find("contact_relative_tolerance=0.10000000000000001"), 46,
                  "contact_relative_tolerance=0");
    const Result differs =
        dir.run("check scenes/box_stack.yaml --reference " + dir.write("tight.csv", tight));
    EXPECT_EQ(differs.exitCode, 1) << differs.out << differs.err;
}

TEST(ContactToleranceCli, ValuesOutOfRangeExitTwoNamingTheFlagOrHeader)
{
    TestDir dir;
    for (const std::string& flags :
         std::vector<std::string>{"--contact-tolerance 2", "--contact-tolerance -1e-3",
                                  "--contact-tolerance nan", "--contact-relative-tolerance 1",
                                  "--contact-relative-tolerance -0.5", "--contact-relative-tolerance x"})
    {
        const Result r = dir.run("run scenes/box_stack.yaml --steps 1 " + flags);
        EXPECT_EQ(r.exitCode, 2) << flags << ": " << r.out << r.err;
        EXPECT_NE(r.err.find(flags.substr(0, flags.find(' '))), std::string::npos) << flags << ": " << r.err;
    }
    const Result recorded = dir.run(
        "run scenes/box_stack.yaml --steps 10 --contact-tolerance 0.5 --trajectory " + dir.out("ref.csv"));
    ASSERT_EQ(recorded.exitCode, 0) << recorded.err;
    std::string text = readText(dir.out("ref.csv"));
    text.replace(text.find("contact_tolerance=0.5"), 21, "contact_tolerance=7");
    const std::string bad = dir.write("bad.csv", text);
    const Result r = dir.run("check scenes/box_stack.yaml --reference " + bad);
    EXPECT_EQ(r.exitCode, 2) << r.out << r.err;
    EXPECT_NE(r.err.find("contact_tolerance=7 is not a velocity in [0, 1] m/s"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("bad.csv"), std::string::npos) << r.err;
}

} // namespace
