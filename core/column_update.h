// core/column_update.h: the innermost loop of the contact Gauss-Seidel (core/extra_rows_solve.cpp),
// v += G(:, c0) d0 + G(:, c1) d1 + G(:, c2) d2 over a run of rows.
//
// The build has no -march flags (Eigen's alignment must match Debian's libfcl), so
// Eigen runs this loop two doubles wide (SSE2). Where the processor has AVX2 a four-wide copy
// runs instead, chosen once at run time. Both compute each element as v + ((c0 d0 + c1 d1) + c2 d2)
// with separate multiplies and adds (no fused multiply-add), so they give bit-identical results:
// trajectories do not depend on which copy ran.
#pragma once

#include <cstddef>

namespace frontier::core
{

// The kernels for this processor, chosen once:
//   three(v, c0, c1, c2, d0, d1, d2, n): v[i] += (c0[i] d0 + c1[i] d1) + c2[i] d2 for i in [0, n)
//   one(v, c0, d0, n):                   v[i] += c0[i] d0
struct ColumnKernels
{
    void (*three)(double* v, const double* c0, const double* c1, const double* c2, double d0, double d1,
                  double d2, std::ptrdiff_t n);
    void (*one)(double* v, const double* c0, double d0, std::ptrdiff_t n);
};
const ColumnKernels& columnKernels();

// True when the AVX2 copies run on this processor.
bool columnUpdateUsesAvx2();

namespace detail
{
// The copies, for tests; the Avx2 ones only where columnUpdateUsesAvx2().
void addThreeColumnsPortable(double* v, const double* c0, const double* c1, const double* c2, double d0,
                             double d1, double d2, std::ptrdiff_t n);
void addThreeColumnsAvx2(double* v, const double* c0, const double* c1, const double* c2, double d0,
                         double d1, double d2, std::ptrdiff_t n);
void addOneColumnPortable(double* v, const double* c0, double d0, std::ptrdiff_t n);
void addOneColumnAvx2(double* v, const double* c0, double d0, std::ptrdiff_t n);
} // namespace detail

} // namespace frontier::core
