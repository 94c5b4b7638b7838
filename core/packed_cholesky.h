// core/packed_cholesky.h: the small dense kernels of the tree solver (internal to core/):
// Cholesky factors of symmetric pivots kept as packed lower triangles, and solves with them, at
// compile-time sizes so they unroll.
#pragma once

#include "core/fixed_rows.h"

#include <algorithm>
#include <cmath>

namespace frontier::core
{

// Symmetric pivots and their Cholesky factors are stored as lower triangles packed by columns.
// Doubles in an n x n lower triangle:
constexpr int triSize(int n)
{
    return n * (n + 1) / 2;
}
constexpr int cTri6 = triSize(6);

// Index of (i, j), i >= j, in an N x N packed lower triangle.
template <int N> constexpr int tri(int i, int j)
{
    return i + j * (2 * N - j - 1) / 2;
}
inline int tri(int n, int i, int j)
{
    return i + j * (2 * n - j - 1) / 2;
}

// In-place lower Cholesky of the N x N packed symmetric matrix a; the factor's diagonal is
// stored as reciprocals 1 / l_jj (the solves multiply instead of divide). Returns false when a
// pivot falls below cRelativePivot times its own row's diagonal entry (cancellation: dependent
// rows), never producing NaN. Per row, not against the largest diagonal entry: a positive
// definite pivot may span many decades (a long revolute chain's articulated inertia about its
// free axis vs its constrained axes; a light body carrying a heavy subtree) without being
// singular.
constexpr double cRelativePivot = 1e-12;

template <int N> inline bool choleskyInPlace(double* a)
{
    double scale = 0.0;
    FRONTIER_UNROLL
    for (int i = 0; i < N; ++i)
    {
        scale = std::max(scale, std::abs(a[tri<N>(i, i)]));
    }
    if (!(scale > 0.0) || !std::isfinite(scale))
    {
        return false;
    }
    FRONTIER_UNROLL
    for (int j = 0; j < N; ++j)
    {
        const double diagonal = a[tri<N>(j, j)];
        double d = diagonal;
        FRONTIER_UNROLL
        for (int k = 0; k < j; ++k)
        {
            d -= a[tri<N>(j, k)] * a[tri<N>(j, k)];
        }
        if (!(d > cRelativePivot * diagonal))
        {
            return false;
        }
        const double inverse = 1.0 / std::sqrt(d);
        a[tri<N>(j, j)] = inverse;
        FRONTIER_UNROLL
        for (int i = j + 1; i < N; ++i)
        {
            double s = a[tri<N>(i, j)];
            FRONTIER_UNROLL
            for (int k = 0; k < j; ++k)
            {
                s -= a[tri<N>(i, k)] * a[tri<N>(j, k)];
            }
            a[tri<N>(i, j)] = s * inverse;
        }
    }
    return true;
}

// x <- (L L^T)^-1 x for the N x N factor l of choleskyInPlace, on the C columns of the N x C
// column-major x.
template <int N, int C> inline void choleskySolveInPlace(const double* l, double* x)
{
    FRONTIER_UNROLL
    for (int i = 0; i < N; ++i)
    {
        FRONTIER_UNROLL
        for (int c = 0; c < C; ++c)
        {
            double s = x[i + c * N];
            FRONTIER_UNROLL
            for (int k = 0; k < i; ++k)
            {
                s -= l[tri<N>(i, k)] * x[k + c * N];
            }
            x[i + c * N] = s * l[tri<N>(i, i)];
        }
    }
    FRONTIER_UNROLL
    for (int i = N - 1; i >= 0; --i)
    {
        FRONTIER_UNROLL
        for (int c = 0; c < C; ++c)
        {
            double s = x[i + c * N];
            FRONTIER_UNROLL
            for (int k = i + 1; k < N; ++k)
            {
                s -= l[tri<N>(k, i)] * x[k + c * N];
            }
            x[i + c * N] = s * l[tri<N>(i, i)];
        }
    }
}

// (L L^T)^-1 into the N x N column-major `inverse`, for the factor l of choleskyInPlace: with
// M = L^-1 (lower triangular, by forward substitution), (L L^T)^-1 = M^T M. About N^3 / 3
// multiplications, against N^3 for N solves with the identity.
template <int N> inline void choleskyInverse(const double* l, double* inverse)
{
    double m[N][N] = {}; // m[i][j] = M(i, j), i >= j
    FRONTIER_UNROLL
    for (int j = 0; j < N; ++j)
    {
        m[j][j] = l[tri<N>(j, j)]; // the factor keeps 1 / l_jj
        FRONTIER_UNROLL
        for (int i = j + 1; i < N; ++i)
        {
            double s = 0.0;
            FRONTIER_UNROLL
            for (int k = j; k < i; ++k)
            {
                s += l[tri<N>(i, k)] * m[k][j];
            }
            m[i][j] = -s * l[tri<N>(i, i)];
        }
    }
    FRONTIER_UNROLL
    for (int b = 0; b < N; ++b)
    {
        FRONTIER_UNROLL
        for (int a = b; a < N; ++a)
        {
            double s = 0.0;
            FRONTIER_UNROLL
            for (int k = a; k < N; ++k)
            {
                s += m[k][a] * m[k][b];
            }
            inverse[a + b * N] = s;
            inverse[b + a * N] = s;
        }
    }
}

} // namespace frontier::core
