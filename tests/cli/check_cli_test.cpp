// tests/cli/check_cli_test.cpp: `frontier check` against references, clean and perturbed.
#include "app_test_util.h"
#include "io/trajectory.h"

#include <gtest/gtest.h>
#include <sstream>

namespace
{
using frontier::app::test::readText;
using frontier::app::test::Result;
using frontier::app::test::TestDir;

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
    const Result r =
        dir.run("check scenes/double_pendulum.yaml --reference " + dir.write("short.csv", cut + "\n"));
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("recorded times"), std::string::npos) << r.err;
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

} // namespace
