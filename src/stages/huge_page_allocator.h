// A std::vector allocator that asks Linux for transparent huge pages on
// large arrays (the wide BVH's nodes and leaf blocks).
//
// Why: an incoherent ray touches a few nodes and leaf blocks scattered over
// several megabytes (the beast's 8-wide tree and blocks: about 8 MB, some
// 2,000 pages of 4 KB, about as many as the second-level TLB holds), so many
// of its loads also miss the TLB. With 2 MB pages the same data spans four
// TLB entries. Arrays of at least kHugeFrom bytes are allocated 2 MB-aligned
// (rounded up to whole 2 MB pages) and marked MADV_HUGEPAGE before they are
// written, so the kernel backs them with huge pages when it has them (Linux,
// transparent_hugepage "madvise" or "always"); elsewhere, or when the advice
// fails, they are ordinary memory. Smaller arrays use operator new.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pt {

template <class T>
struct HugePageAllocator {
    using value_type = T;
    static constexpr size_t kHugePage = size_t(2) << 20;
    static constexpr size_t kHugeFrom = size_t(1) << 20;

    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) {}

    T* allocate(size_t n) {
        const size_t bytes = n * sizeof(T);
        if (bytes < kHugeFrom) return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
        const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
        void* p = std::aligned_alloc(kHugePage, rounded);
        if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        madvise(p, rounded, MADV_HUGEPAGE);  // advice only: failure leaves ordinary pages
#endif
        return static_cast<T*>(p);
    }

    void deallocate(T* p, size_t n) {
        if (n * sizeof(T) < kHugeFrom) ::operator delete(p, std::align_val_t(alignof(T)));
        else std::free(p);
    }

    template <class U>
    bool operator==(const HugePageAllocator<U>&) const { return true; }
    template <class U>
    bool operator!=(const HugePageAllocator<U>&) const { return false; }
};

}  // namespace pt
