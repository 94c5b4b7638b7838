// tests/app/info_test.cpp: `frontier info` on the falling doll: counts, rows, degrees of freedom,
// the frontier order, loops and collision pairs, in JSON; the text form runs.
#include "app_test_util.h"
#include "info_test_util.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

namespace frontier::app::test
{
namespace
{

// Rows per joint type (docs/method.md §2), written out here rather than taken from core.
const std::map<std::string, int> cRowsByType = {{"ball", 3},  {"nail", 3},        {"revolute", 5},
                                                {"angle", 4}, {"cylindrical", 4}, {"prismatic", 5},
                                                {"fixed", 6}};

TEST(Info, FallingDollJson)
{
    const TestDir dir;
    const Result r = dir.run("info scenes/falling_doll.yaml --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    nlohmann::json info;
    ASSERT_NO_THROW(info = nlohmann::json::parse(r.out)) << r.out;

    ASSERT_EQ(info.at("bodies").size(), 16u);
    ASSERT_EQ(info.at("joints").size(), 14u);
    std::set<std::string> moving;
    std::set<std::string> statics;
    for (const auto& body : info.at("bodies"))
    {
        (body.at("static").get<bool>() ? statics : moving).insert(body.at("name").get<std::string>());
    }
    EXPECT_EQ(moving.size(), 15u);
    EXPECT_EQ(statics, std::set<std::string>{"floor"});

    int rows = 0;
    std::set<std::string> joints;
    for (const auto& joint : info.at("joints"))
    {
        const std::string type = joint.at("type").get<std::string>();
        ASSERT_TRUE(cRowsByType.count(type)) << type;
        EXPECT_EQ(joint.at("rows").get<int>(), cRowsByType.at(type)) << joint.dump();
        EXPECT_FALSE(joint.at("loop").get<bool>()) << joint.dump();
        rows += cRowsByType.at(type);
        joints.insert(joint.at("name").get<std::string>());
    }
    // 4 ball (3), 6 revolute (5), 4 angle (4).
    EXPECT_EQ(rows, 4 * 3 + 6 * 5 + 4 * 4);
    EXPECT_EQ(info.at("constraint_rows").get<int>(), rows);
    EXPECT_EQ(info.at("degrees_of_freedom").get<int>(), 6 * 15 - rows);
    EXPECT_TRUE(info.at("loops").empty()) << info.at("loops").dump();

    // The frontier order: every moving body and every (tree) joint exactly once, nothing else.
    std::multiset<std::string> listed;
    for (const auto& entry : info.at("frontier_order"))
    {
        listed.insert(entry.get<std::string>());
    }
    std::multiset<std::string> expected;
    for (const std::string& body : moving)
    {
        expected.insert("body " + body);
    }
    for (const std::string& joint : joints)
    {
        expected.insert("joint " + joint);
    }
    EXPECT_EQ(listed, expected);
    // Node 1, edge 1, node 2, ...: alternating, ending at the root body.
    const auto& order = info.at("frontier_order");
    ASSERT_EQ(order.size(), 29u);
    for (std::size_t k = 0; k < order.size(); ++k)
    {
        EXPECT_EQ(order[k].get<std::string>().rfind(k % 2 == 0 ? "body " : "joint ", 0), 0u) << order.dump();
    }

    const nlohmann::json& pairs = info.at("collision_pairs");
    EXPECT_FALSE(hasPair(pairs, "chest", "head")); // jointed (neck)
    EXPECT_FALSE(hasPair(pairs, "pelvis", "chest"));
    EXPECT_FALSE(hasPair(pairs, "forearm_left", "hand_left"));
    EXPECT_TRUE(hasPair(pairs, "hand_left", "floor"));
    EXPECT_TRUE(hasPair(pairs, "head", "floor"));
    EXPECT_TRUE(hasPair(pairs, "hand_left", "thigh_left")); // not jointed, may touch
    // No pair joined by a joint, none twice.
    std::set<std::pair<std::string, std::string>> seen;
    for (const auto& joint : info.at("joints"))
    {
        EXPECT_FALSE(
            hasPair(pairs, joint.at("parent").get<std::string>(), joint.at("child").get<std::string>()))
            << joint.dump();
    }
    for (const auto& pair : pairs)
    {
        std::string a = pair.at(0).get<std::string>();
        std::string b = pair.at(1).get<std::string>();
        if (b < a)
        {
            std::swap(a, b);
        }
        EXPECT_TRUE(seen.insert({a, b}).second) << pair.dump();
    }
}

TEST(Info, TextModeRuns)
{
    const TestDir dir;
    const Result r = dir.run("info scenes/falling_doll.yaml");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("frontier order"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("degrees of freedom: 32"), std::string::npos) << r.out;
}

// Damping and friction are shown for the joints that have them, and only there.
TEST(Info, ShowsJointDampingAndFriction)
{
    const TestDir dir;
    const std::string scene = dir.write("damped.yaml", R"(
bodies:
  - {name: rod, shape: {type: box, size: [0.5, 0.04, 0.04]}, mass: 1, position: [0.25, 0, 1]}
  - {name: slider, shape: {type: box, size: [0.1, 0.1, 0.1]}, mass: 2, position: [0, 1, 1]}
  - {name: ball, shape: {type: sphere, radius: 0.1}, mass: 1, position: [0, 2, 1]}
joints:
  - {name: hinge, type: revolute, parent: world, child: rod, anchor: [0, 0, 1], axis: [0, 1, 0], damping: 0.25, friction: 0.5}
  - {name: rail, type: prismatic, parent: world, child: slider, anchor: [0, 1, 1], axis: [1, 0, 0], friction: 3}
  - {name: pin, type: ball, parent: world, child: ball, anchor: [0, 2, 1.1]}
)");
    const Result json = dir.run("info " + scene + " --json");
    ASSERT_EQ(json.exitCode, 0) << json.err;
    const nlohmann::json info = nlohmann::json::parse(json.out);
    const nlohmann::json& joints = info.at("joints");
    ASSERT_EQ(joints.size(), 3u);
    EXPECT_EQ(joints[0].at("damping").get<double>(), 0.25);
    EXPECT_EQ(joints[0].at("friction").get<double>(), 0.5);
    EXPECT_FALSE(joints[1].contains("damping"));
    EXPECT_EQ(joints[1].at("friction").get<double>(), 3.0);
    EXPECT_FALSE(joints[2].contains("damping"));
    EXPECT_FALSE(joints[2].contains("friction"));

    const Result text = dir.run("info " + scene);
    ASSERT_EQ(text.exitCode, 0) << text.err;
    EXPECT_NE(text.out.find("damping 0.25 N m s/rad  friction 0.5 N m"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("rail  prismatic (5 rows)  world -> slider  friction 3 N\n"), std::string::npos)
        << text.out;
}

// A chain of 1 500 boxes has about 1.1 million collision pairs: `info` gives their count (all pairs
// less the 1 499 joined ones) and does not list them; the doll's few are still listed.
TEST(Info, LargeChainCountsItsPairsInsteadOfListingThem)
{
    constexpr long long n = 1500;
    std::string text = "bodies:\n";
    for (long long i = 0; i < n; ++i)
    {
        text += "  - {name: link" + std::to_string(i) +
                ", shape: {type: box, size: [0.08, 0.02, 0.02]}, mass: 0.1, position: [" +
                std::to_string(0.1 * i) + ", 0, 2]}\n";
    }
    text += "joints:\n";
    for (long long i = 1; i < n; ++i)
    {
        text += "  - {name: j" + std::to_string(i) + ", type: ball, parent: link" + std::to_string(i - 1) +
                ", child: link" + std::to_string(i) + ", anchor: [" + std::to_string(0.1 * i - 0.05) +
                ", 0, 2]}\n";
    }
    const TestDir dir;
    const std::string scene = dir.write("chain.yaml", text);
    const Result json = dir.run("info " + scene + " --json");
    ASSERT_EQ(json.exitCode, 0) << json.err;
    const nlohmann::json info = nlohmann::json::parse(json.out);
    EXPECT_EQ(info.at("collision_pair_count").get<long long>(), n * (n - 1) / 2 - (n - 1));
    EXPECT_FALSE(info.contains("collision_pairs"));
    const Result plain = dir.run("info " + scene);
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    EXPECT_NE(plain.out.find("collision pairs: 1122751 (not listed"), std::string::npos);
    EXPECT_EQ(plain.out.find("link0 - link2\n"), std::string::npos);

    const Result doll = dir.run("info scenes/falling_doll.yaml --json");
    ASSERT_EQ(doll.exitCode, 0) << doll.err;
    const nlohmann::json small = nlohmann::json::parse(doll.out);
    EXPECT_EQ(small.at("collision_pair_count").get<std::size_t>(), small.at("collision_pairs").size());
}

} // namespace
} // namespace frontier::app::test
