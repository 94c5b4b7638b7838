// core/column_update.cpp: the Gauss-Seidel column update, portable (Eigen, SSE2) and AVX2 copies
// (see the header).
#include "core/column_update.h"

#include <Eigen/Core>
#include <immintrin.h>

namespace frontier::core
{

namespace detail
{

// Element by element (the compiler keeps the order: no -ffast-math, no FMA in the base ISA); Eigen's
// two-wide kernels compute the same sums, and are faster on long runs: used from 8 rows on.
using ConstColumn = Eigen::Map<const Eigen::VectorXd>;
constexpr std::ptrdiff_t cShortRun = 8;

void addThreeColumnsPortable(double* v, const double* c0, const double* c1, const double* c2, double d0,
                             double d1, double d2, std::ptrdiff_t n)
{
    if (n >= cShortRun)
    {
        Eigen::Map<Eigen::VectorXd>(v, n) +=
            ConstColumn(c0, n) * d0 + ConstColumn(c1, n) * d1 + ConstColumn(c2, n) * d2;
        return;
    }
    for (std::ptrdiff_t i = 0; i < n; ++i)
    {
        v[i] += (c0[i] * d0 + c1[i] * d1) + c2[i] * d2;
    }
}

void addOneColumnPortable(double* v, const double* c0, double d0, std::ptrdiff_t n)
{
    if (n >= cShortRun)
    {
        Eigen::Map<Eigen::VectorXd>(v, n) += ConstColumn(c0, n) * d0;
        return;
    }
    for (std::ptrdiff_t i = 0; i < n; ++i)
    {
        v[i] += c0[i] * d0;
    }
}

// AVX2 without FMA: the same multiplies and adds in the same order as the portable copies; the
// last n mod 4 elements by the portable copy's element-by-element loop (fewer than cShortRun).
__attribute__((target("avx2"))) void addThreeColumnsAvx2(double* v, const double* c0, const double* c1,
                                                         const double* c2, double d0, double d1, double d2,
                                                         std::ptrdiff_t n)
{
    const __m256d s0 = _mm256_set1_pd(d0);
    const __m256d s1 = _mm256_set1_pd(d1);
    const __m256d s2 = _mm256_set1_pd(d2);
    std::ptrdiff_t i = 0;
    for (; i + 4 <= n; i += 4)
    {
        const __m256d pair = _mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(c0 + i), s0),
                                           _mm256_mul_pd(_mm256_loadu_pd(c1 + i), s1));
        const __m256d sum = _mm256_add_pd(pair, _mm256_mul_pd(_mm256_loadu_pd(c2 + i), s2));
        _mm256_storeu_pd(v + i, _mm256_add_pd(_mm256_loadu_pd(v + i), sum));
    }
    addThreeColumnsPortable(v + i, c0 + i, c1 + i, c2 + i, d0, d1, d2, n - i); // < 4 left: one by one
}

__attribute__((target("avx2"))) void addOneColumnAvx2(double* v, const double* c0, double d0,
                                                      std::ptrdiff_t n)
{
    const __m256d s0 = _mm256_set1_pd(d0);
    std::ptrdiff_t i = 0;
    for (; i + 4 <= n; i += 4)
    {
        _mm256_storeu_pd(v + i,
                         _mm256_add_pd(_mm256_loadu_pd(v + i), _mm256_mul_pd(_mm256_loadu_pd(c0 + i), s0)));
    }
    addOneColumnPortable(v + i, c0 + i, d0, n - i); // < 4 left: one by one
}

} // namespace detail

bool columnUpdateUsesAvx2()
{
    static const bool avx2 = __builtin_cpu_supports("avx2");
    return avx2;
}

const ColumnKernels& columnKernels()
{
    static const ColumnKernels kernels =
        columnUpdateUsesAvx2() ? ColumnKernels{detail::addThreeColumnsAvx2, detail::addOneColumnAvx2}
                               : ColumnKernels{detail::addThreeColumnsPortable, detail::addOneColumnPortable};
    return kernels;
}

} // namespace frontier::core
