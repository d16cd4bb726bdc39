// Smaller disks where an LRRT has defects (report/lrrt_repair.h).
#include "report/lrrt_repair.h"

#include <algorithm>
#include <limits>

#include "mesh/kd_tree.h"
#include "mesh/self_intersections.h"
#include "remesh/dual_defects.h"

namespace lrvd {

namespace {

struct Positions {
  const std::vector<Vec3>& points;
  std::size_t size() const { return points.size(); }
  const Vec3& operator[](std::size_t i) const { return points[i]; }
};

}  // namespace

std::vector<double> sampled_radius_field(const SurfaceMesh& input, const MpsOptions& options, const MpsResult& result) {
  if (!options.radius_field.empty()) return options.radius_field;
  if (options.adaptive) return adaptive_radius_field(input, result.radius, options);
  return std::vector<double>(input.vertex_count(), result.radius);
}

std::vector<int> lrrt_defect_samples(const SurfaceMesh& input, const MpsResult& result, const Diagram& lrpd,
                                     const DualMesh& dual) {
  const DualDefects defects = find_dual_defects(dual, lrpd, result.mesh, result.samples, input.is_closed());
  return defects.where_to_act();
}

int halve_radius_round(const SurfaceMesh& input, const MpsResult& result, const std::vector<int>& samples,
                       double gradation, std::vector<double>& field) {
  const std::vector<double> before = field;
  const KdPoints<Positions> cloud{Positions{input.positions()}};
  KdTree<Positions> tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  std::vector<std::pair<unsigned, double>> found;
  for (int s : samples) {
    const Vec3& p = result.samples.positions[s];
    const double r = result.radii[s];
    const double query[3] = {p.x, p.y, p.z};
    found.clear();
    tree.radiusSearch(query, kLoweredReach * kLoweredReach * r * r, found, nanoflann::SearchParams(32, 0, false));
    if (found.empty()) {
      unsigned nearest[3];
      double squared[3];
      const std::size_t k = tree.knnSearch(query, std::min<std::size_t>(3, input.positions().size()), nearest, squared);
      for (std::size_t i = 0; i < k; ++i) found.emplace_back(nearest[i], squared[i]);
    }
    for (const auto& [v, squared] : found) field[v] = std::min(field[v], r / 2);
  }
  limit_radius_gradation(input, gradation, field);
  int lowered = 0;
  for (std::size_t v = 0; v < field.size(); ++v) lowered += field[v] < before[v];
  return lowered;
}

std::vector<Vec3> samples_away_from(const MpsResult& result, const std::vector<int>& defects, double gradation) {
  const double reach = kLoweredReach + 0.5 / gradation + 1;
  std::vector<Vec3> kept;
  const Samples& samples = result.samples;
  for (int j = 0; j < samples.size(); ++j) {
    bool away = true;
    for (int d : defects) {
      const double clear = reach * result.radii[d];
      if (squared_distance(samples.positions[j], samples.positions[d]) <= clear * clear) {
        away = false;
        break;
      }
    }
    if (away) kept.push_back(samples.positions[j]);
  }
  return kept;
}

int exclude_feature_samples(const MpsResult& result, const std::vector<int>& samples,
                            std::vector<std::pair<Vec3, double>>& exclusions) {
  int added = 0;
  for (int s : samples)
    if (s >= result.first_samples && s < result.first_samples + result.feature_samples) {
      exclusions.emplace_back(result.samples.positions[s], kLoweredReach * result.radii[s]);
      ++added;
    }
  return added;
}

std::vector<std::pair<int, int>> crossings_within_parts(const SurfaceMesh& input) {
  const std::vector<int>& component = input.triangle_components();
  std::vector<std::pair<int, int>> within;
  for (const auto& [s, t] : find_self_intersections(input.positions(), input.triangles(),
                                                    proper_triangles(input.positions(), input.triangles())))
    if (component[s] == component[t]) within.emplace_back(s, t);
  return within;
}

std::vector<int> away_from_crossings(const SurfaceMesh& input, const MpsResult& result, const std::vector<int>& samples,
                                     const std::vector<std::pair<int, int>>& crossings) {
  // Each crossing triangle as a ball: its centroid and the distance to its farthest corner.
  std::vector<std::pair<Vec3, double>> balls;
  for (const auto& pair : crossings)
    for (int t : {pair.first, pair.second}) {
      const auto& f = input.triangle(t);
      const Vec3 c = (input.position(f[0]) + input.position(f[1]) + input.position(f[2])) / 3.0;
      double reach = 0;
      for (int v : f) reach = std::max(reach, distance(c, input.position(v)));
      balls.emplace_back(c, reach);
    }
  std::vector<int> away;
  for (int s : samples) {
    const Vec3& p = result.samples.positions[s];
    const double margin = kLoweredReach * result.radii[s];
    bool near = false;
    for (const auto& [c, reach] : balls) near = near || distance(p, c) <= reach + margin;
    if (!near) away.push_back(s);
  }
  return away;
}

}  // namespace lrvd
