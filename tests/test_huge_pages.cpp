// The huge-page storage of large arrays (common/huge_pages.h): a vector on HugePageAllocator keeps
// its values through growth like any vector, and its large storage starts on a 2 MiB boundary.
#include <catch2/catch.hpp>

#include <cstdint>
#include <numeric>
#include <vector>

#include "common/huge_pages.h"

TEST_CASE("A HugePageVector grows, copies and frees like std::vector, large storage 2 MiB-aligned", "[huge_pages]") {
  lrvd::HugePageVector<std::int64_t> v;
  std::vector<std::int64_t> reference;
  for (std::int64_t k = 0; k < 3'000'000; ++k) {  // through small and large storage, 24 MB at the end
    v.push_back(k * 7 - 3);
    reference.push_back(k * 7 - 3);
  }
  REQUIRE(std::equal(v.begin(), v.end(), reference.begin(), reference.end()));
#if defined(__linux__)
  CHECK(reinterpret_cast<std::uintptr_t>(v.data()) % (std::uintptr_t(2) << 20) == 0);
#endif
  lrvd::HugePageVector<std::int64_t> copy = v;
  v.assign(10, 1);
  v.shrink_to_fit();
  CHECK(std::accumulate(v.begin(), v.end(), std::int64_t(0)) == 10);
  REQUIRE(std::equal(copy.begin(), copy.end(), reference.begin(), reference.end()));
}

TEST_CASE("reserve_huge keeps the values and makes room for at least the count asked", "[huge_pages]") {
  std::vector<double> v(1000);
  std::iota(v.begin(), v.end(), 0.5);
  lrvd::reserve_huge(v, 1'000'000);
  CHECK(v.capacity() >= 1'000'000);
  REQUIRE(v.size() == 1000);
  for (int k = 0; k < 1000; ++k) REQUIRE(v[k] == k + 0.5);
  lrvd::reserve_huge(v, 10);  // never shrinks
  CHECK(v.capacity() >= 1'000'000);
}
