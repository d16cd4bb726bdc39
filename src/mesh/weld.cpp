// Welding near-coincident points and finding near twins with a k-d tree (nanoflann).
#include "mesh/weld.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mesh/kd_tree.h"

namespace lrvd {

namespace {

// A subset of points (all of them when `subset` is null).
struct PointSubset {
  const std::vector<Vec3>& points;
  const std::vector<int>* subset;
  std::size_t size() const { return subset ? subset->size() : points.size(); }
  const Vec3& operator[](std::size_t i) const { return points[subset ? (*subset)[i] : i]; }
};
using PointCloud = KdPoints<PointSubset>;
using PointTree = KdTree<PointSubset>;

// The tree's radius search compares squared distances with `<`: within the tolerance, excluded.
// A tolerance whose square underflows still takes the points at the same place.
std::vector<std::pair<unsigned, double>> within(const PointTree& tree, const Vec3& p, double tolerance) {
  std::vector<std::pair<unsigned, double>> found;
  const double query[3] = {p.x, p.y, p.z};
  const double squared = std::max(tolerance * tolerance, std::numeric_limits<double>::denorm_min());
  tree.radiusSearch(query, squared, found, nanoflann::SearchParams(32, 0, true));
  return found;
}

}  // namespace

std::vector<int> weld_representatives(const std::vector<Vec3>& points, double tolerance) {
  const int n = static_cast<int>(points.size());
  std::vector<int> representative(n, -1);
  if (!(tolerance > 0)) {
    for (int i = 0; i < n; ++i) representative[i] = i;
    return representative;
  }
  PointCloud cloud{{points, nullptr}};
  PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  for (int i = 0; i < n; ++i) {
    if (representative[i] >= 0) continue;
    representative[i] = i;
    for (const auto& [j, squared] : within(tree, points[i], tolerance))
      if (representative[j] < 0) representative[j] = i;
  }
  return representative;
}

NearTwins find_near_twins(const std::vector<Vec3>& points, const std::vector<int>& candidates, double tolerance,
                          const std::function<bool(int, int)>& joined) {
  NearTwins twins;
  if (candidates.empty() || !(tolerance > 0)) return twins;
  PointCloud cloud{{points, &candidates}};
  PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  for (const int a : candidates) {
    int nearest = -1;
    double nearest_squared = 0;
    for (const auto& [i, squared] : within(tree, points[a], tolerance)) {
      const int b = candidates[i];
      if (b == a || points[b] == points[a] || joined(a, b)) continue;
      twins.max_distance = std::max(twins.max_distance, std::sqrt(squared));
      if (nearest < 0 || squared < nearest_squared || (squared == nearest_squared && b < nearest))
        nearest = b, nearest_squared = squared;
    }
    if (nearest < 0) continue;
    ++twins.count;
    if (twins.a < 0 || a < twins.a) twins.a = a, twins.b = nearest, twins.distance = std::sqrt(nearest_squared);
  }
  return twins;
}

std::vector<TJunction> find_t_junctions(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                                        double tolerance) {
  std::vector<TJunction> found;
  if (!(tolerance >= 0)) return found;
  const auto key = [](int a, int b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint32_t>(std::max(a, b));
  };
  const auto proper = [](const Triangle& t) { return t[0] != t[1] && t[1] != t[2] && t[0] != t[2]; };
  std::unordered_map<std::uint64_t, int> uses;
  uses.reserve(2 * triangles.size());
  for (const Triangle& t : triangles)
    if (proper(t))
      for (int e = 0; e < 3; ++e) ++uses[key(t[e], t[(e + 1) % 3])];
  std::vector<int> corners;  // on the boundary
  std::vector<char> on_boundary(points.size(), 0);
  for (const Triangle& t : triangles)
    if (proper(t))
      for (int e = 0; e < 3; ++e)
        if (uses[key(t[e], t[(e + 1) % 3])] == 1)
          for (int v : {t[e], t[(e + 1) % 3]})
            if (!on_boundary[v]) on_boundary[v] = 1, corners.push_back(v);
  if (corners.empty()) return found;
  PointCloud cloud{{points, &corners}};
  PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
    const Triangle& f = triangles[t];
    if (!proper(f)) continue;
    for (int e = 0; e < 3; ++e) {
      const int a = f[e], b = f[(e + 1) % 3];
      if (uses[key(a, b)] != 1) continue;
      const Vec3 &pa = points[a], &pb = points[b], ab = pb - pa;
      const double length2 = dot(ab, ab);
      if (!(length2 > 0)) continue;
      // The corners within reach of the edge lie in the ball round its midpoint that holds it.
      const double reach = 0.5 * std::sqrt(length2) + tolerance;
      const std::size_t first = found.size();
      for (const auto& [i, squared] : within(tree, 0.5 * (pa + pb), reach)) {
        const int v = corners[i];
        if (v == f[0] || v == f[1] || v == f[2]) continue;
        const Vec3& p = points[v];
        // Its closest point on the edge's line, farther than the tolerance from both ends.
        const double s = dot(p - pa, ab) / length2, length = std::sqrt(length2);
        if (s * length > tolerance && (1 - s) * length > tolerance && distance(p, pa + s * ab) <= tolerance)
          found.push_back({v, t, e, s});
      }
      std::sort(found.begin() + static_cast<std::ptrdiff_t>(first), found.end(),
                [](const TJunction& x, const TJunction& y) { return std::tie(x.along, x.vertex) < std::tie(y.along, y.vertex); });
    }
  }
  return found;
}

int split_at_t_junctions(std::vector<Triangle>& triangles, const std::vector<TJunction>& junctions) {
  int split = 0;
  for (std::size_t i = 0, j; i < junctions.size(); i = j) {
    const int t = junctions[i].triangle, e = junctions[i].edge;
    for (j = i + 1; j < junctions.size() && junctions[j].triangle == t; ++j) {}
    std::size_t end = i;  // this triangle's junctions on its first such edge
    while (end < j && junctions[end].edge == e) ++end;
    const Triangle f = triangles[t];
    const int opposite = f[(e + 2) % 3];
    int from = f[e];
    for (std::size_t k = i; k < end; ++k) {
      const Triangle part{from, junctions[k].vertex, opposite};
      if (k == i)
        triangles[t] = part;
      else
        triangles.push_back(part);
      from = junctions[k].vertex;
    }
    triangles.push_back({from, f[(e + 1) % 3], opposite});
    ++split;
  }
  return split;
}

}  // namespace lrvd
