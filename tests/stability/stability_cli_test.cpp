// tests/stability/stability_cli_test.cpp: `frontier stability` end to end (a child process in a
// per-test folder, tests/app/app_test_util.h).
#include "app/commands.h"
#include "app_test_util.h"

#include <gtest/gtest.h>

namespace frontier::app::test
{
namespace
{

TEST(StabilityCli, WritesTheTable)
{
    TestDir dir;
    const Result r = dir.run(
        "stability scenes/stability/tunnelling_small_step.yaml scenes/stability/tunnelling.yaml "
        "scenes/stability/whip.yaml --duration 0.05 --methods linear/euler,pgs:5/euler --quiet --out " +
        shellQuote(dir.out("table.md")));
    ASSERT_EQ(r.exitCode, cExitOk) << r.err;
    const std::string table = readText(dir.out("table.md"));
    EXPECT_EQ(table, r.out);
    EXPECT_NE(table.find("| scene | linear/euler | pgs:5/euler |"), std::string::npos) << table;
    EXPECT_NE(table.find("| tunnelling_small_step | ok | ok |"), std::string::npos) << table;
    EXPECT_NE(table.find("| tunnelling | ok | ok |"), std::string::npos) << table; // swept: bounces back
    EXPECT_NE(table.find("| whip | ok | **FAILED**: came apart"), std::string::npos) << table;
    EXPECT_TRUE(r.err.empty()) << r.err; // --quiet
}

// --largest-dt adds the table of where each scene ends: the joint limits beyond pi overshoot at 1/30 s
// and 1/60 s (tests/stability/stability_criteria_test.cpp) and hold at 1/120 s.
TEST(StabilityCli, LargestDtTable)
{
    TestDir dir;
    const Result r = dir.run(
        "stability scenes/stability/limit_beyond_pi.yaml --methods linear/euler --largest-dt --quiet");
    ASSERT_EQ(r.exitCode, cExitOk) << r.err;
    EXPECT_NE(r.out.find("Where it ends"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("| limit_beyond_pi | 1/120 s (8.33 ms) |"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("'swung_hinge' within [-4.05, 4.05] rad"), std::string::npos) << r.out;
}

TEST(StabilityCli, BadMethodOrSceneIsBadInput)
{
    TestDir dir;
    Result r = dir.run("stability scenes/stability/tunnelling.yaml --methods linear/verlet");
    EXPECT_EQ(r.exitCode, cExitBadInput);
    EXPECT_NE(r.err.find("bad method 'linear/verlet'"), std::string::npos) << r.err;
    r = dir.run("stability scenes/stability/no_such_scene.yaml");
    EXPECT_EQ(r.exitCode, cExitBadInput);
    EXPECT_NE(r.err.find("no_such_scene.yaml"), std::string::npos) << r.err;
    EXPECT_TRUE(dir.outputs().empty());
}

} // namespace
} // namespace frontier::app::test
