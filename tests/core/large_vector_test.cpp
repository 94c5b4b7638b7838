// tests/core/large_vector_test.cpp: the huge-page allocator of the solver's arrays
// (core/large_vector.h) keeps values, alignment and the ordinary path for small arrays.
#include "core/joints/joint_rows.h"
#include "core/large_vector.h"

#include <cstdint>
#include <gtest/gtest.h>

namespace frontier::core
{
namespace
{

std::uintptr_t address(const void* p)
{
    return reinterpret_cast<std::uintptr_t>(p);
}

TEST(LargeVector, LargeArraysStartOnAHugePageAndKeepTheirValuesWhenTheyGrow)
{
    LargeVector<double> v;
    for (int i = 0; i < 300000; ++i) // 2.4 MB: crosses the 2 MiB line while growing
    {
        v.push_back(0.5 * i);
    }
    EXPECT_EQ(address(v.data()) % cHugePageBytes, 0u);
    for (int i = 0; i < 300000; ++i)
    {
        ASSERT_EQ(v[static_cast<std::size_t>(i)], 0.5 * i);
    }
}

TEST(LargeVector, SmallArraysAndEigenBlocksKeepTheirAlignment)
{
    LargeVector<Vec6> small(3, Vec6::Constant(2.0));
    EXPECT_EQ(address(small.data()) % alignof(Vec6), 0u);
    LargeVector<Vec6> large(cHugePageBytes / sizeof(Vec6) + 1, Vec6::Constant(1.0));
    EXPECT_EQ(address(large.data()) % cHugePageBytes, 0u);
    large[large.size() - 1] += small[2];
    EXPECT_EQ(large.back()(5), 3.0);
    LargeVector<Vec6> copy = large;
    EXPECT_EQ(copy.back()(0), 3.0);
}

} // namespace
} // namespace frontier::core
