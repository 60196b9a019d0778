// Large arrays on 2 MiB pages where Linux offers them (machinery, not part of the article;
// issue 50). A ray's walk and a light sample read the triangles, the light table and the
// CPU's wide BVH at random places: on a million-triangle mesh each read is a cache miss and,
// on 4 KiB pages, a TLB miss as well (the TLB of a desktop core covers a few MB). Linux backs
// memory with 2 MiB pages (transparent huge pages) where the program asks with
// madvise(MADV_HUGEPAGE), which is how Debian sets it up ("madvise" in
// /sys/kernel/mm/transparent_hugepage/enabled), and how Embree allocates its own BVH.
// HugePageAllocator asks for every allocation of 2 MiB or more, aligned to 2 MiB, before the
// memory is first touched; smaller ones, and systems without madvise, get plain memory. The
// values stored are the same either way: only their addresses' pages differ.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pt {

constexpr std::size_t kHugePage = std::size_t(2) << 20;

template <class T> struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U> HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  // Whether n elements go on huge pages (allocate and deallocate must agree).
  static bool huge(std::size_t n) { return n * sizeof(T) >= kHugePage; }

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (!huge(n)) return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE);  // a hint: refused (no THP), the memory is as usable
#endif
    return static_cast<T*>(p);
  }

  void deallocate(T* p, std::size_t n) noexcept {
    if (huge(n)) {
      std::free(p);
    } else {
      ::operator delete(p, std::align_val_t(alignof(T)));
    }
  }

  template <class U> bool operator==(const HugePageAllocator<U>&) const noexcept { return true; }
  template <class U> bool operator!=(const HugePageAllocator<U>&) const noexcept { return false; }
};

// A std::vector whose storage of 2 MiB or more lies on huge pages where the system gives them.
template <class T> using HugeVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace pt
