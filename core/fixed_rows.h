// core/fixed_rows.h: dispatch from a run-time row count (1..6) to code compiled for that size,
// so the small dense kernels of the tree solver unroll (internal to core/).
#pragma once

#include <stdexcept>
#include <type_traits>

// Full unrolling of the kernels' loops over block rows (at most 6): -O2 alone keeps them as
// loops with a counter, which costs as much as the arithmetic at these sizes.
#if defined(__clang__) || defined(__GNUC__)
#define FRONTIER_UNROLL _Pragma("GCC unroll 8")
#else
#define FRONTIER_UNROLL
#endif

namespace frontier::core
{

// Calls f(std::integral_constant<int, rows>) for rows = 1..6.
template <typename F> inline void withRows(int rows, F&& f)
{
    switch (rows)
    {
    case 1:
        f(std::integral_constant<int, 1>{});
        return;
    case 2:
        f(std::integral_constant<int, 2>{});
        return;
    case 3:
        f(std::integral_constant<int, 3>{});
        return;
    case 4:
        f(std::integral_constant<int, 4>{});
        return;
    case 5:
        f(std::integral_constant<int, 5>{});
        return;
    case 6:
        f(std::integral_constant<int, 6>{});
        return;
    default:
        throw std::logic_error("tree solver: a joint block must have 1 to 6 rows");
    }
}

} // namespace frontier::core
