// Arrays of many megabytes that are written in full right after they are made (the environment
// table's texels and cumulative distributions): allocated on 2 MiB boundaries with transparent
// huge pages advised, and left uninitialised by resize (no zeroing pass before the real one).
// A 4 KiB page costs a page fault on its first touch, about 10 us on this project's virtual
// machines: a 32 MB array took about 95 ms to fault in, against 3 ms in 2 MiB pages
// (docs/PERFORMANCE.md, "The environment light"). Where the kernel gives no huge pages the advice
// is ignored and the array is an ordinary one.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

#include <sys/mman.h>

namespace gpurt {

template <typename T>
struct LargeAllocator {
    using value_type = T;
    static constexpr size_t kHugePage = size_t(2) << 20;

    LargeAllocator() = default;
    template <typename U>
    LargeAllocator(const LargeAllocator<U>&) noexcept {}

    T* allocate(size_t n) {
        const size_t bytes = n * sizeof(T);
        if (bytes < kHugePage) return static_cast<T*>(::operator new(bytes));
        const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
        void* p = std::aligned_alloc(kHugePage, rounded);
        if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
        madvise(p, rounded, MADV_HUGEPAGE);  // advice: without huge pages it is a no-op
#endif
        return static_cast<T*>(p);
    }
    void deallocate(T* p, size_t n) noexcept {
        if (n * sizeof(T) < kHugePage) ::operator delete(p);
        else std::free(p);
    }
    // Default-initialise: resize(n) leaves trivial elements (floats, glm vectors) unwritten.
    template <typename U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;
    }
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    friend bool operator==(const LargeAllocator&, const LargeAllocator&) { return true; }
};

template <typename T>
using LargeArray = std::vector<T, LargeAllocator<T>>;

}  // namespace gpurt
