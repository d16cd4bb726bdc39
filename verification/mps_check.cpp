// verify_mps: the minimum-distance and maximality properties of a Poisson-disk sampling, from the
// samples and a freshly computed LRPD alone (nothing of the sampler's state is reused).
#include "verification/mps_check.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include <fmt/format.h>

#include "common/error.h"
#include "mesh/closest_point.h"
#include "predicates/exact.h"
#include "voronoi/lrvd.h"

namespace lrvd {

namespace {

// Exact sign of |a - b|² - w.
CGAL::Sign squared_distance_minus(const Vec3& a, const Vec3& b, double w) {
  const double d = squared_distance(a, b);
  if (d >= 1e-250) {  // |fl(d) - d| <= 5u·d, plus u·|d - w| for the subtraction
    const double margin = 1e-15 * (d + w);
    if (d - w > margin) return CGAL::POSITIVE;
    if (w - d > margin) return CGAL::NEGATIVE;
  }
  return CGAL::sign(exact_power_distance(to_exact(a), Site{b, w, 0}));
}

// Samples of each triangle (CSR).
struct TriangleSamples {
  std::vector<int> offset, items;
  TriangleSamples(const SurfaceMesh& mesh, const Samples& s) : offset(mesh.triangle_count() + 1, 0) {
    for (int t : s.triangles) ++offset[t + 1];
    for (int t = 0; t < mesh.triangle_count(); ++t) offset[t + 1] += offset[t];
    items.resize(s.size());
    std::vector<int> fill(offset.begin(), offset.end() - 1);
    for (int i = 0; i < s.size(); ++i) items[fill[s.triangles[i]]++] = i;
  }
};

std::uint64_t pair_key(int i, int j) {
  return (static_cast<std::uint64_t>(std::min(i, j)) << 32) | static_cast<std::uint32_t>(std::max(i, j));
}

// Local regions of balls, grown independently of the sampler: the triangles the ball B(x, r)
// meets that face like x's triangle t (normals at less than 90°), edge-connected to t through
// such triangles.
class LocalRegions {
 public:
  explicit LocalRegions(const SurfaceMesh& mesh) : mesh_(mesh), stamp_(mesh.triangle_count(), -1), normals_(mesh.triangle_count()) {
    for (int t = 0; t < mesh.triangle_count(); ++t) normals_[t] = mesh.triangle_normal(t);
  }
  //! Calls f(triangle) for each triangle of the region until f returns true; returns whether it did.
  template <class F>
  bool search(const Vec3& x, int t, double w, F&& f) {
    ++epoch_;
    queue_.assign(1, t);
    stamp_[t] = epoch_;
    if (f(t)) return true;
    for (size_t k = 0; k < queue_.size(); ++k)
      for (int e = 0; e < 3; ++e) {
        const int n = mesh_.neighbor(queue_[k], e);
        if (n < 0 || stamp_[n] == epoch_) continue;
        stamp_[n] = epoch_;
        if (!(dot(normals_[n], normals_[t]) > 0)) continue;
        const Triangle& tri = mesh_.triangle(n);
        const ClosestPoint c =
            closest_point_on_triangle(x, mesh_.position(tri[0]), mesh_.position(tri[1]), mesh_.position(tri[2]));
        if (!(squared_distance(x, c.point) < w)) continue;
        queue_.push_back(n);
        if (f(n)) return true;
      }
    return false;
  }
  bool reaches(const Vec3& x, int t, double w, int target) {
    return search(x, t, w, [&](int n) { return n == target; });
  }

 private:
  const SurfaceMesh& mesh_;
  std::vector<int> stamp_, queue_;
  std::vector<Vec3> normals_;
  int epoch_ = 0;
};

// Two samples are local to each other when each one's triangle lies in the local region of the
// other's ball of radius ρ = max(r_i, r_j); local samples closer than ρ violate the property.
// Returns those pairs.
std::unordered_set<std::uint64_t> check_min_distance(const SurfaceMesh& mesh, const Samples& s, MpsVerification& out) {
  const TriangleSamples by_triangle(mesh, s);
  LocalRegions regions(mesh);
  std::vector<int> region;
  std::unordered_set<std::uint64_t> close;
  double min_ratio2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < s.size(); ++i) {
    const Vec3& x = s.positions[i];
    const double w = s.weights[i];
    const int ti = s.triangles[i];
    region.clear();
    regions.search(x, ti, w, [&](int n) {
      region.push_back(n);
      return false;
    });
    // Every violating pair is seen from the sample with the larger radius: the other's centre
    // lies in its ball and, the pair being local, in its region.
    for (int t : region)
      for (int k = by_triangle.offset[t]; k < by_triangle.offset[t + 1]; ++k) {
        const int j = by_triangle.items[k];
        if (j == i) continue;
        const double d2 = squared_distance(x, s.positions[j]);
        const double rho2 = std::max(w, s.weights[j]);
        if (squared_distance_minus(s.positions[j], x, w) != CGAL::NEGATIVE) {
          if (d2 >= rho2) min_ratio2 = std::min(min_ratio2, d2 / rho2);
          continue;
        }
        ++out.min_distance.checked;
        const bool local = (s.weights[j] <= w || regions.reaches(x, ti, rho2, t)) &&
                           regions.reaches(s.positions[j], t, rho2, ti);
        if (!local) {
          ++out.one_sided_close_pairs;
          continue;
        }
        min_ratio2 = std::min(min_ratio2, d2 / rho2);
        close.insert(pair_key(i, j));
        out.min_distance.fail(fmt::format("sample {} lies in the disk of sample {} (distance {:.6g}, radius {:.6g})", j, i,
                                          std::sqrt(d2), std::sqrt(w)));
      }
  }
  out.min_distance_ratio = std::isfinite(min_ratio2) ? std::sqrt(min_ratio2) : 0;
  return close;
}

// Pairs closer than max(r_i, r_j) anywhere in space (hash grid of cell r_max) that are not local
// to each other: on different sheets or past a notch (allowed, reported).
std::int64_t count_close_pairs(const Samples& s, const std::unordered_set<std::uint64_t>& local) {
  if (s.size() < 2) return 0;
  double r_max = 0;
  for (double w : s.weights) r_max = std::max(r_max, std::sqrt(w));
  if (!(r_max > 0)) return 0;
  using Cell = std::array<std::int64_t, 3>;
  struct CellHash {
    std::size_t operator()(const Cell& c) const {
      return static_cast<std::size_t>(c[0] * 73856093 ^ c[1] * 19349663 ^ c[2] * 83492791);
    }
  };
  auto cell_of = [&](const Vec3& p) {
    return Cell{static_cast<std::int64_t>(std::floor(p.x / r_max)), static_cast<std::int64_t>(std::floor(p.y / r_max)),
                static_cast<std::int64_t>(std::floor(p.z / r_max))};
  };
  std::unordered_map<Cell, std::vector<int>, CellHash> grid;
  for (int i = 0; i < s.size(); ++i) grid[cell_of(s.positions[i])].push_back(i);
  std::int64_t pairs = 0;
  for (int i = 0; i < s.size(); ++i) {
    const Cell c = cell_of(s.positions[i]);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = grid.find(Cell{c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (int j : it->second) {
            if (j <= i) continue;
            const double w = std::max(s.weights[i], s.weights[j]);
            if (squared_distance(s.positions[i], s.positions[j]) < w && !local.count(pair_key(i, j))) ++pairs;
          }
        }
  }
  return pairs;
}

void check_maximality(const SurfaceMesh& mesh, const Samples& s, const Diagram& d, const MpsVerifyOptions& options,
                      MpsVerification& out) {
  const SymbolicContext ctx = d.context(mesh);
  std::vector<double> area_sum(mesh.triangle_count(), 0);
  for (const CellPolygon& cp : d.polygons) {
    const int i = cp.cell;
    const Site site{s.positions[i], s.weights[i], i};
    const SymbolicVertex* q = d.polygon_vertices(cp);
    std::vector<Vec3> p(cp.vertex_count);
    for (int k = 0; k < cp.vertex_count; ++k) p[k] = position(q[k], ctx);
    Vec3 twice{};
    for (int k = 1; k + 1 < cp.vertex_count; ++k) twice += cross(p[k] - p[0], p[k + 1] - p[0]);
    area_sum[cp.triangle] += 0.5 * norm(twice);
    ++out.maximal.checked;
    for (int k = 0; k < cp.vertex_count; ++k) {
      const double pd = squared_distance(p[k], site.p) - site.w;
      bool outside;
      if (options.exact_maximality || std::abs(pd) <= 1e-6 * site.w) {
        ++out.exact_vertex_tests;
        outside = CGAL::sign(exact_power_distance(exact_position(q[k], ctx), site)) == CGAL::POSITIVE;
      } else {
        outside = pd > 0;
      }
      if (outside) {
        out.maximal.fail(fmt::format("triangle {}: cell {} reaches {:.4g}·r_i from x_i (uncovered)", cp.triangle, i,
                                     std::sqrt(std::max(0.0, 1 + pd / site.w))));
        break;
      }
    }
  }
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    ++out.diagram_covers.checked;
    const double a = mesh.triangle_area(t);
    if (!(std::abs(area_sum[t] - a) <= 1e-9 * a))
      out.diagram_covers.fail(fmt::format("triangle {}: polygons cover {:.9g} of area {:.9g}", t, area_sum[t], a));
  }
}

}  // namespace

nlohmann::json MpsVerification::to_json() const {
  return {{"passed", passed},
          {"time_s", time_s},
          {"min_distance_ratio", min_distance_ratio},
          {"close_pairs_not_local", close_pairs_not_local},
          {"one_sided_close_pairs", one_sided_close_pairs},
          {"exact_vertex_tests", exact_vertex_tests},
          {"properties",
           {{"min_distance", min_distance.to_json()},
            {"maximal", maximal.to_json()},
            {"diagram_covers", diagram_covers.to_json()}}}};
}

std::string MpsVerification::summary() const {
  return min_distance.summary_line("min_distance") + maximal.summary_line("maximal") +
         diagram_covers.summary_line("diagram_covers");
}

MpsVerification verify_mps(const SurfaceMesh& mesh, const Samples& samples, const Diagram& lrpd,
                           const MpsVerifyOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (samples.size() == 0) throw InputError("no samples to verify");
  if (static_cast<int>(samples.weights.size()) != samples.size())
    throw InputError("a Poisson-disk sampling needs a weight (radius²) for every sample");
  if (!is_power(lrpd.kind) || lrpd.sample_count != samples.size())
    throw InputError("the maximality check needs a power diagram (LRPD) of these samples");
  for (int i = 0; i < samples.size(); ++i)
    if (samples.triangles[i] < 0 || samples.triangles[i] >= mesh.triangle_count())
      throw InputError(fmt::format("sample {} is not located on a triangle of the mesh", i));
  MpsVerification out;
  out.close_pairs_not_local = count_close_pairs(samples, check_min_distance(mesh, samples, out));
  check_maximality(mesh, samples, lrpd, options, out);
  out.passed = out.min_distance.passed && out.maximal.passed && out.diagram_covers.passed;
  out.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

MpsVerification verify_mps(const SurfaceMesh& mesh, const Samples& samples, const MpsVerifyOptions& options) {
  LrvdOptions lrpd;
  lrpd.weighted = true;
  return verify_mps(mesh, samples, compute_lrvd(mesh, samples, lrpd), options);
}

}  // namespace lrvd
