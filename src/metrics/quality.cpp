// Remesh quality metrics (paper §5): triangle shape from the corner positions, distances from
// points drawn on each surface to the other through Embree closest-point queries.
#include "metrics/quality.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/error.h"
#include "mesh/closest_point.h"
#include "mesh/spatial_order.h"
#include "predicates/predicates.h"
#include "samples/samples.h"

namespace lrvd {

namespace {

constexpr double kPi = 3.14159265358979323846;

//! Throws when a triangle names a vertex that does not exist or a used vertex is not finite:
//! the metrics of such a mesh mean nothing.
void check_indices(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles) {
  const int n = static_cast<int>(positions.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int v : triangles[t]) {
      if (v < 0 || v >= n)
        throw InputError(fmt::format("triangle {} refers to vertex {}, but the mesh has {} vertices", t, v, n));
      if (!is_finite(positions[v]))
        throw InputError(fmt::format("vertex {} (used by triangle {}) has a non-finite coordinate", v, t));
    }
}

//! The corner angle at a between edges to b and c, in degrees; 0 when an edge has zero length.
double corner_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, v = c - a;
  return std::atan2(norm(cross(u, v)), dot(u, v)) * (180.0 / kPi);
}

//! The vertices some triangle uses, in increasing order (unused vertices are not on the surface).
std::vector<Vec3> used_vertices(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles) {
  std::vector<char> used(positions.size(), 0);
  for (const Triangle& t : triangles)
    for (int v : t) used[v] = 1;
  std::vector<Vec3> out;
  for (std::size_t v = 0; v < positions.size(); ++v)
    if (used[v]) out.push_back(positions[v]);
  return out;
}

//! n points uniformly distributed by area over plain triangles (the remesh may be non-manifold, so
//! no SurfaceMesh), appended to `out`. Zero-area triangles receive none; nothing when all are.
void append_area_samples(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles, int n,
                         unsigned long long seed, std::vector<Vec3>& out) {
  std::vector<double> cumulative(triangles.size());
  double total = 0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Triangle& f = triangles[t];
    const Vec3 &a = positions[f[0]], &b = positions[f[1]], &c = positions[f[2]];
    cumulative[t] = (total += 0.5 * norm(cross(b - a, c - a)));
  }
  if (n <= 0 || !(total > 0)) return;
  Random random(seed);
  const int m = static_cast<int>(triangles.size());
  out.reserve(out.size() + n);
  for (int i = 0; i < n; ++i) {
    const double target = random.uniform() * total;
    const int t = std::min<int>(
        static_cast<int>(std::upper_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin()), m - 1);
    // sqrt warps r1 so that the density is uniform over the triangle, not over the fan of segments.
    const double s = std::sqrt(random.uniform()), r = random.uniform();
    const Triangle& f = triangles[t];
    out.push_back((1 - s) * positions[f[0]] + (s * (1 - r)) * positions[f[1]] + (s * r) * positions[f[2]]);
  }
}

//! Distance from each point to the indexed surface, one slot per point (parallel, deterministic).
//! The points are taken along a Morton curve (copied in that order first: read in place, each
//! query would wait on its point), each query hinted by the closest triangle of the point before
//! it: a nearby point's answer bounds the search at once. A hint leaves the answer as it is
//! (ClosestPointIndex::query), so the distances are those of plain queries.
std::vector<double> distances_to(const ClosestPointIndex& index, const std::vector<Vec3>& points) {
  const std::vector<int> order = morton_order(points);
  std::vector<Vec3> along(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) along[k] = points[order[k]];
  std::vector<double> d_along(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      int hint = -1;
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const ClosestPoint c = index.query(along[k], hint);
                        d_along[k] = c.distance;
                        hint = c.triangle;
                      }
                    });
  std::vector<double> d(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) d[order[k]] = d_along[k];
  return d;
}

}  // namespace

nlohmann::json QualityMetrics::to_json() const {
  return {{"Qmin", q_min},
          {"Qavg", q_avg},
          {"theta_min", theta_min},
          {"theta_max", theta_max},
          {"pct_triangles_below_30", pct_triangles_below_30},
          {"pct_angles_below_30", pct_angles_below_30},
          {"hausdorff_pct", hausdorff_pct},
          {"rms_pct", rms_pct},
          {"triangles", triangles},
          {"vertices", vertices}};
}

double triangle_quality(const Vec3& a, const Vec3& b, const Vec3& c) {
  // Q(t) = 6/√3 · |t| / (p(t) h(t)): 1 for the equilateral triangle, 0 for a degenerate one.
  const double la = distance(b, c), lb = distance(c, a), lc = distance(a, b);
  const double area = 0.5 * norm(cross(b - a, c - a));
  const double half_perimeter = 0.5 * (la + lb + lc), longest = std::max({la, lb, lc});
  return half_perimeter * longest > 0 ? 6.0 / std::sqrt(3.0) * area / (half_perimeter * longest) : 0.0;
}

double triangle_min_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::min({corner_angle(a, b, c), corner_angle(b, c, a), corner_angle(c, a, b)});
}

QualityMetrics shape_metrics(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles) {
  check_indices(positions, triangles);
  QualityMetrics m;
  m.triangles = static_cast<int>(triangles.size());
  m.vertices = static_cast<int>(positions.size());
  if (triangles.empty()) return m;

  double q_sum = 0;
  long long triangles_below = 0, angles_below = 0;
  m.q_min = std::numeric_limits<double>::infinity();
  m.theta_min = std::numeric_limits<double>::infinity();
  m.theta_max = -std::numeric_limits<double>::infinity();
  for (const Triangle& f : triangles) {
    const Vec3 &a = positions[f[0]], &b = positions[f[1]], &c = positions[f[2]];
    const double q = triangle_quality(a, b, c);
    m.q_min = std::min(m.q_min, q);
    q_sum += q;

    const double angles[3] = {corner_angle(a, b, c), corner_angle(b, c, a), corner_angle(c, a, b)};
    bool below = false;
    for (double angle : angles) {
      m.theta_min = std::min(m.theta_min, angle);
      m.theta_max = std::max(m.theta_max, angle);
      if (angle < 30.0) ++angles_below, below = true;
    }
    if (below) ++triangles_below;
  }
  const double count = static_cast<double>(triangles.size());
  m.q_avg = q_sum / count;
  m.pct_triangles_below_30 = 100.0 * static_cast<double>(triangles_below) / count;
  m.pct_angles_below_30 = 100.0 * static_cast<double>(angles_below) / (3 * count);
  return m;
}

QualityMetrics quality_metrics(const SurfaceMesh& reference, const std::vector<Vec3>& positions,
                               const std::vector<Triangle>& triangles, const DistanceOptions& options) {
  QualityMetrics m = shape_metrics(positions, triangles);
  if (triangles.empty()) throw InputError("the remesh has no triangles: no distance to the reference");
  if (reference.triangle_count() == 0) throw InputError("the reference mesh has no triangles");
  require_workable_model(reference, "measuring the quality");
  // Each surface's points start with its (used) vertices. A remesh whose used vertices span far
  // more than the workable sizes has areas and distances beyond the doubles (inf and NaN metrics);
  // a vertex no triangle uses is not on the surface and does not count.
  std::vector<Vec3> remesh_points = used_vertices(positions, triangles);
  require_workable_size(remesh_points, "the remesh", "measuring the quality");

  // Zero-area triangles are left out of sampling and of the index: they add no surface, and a
  // triangle with coincident corners has no well-defined closest-point regions.
  std::vector<Triangle> proper;
  for (const Triangle& f : triangles)
    if (!predicates::collinear(positions[f[0]], positions[f[1]], positions[f[2]])) proper.push_back(f);
  if (proper.empty()) throw InputError("every triangle of the remesh has collinear corners: it has no surface");
  require_within_reach(reference.bounding_box(), positions, triangles, "the remesh", "the reference", "measuring the quality");
  require_within_reach(bounding_box(remesh_points), reference.positions(), reference.triangles(), "the reference",
                       "the remesh", "measuring the quality");

  // Then samples by area. The reference gets a different seed so that its points are not drawn
  // with the same random sequence.
  append_area_samples(positions, proper, options.samples_per_surface, options.seed, remesh_points);
  std::vector<Vec3> reference_points = reference.positions();
  append_area_samples(reference.positions(), reference.triangles(), options.samples_per_surface,
                      options.seed ^ 0x9e3779b97f4a7c15ull, reference_points);

  const ClosestPointIndex reference_index(reference);
  const ClosestPointIndex remesh_index(positions, proper);
  const std::vector<double> to_reference = distances_to(reference_index, remesh_points);
  const std::vector<double> to_remesh = distances_to(remesh_index, reference_points);

  // Serial reduction in point order: the same sum on every run and thread count.
  double hausdorff = 0, squared_sum = 0;
  for (const std::vector<double>* d : {&to_reference, &to_remesh})
    for (double x : *d) {
      hausdorff = std::max(hausdorff, x);
      squared_sum += x * x;
    }
  const double count = static_cast<double>(to_reference.size() + to_remesh.size());
  const double diagonal = reference.bounding_box().diagonal();
  const double scale = diagonal > 0 ? 100.0 / diagonal : 0.0;
  m.hausdorff_pct = hausdorff * scale;
  m.rms_pct = std::sqrt(squared_sum / count) * scale;
  return m;
}

}  // namespace lrvd
