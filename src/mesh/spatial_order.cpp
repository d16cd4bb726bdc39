// Morton order of a point set (spatial_order.h).
#include "mesh/spatial_order.h"

#include <algorithm>
#include <cstdint>
#include <utility>

#include <boost/sort/spreadsort/integer_sort.hpp>

#include "mesh/surface_mesh.h"

namespace lrvd {

namespace {

// Spreads the low 21 bits of x to every third bit.
std::uint64_t spread(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

}  // namespace

std::vector<int> morton_order(const std::vector<Vec3>& points) {
  const int n = static_cast<int>(points.size());
  if (n == 0) return {};
  const BoundingBox box = bounding_box(points);
  const Vec3 &lo = box.min, &hi = box.max;
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  const double cells = (1 << 21) - 1;
  std::vector<std::pair<std::uint64_t, int>> keyed(n);
  for (int i = 0; i < n; ++i) {
    std::uint64_t code = 0;
    for (int c = 0; c < 3; ++c) {
      // Written so that a NaN (an infinite extent) lands in cell 0 instead of an undefined cast.
      const double u = extent > 0 ? (points[i][c] - lo[c]) / extent : 0.0;
      code |= spread(static_cast<std::uint64_t>(u > 0 ? (u < 1 ? u * cells : cells) : 0.0)) << c;
    }
    keyed[i] = {code, i};
  }
  // A radix sort on the code, ties by index: the order std::sort gives the pairs, in less time (the
  // quality metrics sort 400k points on elk 516's remesh, where std::sort took 11 % of lrvd quality).
  using Keyed = std::pair<std::uint64_t, int>;
  boost::sort::spreadsort::integer_sort(
      keyed.begin(), keyed.end(), [](const Keyed& p, unsigned shift) { return p.first >> shift; },
      [](const Keyed& a, const Keyed& b) { return a < b; });
  std::vector<int> order(n);
  for (int k = 0; k < n; ++k) order[k] = keyed[k].second;
  return order;
}

}  // namespace lrvd
