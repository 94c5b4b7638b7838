// tests/cli/check_cli_test.cpp: `frontier check` against references, clean and perturbed.
#include "app_test_util.h"
#include "io/trajectory.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <sstream>

namespace
{
using frontier::app::test::readText;
using frontier::app::test::Result;
using frontier::app::test::spawnFrontier;
using frontier::app::test::TestDir;
using frontier::app::test::waitForExit;
using frontier::app::test::waitForHandler;

// Records a double pendulum reference: 0.5 s, a row every 5 steps (101 times, 2 bodies).
std::string recordReference(const TestDir& dir)
{
    const Result r = dir.run("run scenes/double_pendulum.yaml --duration 0.5 --record-every 5 --trajectory " +
                             dir.out("ref.csv"));
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return readText(dir.out("ref.csv"));
}

// The same text with one number of the row (time, body) moved by `delta` in column `column`.
std::string perturb(const std::string& text, const std::string& timePrefix, const std::string& body,
                    int column, double delta)
{
    std::istringstream in(text);
    std::string line, out;
    bool done = false;
    while (std::getline(in, line))
    {
        if (!done && line.rfind(timePrefix, 0) == 0 && line.find("," + body + ",") != std::string::npos)
        {
            std::vector<std::string> fields;
            std::stringstream ss(line);
            std::string field;
            while (std::getline(ss, field, ','))
            {
                fields.push_back(field);
            }
            char number[64];
            std::snprintf(number, sizeof number, "%.17g",
                          std::stod(fields[static_cast<std::size_t>(column)]) + delta);
            fields[static_cast<std::size_t>(column)] = number;
            line.clear();
            for (std::size_t k = 0; k < fields.size(); ++k)
            {
                line += (k ? "," : "") + fields[k];
            }
            done = true;
        }
        out += line + "\n";
    }
    EXPECT_TRUE(done) << "no row " << timePrefix << " " << body;
    return out;
}

TEST(CheckCli, ReferenceChecksCleanAgainstItself)
{
    TestDir dir;
    recordReference(dir);
    const Result r = dir.run("check scenes/double_pendulum.yaml --reference " + dir.out("ref.csv"));
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("OK"), std::string::npos);
    EXPECT_NE(r.out.find("largest position error 0 m"), std::string::npos)
        << r.out; // same binary: bit-identical
}

TEST(CheckCli, PerturbedReferenceFailsNamingBodyAndTime)
{
    TestDir dir;
    const std::string text = recordReference(dir);
    // px of 'lower' at t = 0.25 s moved by 1 mm (tolerance 1 micrometre).
    const std::string bad = dir.write("bad.csv", perturb(text, "0.25", "lower", 2, 1e-3));
    const Result r = dir.run("check scenes/double_pendulum.yaml --reference " + bad);
    EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
    EXPECT_NE(r.out.find("first divergence at t = 0.25"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("body 'lower', position"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("error 0.001 m"), std::string::npos) << r.out;
}

TEST(CheckCli, ToleranceFlagDecides)
{
    TestDir dir;
    const std::string text = recordReference(dir);
    const std::string slight = dir.write("slight.csv", perturb(text, "0.25", "upper", 3, 1e-7));
    EXPECT_EQ(dir.run("check scenes/double_pendulum.yaml --reference " + slight).exitCode, 0);
    EXPECT_EQ(dir.run("check scenes/double_pendulum.yaml --tol 1e-8 --reference " + slight).exitCode, 1);
    const std::string spun = dir.write("spun.csv", perturb(text, "0.25", "upper", 13, 1e-3));
    const Result r = dir.run("check scenes/double_pendulum.yaml --reference " + spun);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.out.find("angular velocity"), std::string::npos) << r.out;
}

TEST(CheckCli, ReferenceOfAnotherSceneExitsTwoNamingTheBody)
{
    TestDir dir;
    recordReference(dir);
    const Result r = dir.run("check scenes/pendulum.yaml --reference " + dir.out("ref.csv"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("'upper'"), std::string::npos) << r.err;
}

TEST(CheckCli, MissingColumnExitsTwoNamingIt)
{
    TestDir dir;
    const std::string text = recordReference(dir);
    std::istringstream in(text);
    std::string line, out;
    while (std::getline(in, line))
    {
        if (line[0] != '#')
        {
            line = line.substr(0, line.rfind(',')); // drop wz
        }
        out += line + "\n";
    }
    const Result r = dir.run("check scenes/double_pendulum.yaml --reference " + dir.write("nowz.csv", out));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("'wz'"), std::string::npos) << r.err;
}

TEST(CheckCli, MissingTimesExitTwo)
{
    TestDir dir;
    const std::string text = recordReference(dir);
    const std::size_t at = text.find("\n0.25"); // the first row at t = 0.25 s
    ASSERT_NE(at, std::string::npos);
    const std::string cut = text.substr(0, at); // rows before t = 0.25 s only
    const std::string shortened = dir.write("short.csv", cut + "\n");
    const Result r = dir.run("check scenes/double_pendulum.yaml --reference " + shortened);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("recorded times"), std::string::npos) << r.err;
    // Named at the last row of the file (the line after which times are missing).
    const std::string lastLine = std::to_string(std::count(cut.begin(), cut.end(), '\n') + 1);
    EXPECT_NE(r.err.find(shortened + ":" + lastLine + ":"), std::string::npos) << r.err;
}

// A recorded time that is not the run's: exit 2 naming the reference's file and the row's line.
TEST(CheckCli, WrongRecordedTimeExitsTwoNamingTheLine)
{
    TestDir dir;
    const std::string text = recordReference(dir);
    // Both rows at t = 0.25 s moved to 0.251 s (still between 0.245 and 0.255 s: the file reads).
    const std::string shifted = perturb(perturb(text, "0.25", "upper", 0, 1e-3), "0.25", "lower", 0, 1e-3);
    const std::size_t at = text.find("\n0.25");
    ASSERT_NE(at, std::string::npos);
    const std::string line = std::to_string(std::count(text.begin(), text.begin() + at, '\n') + 2);
    const std::string bad = dir.write("times.csv", shifted);
    const Result r = dir.run("check scenes/double_pendulum.yaml --reference " + bad);
    EXPECT_EQ(r.exitCode, 2) << r.out << r.err;
    EXPECT_NE(r.err.find(bad + ":" + line + ":1: error: the reference's time 0.251"), std::string::npos)
        << r.err;
}

TEST(CheckCli, HeaderWithoutSettingsExitsTwo)
{
    TestDir dir;
    const std::string text = recordReference(dir);
    const std::string bare = text.substr(text.find('\n') + 1); // no "# frontier trajectory:" line
    const Result r = dir.run("check scenes/double_pendulum.yaml --reference " + dir.write("bare.csv", bare));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("header line"), std::string::npos) << r.err;
}

// SIGINT and SIGTERM stop a check between steps: exit 128 + the signal, one line naming the
// signal and saying the check did not finish; nothing written (a check writes no file).
TEST(CheckCli, SignalStopsTheCheck)
{
    for (const int signal : {SIGINT, SIGTERM})
    {
        TestDir dir;
        // A pendulum reference of 10 steps, its header turned into one of 1e8 steps with a row at
        // the start and at the end: the check runs long enough to be interrupted.
        const Result run = dir.run(
            "run scenes/pendulum.yaml --duration 0.01 --record-every 10 --trajectory " + dir.out("ref.csv"));
        ASSERT_EQ(run.exitCode, 0) << run.err;
        std::string text = readText(dir.out("ref.csv"));
        const std::size_t at = text.find("steps=10 record_every=10 ");
        ASSERT_NE(at, std::string::npos) << text;
        text.replace(at, 25, "steps=100000000 record_every=100000000 ");
        const std::string ref = dir.write("long.csv", text);
        const pid_t pid =
            spawnFrontier(dir, {"check", "scenes/pendulum.yaml", "--quiet", "--reference", ref});
        ASSERT_GT(pid, 0);
        ASSERT_TRUE(waitForHandler(pid, signal, 60.0));
        ::kill(pid, signal);
        EXPECT_EQ(waitForExit(pid, 30.0), 128 + signal);
        const std::string err = readText(dir.path() / "stderr.txt");
        EXPECT_EQ(err.rfind("frontier: interrupted by SIG", 0), 0u) << err;
        EXPECT_NE(err.find("; the check did not finish\n"), std::string::npos) << err;
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
        EXPECT_EQ(dir.outputs(), std::vector<std::string>{"ref.csv"});
    }
}

} // namespace
