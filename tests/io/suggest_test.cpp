// tests/io/suggest_test.cpp: edit distance and "did you mean".
#include "io/suggest.h"

#include <gtest/gtest.h>

namespace frontier::io::detail
{
namespace
{

TEST(Suggest, EditDistance)
{
    EXPECT_EQ(editDistance("mass", "mass"), 0);
    EXPECT_EQ(editDistance("mas", "mass"), 1);
    EXPECT_EQ(editDistance("dnesity", "density"), 1); // adjacent swap counts once
    EXPECT_EQ(editDistance("kitten", "sitting"), 3);
    EXPECT_EQ(editDistance("", "abc"), 3);
}

TEST(Suggest, ClosestMatch)
{
    const std::vector<std::string> keys = {"mass", "density", "position", "angular_velocity", "velocity"};
    EXPECT_EQ(closestMatch("mas", keys), "mass");
    EXPECT_EQ(closestMatch("postion", keys), "position");
    EXPECT_EQ(closestMatch("angular_vel", keys), "angular_velocity");
    EXPECT_EQ(closestMatch("zzzzzzzz", keys), "");
    EXPECT_EQ(suggestionSuffix("mas", keys, true), "; did you mean 'mass'?");
    EXPECT_EQ(suggestionSuffix("qqqqqqq", {"a", "b"}, true), " (known: a, b)");
}

// A name of megabytes is compared with nothing and quoted cut short; among many candidates the
// closest is still found.
TEST(Suggest, LongWordsAndManyCandidates)
{
    const std::string huge(4 << 20, 'x');
    std::vector<std::string> names(100000);
    for (std::size_t i = 0; i < names.size(); ++i)
    {
        names[i] = "link_" + std::to_string(i);
    }
    names.push_back(huge);
    EXPECT_EQ(closestMatch(huge, names), "");
    EXPECT_EQ(closestMatch("link_9999x", names), "link_9999");
    EXPECT_EQ(editDistance(huge.substr(0, 1000), huge.substr(0, 999)), 1);
    EXPECT_EQ(quotedName("pelvis"), "'pelvis'");
    const std::string quoted = quotedName(huge);
    EXPECT_LT(quoted.size(), 100u);
    EXPECT_NE(quoted.find("...' (4194304 bytes)"), std::string::npos) << quoted;
    // Not cut inside a UTF-8 character: the kept bytes end before the two-byte "é" at 59..60.
    EXPECT_EQ(quotedName(std::string(59, 'a') + "\xc3\xa9" + std::string(40, 'b')),
              "'" + std::string(59, 'a') + "...' (101 bytes)");
}

TEST(Suggest, InvalidNames)
{
    EXPECT_EQ(invalidNameReason("pelvis"), "");
    EXPECT_NE(invalidNameReason(""), "");
    EXPECT_NE(invalidNameReason("world"), "");
    EXPECT_NE(invalidNameReason("a,b"), "");
    EXPECT_NE(invalidNameReason("a\nb"), "");
}

} // namespace
} // namespace frontier::io::detail
