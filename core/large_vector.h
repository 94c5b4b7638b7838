// core/large_vector.h: std::vector for the solver's per-body arrays, backed by transparent huge
// pages once an array reaches 2 MiB.
//
// Why: at 100 000 bodies the factorization streams about 200 MB (the factors, the joint rows,
// masses, right-hand sides) and reaches a far parent block at every branching edge. With 4 KiB
// pages that is some 50 000 pages, far more than the TLB holds, so a miss in the cache is often
// a page walk as well. Arrays of 2 MiB or more are allocated 2 MiB-aligned and their whole huge
// pages marked MADV_HUGEPAGE (Linux: honoured when /sys/kernel/mm/transparent_hugepage/enabled is
// `always` or `madvise`, the Debian default; elsewhere a no-op). The last, partial 2 MiB of an
// array is left to small pages: a huge page there would be resident whole, up to 2 MiB more
// memory per array (a simulator of 64 000 bodies has some 25 such arrays). Smaller arrays, the
// common case for scenes of tens of bodies, use the ordinary allocator. The values stored are
// unaffected.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace frontier::core
{

inline constexpr std::size_t cHugePageBytes = std::size_t{2} << 20; // 2 MiB

template <class T> struct HugePageAllocator
{
    using value_type = T;

    HugePageAllocator() = default;
    template <class U> HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

    T* allocate(std::size_t n)
    {
        if (n * sizeof(T) < cHugePageBytes)
        {
            return std::allocator<T>().allocate(n);
        }
        const std::size_t bytes = n * sizeof(T);
        void* p = nullptr;
        if (posix_memalign(&p, cHugePageBytes, bytes) != 0 || p == nullptr)
        {
            throw std::bad_alloc();
        }
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        // Advice only (failure leaves small pages), for the whole huge pages of the array.
        madvise(p, bytes / cHugePageBytes * cHugePageBytes, MADV_HUGEPAGE);
#endif
        return static_cast<T*>(p);
    }

    void deallocate(T* p, std::size_t n) noexcept
    {
        if (n * sizeof(T) < cHugePageBytes)
        {
            std::allocator<T>().deallocate(p, n);
            return;
        }
        std::free(p);
    }

    template <class U> bool operator==(const HugePageAllocator<U>&) const noexcept
    {
        return true;
    }
};

template <class T> using LargeVector = std::vector<T, HugePageAllocator<T>>;

} // namespace frontier::core
