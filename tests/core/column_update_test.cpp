// tests/core/column_update_test.cpp: the Gauss-Seidel column update (core/column_update.h): the
// AVX2 copy gives the same bits as the portable one, and both give v + ((c0 d0 + c1 d1) + c2 d2)
// as written out element by element here.
#include "core/column_update.h"

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace frontier::test
{

namespace
{

struct Columns
{
    std::vector<double> v, c0, c1, c2;
};

// Values over many orders of magnitude and both signs, so that round-off differs between
// evaluation orders and a reordering would show.
Columns randomColumns(std::ptrdiff_t n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-12, 3);
    auto value = [&]
    {
        const int e = exponent(rng); // one draw per statement: argument order is the compiler's
        return std::ldexp(mantissa(rng), e);
    };
    Columns c;
    for (std::vector<double>* x : {&c.v, &c.c0, &c.c1, &c.c2})
    {
        x->resize(static_cast<std::size_t>(n));
        for (double& e : *x)
        {
            e = value();
        }
    }
    return c;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b)
{
    // (memcmp is not called on empty vectors: their data() may be null)
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

} // namespace

TEST(ColumnUpdate, PortableCopyAddsInTheStatedOrder)
{
    // Every length up to 37, so both the vector body and the tail are covered.
    for (std::ptrdiff_t n = 0; n <= 37; ++n)
    {
        const Columns c = randomColumns(n, static_cast<unsigned>(n) + 1);
        const double d0 = 0.37, d1 = -1.3e-3, d2 = 2.5e4;
        std::vector<double> three = c.v;
        std::vector<double> one = c.v;
        core::detail::addThreeColumnsPortable(three.data(), c.c0.data(), c.c1.data(), c.c2.data(), d0, d1, d2,
                                              n);
        core::detail::addOneColumnPortable(one.data(), c.c0.data(), d0, n);
        for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i)
        {
            volatile double a = c.c0[i] * d0; // volatile: no fused multiply-add in the reference
            volatile double b = c.c1[i] * d1;
            volatile double e = c.c2[i] * d2;
            const double pair = a + b;
            const double sum = pair + e;
            EXPECT_EQ(three[i], c.v[i] + sum) << "n " << n << " i " << i;
            EXPECT_EQ(one[i], c.v[i] + a) << "n " << n << " i " << i;
        }
    }
}

TEST(ColumnUpdate, Avx2CopyGivesTheSameBitsAsThePortableOne)
{
    if (!core::columnUpdateUsesAvx2())
    {
        GTEST_SKIP() << "this processor has no AVX2";
    }
    for (std::ptrdiff_t n : {0, 1, 3, 4, 5, 7, 8, 63, 64, 65, 237})
    {
        const Columns c = randomColumns(n, 100u + static_cast<unsigned>(n));
        const double d0 = -0.71, d1 = 3.3e-5, d2 = 1.9;
        std::vector<double> portable = c.v;
        std::vector<double> avx2 = c.v;
        core::detail::addThreeColumnsPortable(portable.data(), c.c0.data(), c.c1.data(), c.c2.data(), d0, d1,
                                              d2, n);
        core::detail::addThreeColumnsAvx2(avx2.data(), c.c0.data(), c.c1.data(), c.c2.data(), d0, d1, d2, n);
        EXPECT_TRUE(sameBits(portable, avx2)) << "three columns, n = " << n;
        portable = c.v;
        avx2 = c.v;
        core::detail::addOneColumnPortable(portable.data(), c.c0.data(), d0, n);
        core::detail::addOneColumnAvx2(avx2.data(), c.c0.data(), d0, n);
        EXPECT_TRUE(sameBits(portable, avx2)) << "one column, n = " << n;
    }
}

} // namespace frontier::test
