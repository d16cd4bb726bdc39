// Transparent huge pages for the few large arrays a computation fills once (a sampling's diagram
// of a large mesh, the per-triangle records): first touching them costs a page fault per 4 KiB.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace lrvd {

//! Arrays smaller than this are left to the allocator's pages: a huge page must lie whole inside
//! (one from 2 to 4 MiB holds one or none, as it lies).
constexpr std::size_t kHugePageArrayBytes = std::size_t(2) << 20;

//! Asks the kernel to back the whole 2 MiB pages of [data, data + bytes) with transparent huge
//! pages from their first touch. With THP in "madvise" mode (the default of many distributions)
//! the pages of an array of 50 MB fresh from the allocator would otherwise each fault alone, and
//! where faults are dear (a virtual machine) that is a sixth of a Poisson-disk sampling. A hint
//! only: pages already touched stay as they are, and elsewhere than Linux it does nothing.
inline void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (bytes < kHugePageArrayBytes) return;
  constexpr std::uintptr_t huge = kHugePageArrayBytes;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + huge - 1) & ~(huge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(huge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

//! An allocator for the large arrays internal to a computation (std::vector<T, HugePageAllocator<T>>):
//! storage of kHugePageArrayBytes or more comes 2 MiB-aligned (aligned_alloc) in whole huge pages
//! and is advised to huge pages, so that all of it takes them (with std::allocator the unaligned ends of such an
//! array, up to 2 MiB each, fault page by page); smaller storage comes from std::allocator. Linux
//! only; elsewhere std::allocator throughout.
template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}  // NOLINT: rebinding, as allocators do

  T* allocate(std::size_t n) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (large(n)) {
      // From the allocator, not mmap itself: the leak checker scans what malloc hands out, and a
      // workspace kept for the next diagram holds pointers to the per-triangle lists in here.
      void* storage = std::aligned_alloc(kHugePageArrayBytes, whole_pages_bytes(n));
      if (!storage) throw std::bad_alloc();
      madvise(storage, whole_pages_bytes(n), MADV_HUGEPAGE);
      return static_cast<T*>(storage);
    }
#endif
    return std::allocator<T>().allocate(n);
  }
  void deallocate(T* p, std::size_t n) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (large(n)) {
      std::free(p);
      return;
    }
#endif
    std::allocator<T>().deallocate(p, n);
  }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const { return false; }

 private:
  //! Storage of n values that goes on huge pages of its own (and whose size does not overflow).
  static bool large(std::size_t n) {
    return n * sizeof(T) >= kHugePageArrayBytes && n <= static_cast<std::size_t>(-1) / 2 / sizeof(T);
  }
  //! n values' bytes rounded up to whole huge pages.
  static std::size_t whole_pages_bytes(std::size_t n) {
    return (n * sizeof(T) + kHugePageArrayBytes - 1) / kHugePageArrayBytes * kHugePageArrayBytes;
  }
};

//! A vector whose large storage lies on huge pages of its own (HugePageAllocator).
template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

//! v.reserve(n), the new storage advised to huge pages (advise_huge_pages) before anything
//! touches it.
template <class T, class A>
void reserve_huge(std::vector<T, A>& v, std::size_t n) {
  if (n <= v.capacity()) return;
  v.reserve(n);
  advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

}  // namespace lrvd
