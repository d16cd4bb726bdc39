// Welding near-coincident points and finding near twins with a k-d tree (nanoflann).
#include "mesh/weld.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include <nanoflann.hpp>

namespace lrvd {

namespace {

// nanoflann's view of a subset of points (all of them when `subset` is null).
struct PointCloud {
  const std::vector<Vec3>& points;
  const std::vector<int>* subset;
  std::size_t kdtree_get_point_count() const { return subset ? subset->size() : points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const {
    const Vec3& p = points[subset ? (*subset)[i] : i];
    return dim == 0 ? p.x : (dim == 1 ? p.y : p.z);
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>, PointCloud, 3>;

// The tree's radius search compares squared distances with `<`: within the tolerance, excluded.
// A tolerance whose square underflows still takes the points at the same place.
std::vector<std::pair<unsigned, double>> within(const KdTree& tree, const Vec3& p, double tolerance) {
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
  PointCloud cloud{points, nullptr};
  KdTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
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
  PointCloud cloud{points, &candidates};
  KdTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
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

}  // namespace lrvd
