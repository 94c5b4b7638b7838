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
