// Transparent huge pages for the few large arrays a computation fills once (a sampling's diagram
// of a large mesh, the per-triangle records): first touching them costs a page fault per 4 KiB.
#pragma once

#include <cstddef>
#include <cstdint>
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
  constexpr std::uintptr_t huge = std::uintptr_t(2) << 20;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + huge - 1) & ~(huge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(huge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

//! v.reserve(n), the new storage advised to huge pages (advise_huge_pages) before anything
//! touches it.
template <class T, class A>
void reserve_huge(std::vector<T, A>& v, std::size_t n) {
  if (n <= v.capacity()) return;
  v.reserve(n);
  advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

//! v.assign(n, value) into storage advised to huge pages when it has to grow.
template <class T, class A>
void assign_huge(std::vector<T, A>& v, std::size_t n, const T& value) {
  if (n > v.capacity()) {
    std::vector<T, A>().swap(v);  // not copied: the old values go anyway
    reserve_huge(v, n);
  }
  v.assign(n, value);
}

}  // namespace lrvd
