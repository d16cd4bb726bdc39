// verify_mps: the minimum-distance and maximality properties of a Poisson-disk sampling, from the
// samples, their disks grown here and a freshly computed LRPD alone (nothing of the sampler's
// state is reused).
#include "verification/mps_check.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>
#include <tbb/parallel_invoke.h>

#include "common/error.h"
#include "common/timing.h"
#include "diagram/clip.h"
#include "mesh/closest_point.h"
#include "predicates/ball_triangle.h"
#include "predicates/exact.h"
#include "verification/diagram_geometry.h"
#include "verification/mps_reach_cover.h"

namespace lrvd {

namespace {

// Exact sign of |a - b|² - w.
CGAL::Sign squared_distance_minus(const Vec3& a, const Vec3& b, double w) {
  const double d = squared_distance(a, b);
  if (d >= 1e-250) {  // |fl(d) - d| <= 5u·d, plus u·|d - w| for the subtraction
    const double margin = 1e-15 * (d + w);
    if (d - w > margin) return CGAL::POSITIVE;
    if (w - d > margin) return CGAL::NEGATIVE;
  } else if (w > 1e-240) {
    return CGAL::NEGATIVE;  // |a - b|² is below 1e-249 however the squares rounded
  }
  return CGAL::sign(exact_power_distance(to_exact(a), Site{b, w, 0}));
}

// Samples of each triangle (CSR).
struct TriangleSamples {
  std::vector<int> offset, items;
  //! Each sample under every triangle it lies on (`seeds(i)`: one, or those at its edge or corner).
  template <class Seeds>
  TriangleSamples(const SurfaceMesh& mesh, const Samples& s, Seeds&& seeds) : offset(mesh.triangle_count() + 1, 0) {
    std::vector<std::pair<int, int>> entries;  // (triangle, sample)
    entries.reserve(s.size());
    for (int i = 0; i < s.size(); ++i)
      for (int t : seeds(i)) entries.emplace_back(t, i);
    std::sort(entries.begin(), entries.end());
    items.resize(entries.size());
    for (size_t k = 0; k < entries.size(); ++k) {
      ++offset[entries[k].first + 1];
      items[k] = entries[k].second;
    }
    for (int t = 0; t < mesh.triangle_count(); ++t) offset[t + 1] += offset[t];
  }
};

// Local regions of balls, grown independently of the sampler: the triangles the ball B(x, r)
// meets, edge-connected to x's triangle t through such triangles (the paper's rule); with the
// facing cut (`cut`), only those that face like t (normals at less than 90°).
class LocalRegions {
 public:
  explicit LocalRegions(const SurfaceMesh& mesh) : mesh_(mesh), info_(mesh.triangle_count()) {
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      const Triangle& tri = mesh.triangle(t);
      const Vec3 &a = mesh.position(tri[0]), &b = mesh.position(tri[1]), &c = mesh.position(tri[2]);
      TriangleInfo& info = info_[t];
      info.normal = mesh.triangle_normal(t);
      info.center = (a + b + c) / 3.0;
      info.radius = std::sqrt(
          std::max({squared_distance(info.center, a), squared_distance(info.center, b), squared_distance(info.center, c)}));
    }
  }
  //! Calls f(triangle) for each triangle of the region until f returns true; returns whether it did.
  template <class F>
  bool search(const Vec3& x, int t, double w, bool cut, F&& f) {
    ++epoch_;
    queue_.assign(1, t);
    info_[t].stamp = epoch_;
    if (f(t)) return true;
    const Vec3 facing = info_[t].normal;
    const double r = std::sqrt(w);
    for (size_t k = 0; k < queue_.size(); ++k)
      for (int e = 0; e < 3; ++e) {
        const int n = mesh_.neighbor(queue_[k], e);
        if (n < 0 || info_[n].stamp == epoch_) continue;
        info_[n].stamp = epoch_;
        if ((cut && !(dot(info_[n].normal, facing) > 0)) || !meets(n, x, w, r)) continue;
        queue_.push_back(n);
        if (f(n)) return true;
      }
    return false;
  }
  bool reaches(const Vec3& x, int t, double w, bool cut, int target) {
    return search(x, t, w, cut, [&](int n) { return n == target; });
  }
  //! The triangles sample i lies on: its own, and with barycentric coordinates that put it exactly
  //! on an edge or a corner, the other triangles there (SurfaceMesh::triangles_at). Its ball's
  //! region grows from each: a sample on a sharp edge reaches both faces.
  //! The coordinates are taken only where they give the sample's position back (to rounding), so
  //! that they cannot place a sample on an edge it is not on.
  const std::vector<int>& seeds(const Samples& s, int i) {
    seeds_.clear();
    const int t = s.triangles[i];
    if (s.barycentric.size() == static_cast<size_t>(s.size())) {
      const Vec3& b = s.barycentric[i];
      const Triangle& tri = mesh_.triangle(t);
      const Vec3 q = b.x * mesh_.position(tri[0]) + b.y * mesh_.position(tri[1]) + b.z * mesh_.position(tri[2]);
      const double scale = info_[t].radius + norm(info_[t].center);
      if (squared_distance(q, s.positions[i]) <= 1e-24 * scale * scale) {
        mesh_.triangles_at(t, b, seeds_);
        return seeds_;
      }
    }
    seeds_.push_back(t);
    return seeds_;
  }
  //! Whether `target` is in the region of sample i's ball at weight w.
  bool sample_reaches(const Samples& s, int i, double w, bool cut, int target) {
    for (int t : seeds(s, i))  // search() leaves seeds_ alone
      if (reaches(s.positions[i], t, w, cut, target)) return true;
    return false;
  }

 private:
  // Whether the ball B(x, r), w = r², meets triangle t, exactly (ball_meets_triangle), after
  // one shortcut: a ball far from t's bounding sphere (by more than rounding) misses it.
  bool meets(int t, const Vec3& x, double w, double r) const {
    const double reach = r + info_[t].radius;
    if (squared_distance(x, info_[t].center) > reach * reach * (1 + 1e-9)) return false;
    const Triangle& tri = mesh_.triangle(t);
    return ball_meets_triangle(x, w, mesh_.position(tri[0]), mesh_.position(tri[1]), mesh_.position(tri[2]));
  }

  // What a search reads of a triangle, in one cache line.
  struct TriangleInfo {
    Vec3 normal;
    Vec3 center;        // the bounding sphere about the centroid
    double radius = 0;
    int stamp = -1;     // the last search that saw the triangle
  };
  const SurfaceMesh& mesh_;
  std::vector<TriangleInfo> info_;
  std::vector<int> queue_, seeds_;
  int epoch_ = 0;
};

// The triangles each sample lies on (LocalRegions::seeds).
std::vector<std::vector<int>> sample_triangles(const Samples& s, LocalRegions& regions) {
  std::vector<std::vector<int>> triangles(s.size());
  for (int i = 0; i < s.size(); ++i) triangles[i] = regions.seeds(s, i);
  return triangles;
}

// Halvings of a polygon the reach certificate may take, and polygons it may look at in all
// (ReachCover::covers). Coverings that overlap by 10^-7 r (a thin box's rim, where a disk's circle
// meets the line beyond which a ball no longer reaches round the rim) need about 40 halvings,
// near one point: a few dozen polygons.
constexpr int kReachCoverDepth = 48;
constexpr int kReachCoverBudget = 2000;

// The disk of every sample: the local region of its ball B(x_i, r_i), sorted (CSR by sample).
struct SampleDisks {
  std::vector<int> offset, triangles;
  SampleDisks(const Samples& s, LocalRegions& regions, bool cut) {
    // Grown in the order of the samples' triangles (neighbouring samples touch the same
    // triangles, which stay in cache), then listed by sample.
    std::vector<int> order(s.size());
    for (int i = 0; i < s.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return s.triangles[a] < s.triangles[b]; });
    std::vector<int> found, first(s.size()), count(s.size());
    for (int i : order) {
      first[i] = static_cast<int>(found.size());
      const std::vector<int>& seeds = regions.seeds(s, i);  // search() leaves it alone
      for (int t : seeds)
        regions.search(s.positions[i], t, s.weights[i], cut, [&](int n) {
          found.push_back(n);
          return false;
        });
      std::sort(found.begin() + first[i], found.end());
      if (seeds.size() > 1) found.erase(std::unique(found.begin() + first[i], found.end()), found.end());
      count[i] = static_cast<int>(found.size()) - first[i];
    }
    offset.assign(s.size() + 1, 0);
    for (int i = 0; i < s.size(); ++i) offset[i + 1] = offset[i] + count[i];
    triangles.resize(found.size());
    for (int i = 0; i < s.size(); ++i) std::copy_n(found.begin() + first[i], count[i], triangles.begin() + offset[i]);
  }
  const int* begin(int i) const { return triangles.data() + offset[i]; }
  const int* end(int i) const { return triangles.data() + offset[i + 1]; }
  //! The disk of sample i reaches triangle t.
  bool reaches(int i, int t) const { return std::binary_search(begin(i), end(i), t); }
};

// Pairs closer than max(r_i, r_j), decided exactly, anywhere in space: a grid of cells at least
// r_max wide, the samples sorted by cell. Each pair once, i < j.
std::vector<std::pair<int, int>> close_pairs(const Samples& s) {
  std::vector<std::pair<int, int>> pairs;
  if (s.size() < 2) return pairs;
  double r_max = 0;
  for (double w : s.weights) r_max = std::max(r_max, std::sqrt(w));
  if (!(r_max > 0)) return pairs;
  Vec3 lo = s.positions[0], hi = s.positions[0];
  for (const Vec3& p : s.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  // 21 bits per axis, so that a cell packs into one 64-bit key: cells grow past r_max if needed.
  constexpr double kCellsPerAxis = 1 << 20;
  const double cell = std::max({r_max, (hi.x - lo.x) / kCellsPerAxis, (hi.y - lo.y) / kCellsPerAxis,
                                (hi.z - lo.z) / kCellsPerAxis}) * (1 + 1e-12);
  // Coordinates start at 1, so that the neighbours of a cell at 0 are still inside the 21 bits.
  auto coordinate = [&](double x, double origin) { return static_cast<std::uint64_t>((x - origin) / cell) + 1; };
  auto key = [](std::uint64_t x, std::uint64_t y, std::uint64_t z) { return (x << 42) | (y << 21) | z; };
  std::vector<std::pair<std::uint64_t, int>> by_cell(s.size());
  for (int i = 0; i < s.size(); ++i) {
    const Vec3& p = s.positions[i];
    by_cell[i] = {key(coordinate(p.x, lo.x), coordinate(p.y, lo.y), coordinate(p.z, lo.z)), i};
  }
  std::sort(by_cell.begin(), by_cell.end());
  std::unordered_map<std::uint64_t, int> first;  // the first entry of each cell in by_cell
  first.reserve(by_cell.size());
  for (int k = static_cast<int>(by_cell.size()) - 1; k >= 0; --k) first[by_cell[k].first] = k;
  for (int i = 0; i < s.size(); ++i) {
    const Vec3& p = s.positions[i];
    const std::uint64_t cx = coordinate(p.x, lo.x), cy = coordinate(p.y, lo.y), cz = coordinate(p.z, lo.z);
    for (std::uint64_t x = cx - 1; x <= cx + 1; ++x)
      for (std::uint64_t y = cy - 1; y <= cy + 1; ++y)
        for (std::uint64_t z = cz - 1; z <= cz + 1; ++z) {
          const std::uint64_t c = key(x, y, z);
          const auto it = first.find(c);
          if (it == first.end()) continue;
          for (int k = it->second; k < static_cast<int>(by_cell.size()) && by_cell[k].first == c; ++k) {
            const int j = by_cell[k].second;
            if (j <= i) continue;
            if (squared_distance_minus(s.positions[j], p, std::max(s.weights[i], s.weights[j])) == CGAL::NEGATIVE)
              pairs.emplace_back(i, j);
          }
        }
  }
  return pairs;
}

// The minimum distance. Samples i and j are local to each other when the local region of one's
// ball of radius ρ = max(r_i, r_j) reaches a triangle of the other (the paper's rule: a dart
// conflicts with the disks its region reaches, and with the disks that reach it); local samples
// closer than ρ violate the property. With the facing cut (MpsConflict::CloseAcrossTurns) the regions stop
// where the surface turns by 90° or more and each must reach the other's triangle; the close
// pairs the paper's rule calls local and the cut lets through are counted. A sample exactly on an
// edge or corner lies on every triangle there (LocalRegions::seeds): any of them counts as its
// triangle. Every pair closer than ρ is looked at (close_pairs), whatever the regions.
void check_min_distance(const SurfaceMesh& mesh, const Samples& s, const SampleDisks& disks, LocalRegions& regions,
                        const std::vector<std::vector<int>>& triangles, bool cut, MpsVerification& out) {
  double min_ratio2 = std::numeric_limits<double>::infinity();
  // The ratio over the pairs that keep their distance: the centres in each sample's disk.
  const TriangleSamples by_triangle(mesh, s, [&](int i) -> const std::vector<int>& { return triangles[i]; });
  std::vector<int> seen(s.size(), -1);  // the last sample i from which j was looked at
  for (int i = 0; i < s.size(); ++i) {
    const Vec3& x = s.positions[i];
    for (const int* it = disks.begin(i); it != disks.end(i); ++it)
      for (int k = by_triangle.offset[*it]; k < by_triangle.offset[*it + 1]; ++k) {
        const int j = by_triangle.items[k];
        if (j == i || seen[j] == i) continue;
        seen[j] = i;
        const double rho2 = std::max(s.weights[i], s.weights[j]);
        if (squared_distance_minus(s.positions[j], x, rho2) != CGAL::NEGATIVE)
          min_ratio2 = std::min(min_ratio2, squared_distance(x, s.positions[j]) / rho2);
      }
  }
  for (const auto& [i, j] : close_pairs(s)) {
    ++out.min_distance.checked;
    const double rho2 = std::max(s.weights[i], s.weights[j]);
    // a's region at ρ reaches one of b's triangles.
    auto reaches = [&](int a, int b, bool facing_cut) {
      for (int t : triangles[b])
        if (regions.sample_reaches(s, a, rho2, facing_cut, t)) return true;
      return false;
    };
    const bool ij = reaches(i, j, false), ji = reaches(j, i, false);
    bool local = ij || ji;
    if (ij != ji) ++out.one_sided_close_pairs;
    if (cut) {
      const bool paper = local;
      local = reaches(i, j, true) && reaches(j, i, true);
      if (paper && !local) ++out.close_pairs_local_past_facing_cut;
    }
    if (!local) {
      ++out.close_pairs_not_local;
      continue;
    }
    const double d2 = squared_distance(s.positions[i], s.positions[j]);
    min_ratio2 = std::min(min_ratio2, d2 / rho2);
    out.min_distance.fail(fmt::format("samples {} and {} are local to each other and {:.6g} apart, closer than "
                                      "their larger radius {:.6g}",
                                      i, j, std::sqrt(d2), std::sqrt(rho2)));
  }
  out.min_distance_ratio = std::isfinite(min_ratio2) ? std::sqrt(min_ratio2) : std::numeric_limits<double>::quiet_NaN();
}

// Whether corner q (at p) of a polygon lies outside the ball of `site`: decided on the interval
// enclosure of q's exact position when its power distance's sign is certain there (unless
// `exact`), else with rationals. pd (from the doubles) is for messages only: a corner computed
// from nearly parallel bisectors (many samples on feature lines) can be far from its exact place,
// and a test on the doubles alone called such samplings not maximal.
bool outside_ball(const SymbolicVertex& q, const Vec3& p, const Site& site, const SymbolicContext& ctx, bool exact,
                  std::int64_t& exact_tests, double& pd) {
  pd = squared_distance(p, site.p) - site.w;
  if (!exact)
    if (const std::optional<CGAL::Sign> sign = enclosed_power_sign(q, site, ctx)) return *sign == CGAL::POSITIVE;
  ++exact_tests;
  return CGAL::sign(exact_power_distance(exact_position(q, ctx), site)) == CGAL::POSITIVE;
}

// The LRPD's polygons one by one: their areas summed per triangle (area_sum, for
// check_diagram_covers), whether each lies in its cell's ball (all corners), and the polygons of
// remote balls counted. Returns the triangles with a polygon outside its cell's ball, ascending.
std::vector<int> scan_polygons(const SurfaceMesh& mesh, const Samples& s, const Diagram& d, const SampleDisks& disks,
                               const MpsVerifyOptions& options, std::vector<double>& area_sum, MpsVerification& out) {
  const SymbolicContext ctx = d.context(mesh);
  area_sum.assign(mesh.triangle_count(), 0);
  std::vector<int> undecided;
  std::vector<Vec3> p;
  for (const CellPolygon& cp : d.polygons) {
    const int i = cp.cell;
    const Site site{s.positions[i], s.weights[i], i};
    const SymbolicVertex* q = d.polygon_vertices(cp);
    p.resize(cp.vertex_count);
    for (int k = 0; k < cp.vertex_count; ++k) p[k] = position(q[k], ctx);
    Vec3 twice{};
    for (int k = 1; k + 1 < cp.vertex_count; ++k) twice += cross(p[k] - p[0], p[k + 1] - p[0]);
    area_sum[cp.triangle] += 0.5 * norm(twice);
    bool inside = true;
    double pd = 0;
    for (int k = 0; k < cp.vertex_count && inside; ++k)
      inside = !outside_ball(q[k], p[k], site, ctx, options.exact_maximality, out.exact_vertex_tests, pd);
    if (!inside) {
      ++out.polygons_outside_own_ball;
      if (undecided.empty() || undecided.back() != cp.triangle) undecided.push_back(cp.triangle);
    } else if (!disks.reaches(i, cp.triangle)) {
      ++out.polygons_of_remote_balls;
    }
  }
  return undecided;
}

// A(t) of each undecided triangle t: its LRPD cells, then the samples whose disks reach it
// (unsorted, maybe repeated).
std::vector<std::vector<int>> samples_around(const SurfaceMesh& mesh, const Samples& s, const Diagram& d,
                                             const SampleDisks& disks, const std::vector<int>& undecided) {
  std::vector<int> slot(mesh.triangle_count(), -1);
  std::vector<std::vector<int>> around(undecided.size());
  for (size_t u = 0; u < undecided.size(); ++u) {
    const int t = undecided[u];
    slot[t] = static_cast<int>(u);
    for (int k = d.triangle_offsets[t]; k < d.triangle_offsets[t + 1]; ++k) around[u].push_back(d.polygons[k].cell);
  }
  for (int i = 0; i < s.size(); ++i)
    for (const int* t = disks.begin(i); t != disks.end(i); ++t)
      if (slot[*t] >= 0) around[slot[*t]].push_back(i);
  return around;
}

// Each undecided triangle t on the power diagram of A(t), clipped exactly: every polygon in its
// own ball, or (the paper's rule) certified by the reach cover; else t fails maximality.
void decide_undecided(const SurfaceMesh& mesh, const Samples& s, const Diagram& d, const SampleDisks& disks,
                      const std::vector<std::vector<int>>& sample_triangles, const MpsVerifyOptions& options,
                      const std::vector<int>& undecided, MpsVerification& out) {
  std::vector<std::vector<int>> around = samples_around(mesh, s, d, disks, undecided);
  const std::vector<Site> sites = make_sites(s, true);
  std::optional<verify_detail::ReachCover> reach;
  if (!options.facing_cut) reach.emplace(mesh, s, sample_triangles);
  std::vector<ExactPoint> exact_polygon;
  const SymbolicContext around_ctx{mesh.positions().data(), sites.data()};
  std::vector<SymbolicVertex> polygon, scratch;
  for (size_t u = 0; u < undecided.size(); ++u) {
    const int t = undecided[u];
    std::vector<int>& a = around[u];
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    bool covered = true;
    for (size_t c = 0; c < a.size() && covered; ++c) {
      const int k = a[c];
      clip_triangle(mesh, t, k, a.data(), static_cast<int>(a.size()), around_ctx, polygon, scratch);
      double pd = 0, worst = -std::numeric_limits<double>::infinity();
      for (const SymbolicVertex& q : polygon)
        if (outside_ball(q, position(q, around_ctx), sites[k], around_ctx, options.exact_maximality,
                         out.exact_vertex_tests, pd))
          worst = std::max(worst, pd);
      if (!(worst > -std::numeric_limits<double>::infinity())) continue;
      // The paper's rule from the spot's side: a sample whose ball the spot's region reaches.
      if (reach) {
        exact_polygon.clear();
        for (const SymbolicVertex& q : polygon) exact_polygon.push_back(exact_position(q, around_ctx));
        if (reach->covers(t, exact_polygon, k, kReachCoverDepth, kReachCoverBudget)) {
          ++out.polygons_covered_from_spot_side;
          continue;
        }
      }
      out.maximal.fail(fmt::format("triangle {}: a point {:.4g}·r_k from sample k = {}, the nearest in power of "
                                   "the {} around, is in no disk reaching it nor in its cell's ball{} (uncovered)",
                                   t, std::sqrt(std::max(0.0, 1 + worst / sites[k].w)), k, a.size(),
                                   reach ? ", nor within r_s of a sample s its ball's region reaches" : ""));
      covered = false;
    }
    if (covered) ++out.triangles_covered_by_other_disks;
  }
}

// diagram_covers: the polygons' areas (area_sum, in doubles) fill each triangle. The sums are a
// filter. A triangle they leave in doubt is decided with exact areas: on a sliver (CGAL's mpi.off
// refined: areas of 1.8e-7 at coordinates of 10) the rounding of the vertex positions alone is
// above 1e-9 of the area.
void check_diagram_covers(const SurfaceMesh& mesh, const Diagram& d, const std::vector<double>& area_sum,
                          MpsVerification& out) {
  const SymbolicContext ctx = d.context(mesh);
  std::unique_ptr<verify_detail::ExactVertices> exact;
  std::vector<const verify_detail::ExactVertex*> points;
  std::vector<int> ids;  // a polygon's vertices, all indexed before any is pointed to (indexing may reallocate)
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    ++out.diagram_covers.checked;
    const double a = mesh.triangle_area(t);
    if (std::abs(area_sum[t] - a) <= 1e-9 * a) continue;
    if (!exact) exact = std::make_unique<verify_detail::ExactVertices>(ctx);
    const Triangle& tri = mesh.triangle(t);
    std::array<const verify_detail::ExactVertex*, 3> corners;
    std::array<int, 3> corner_ids;
    for (int c = 0; c < 3; ++c) corner_ids[c] = exact->index(SymbolicVertex::mesh_vertex(tri[c]));
    for (int c = 0; c < 3; ++c) corners[c] = &(*exact)[corner_ids[c]];
    const verify_detail::Frame f = verify_detail::triangle_frame(mesh, t, corners);
    bool covered = f.valid;
    if (covered) {
      points.assign(corners.begin(), corners.end());
      const verify_detail::Q whole = verify_detail::twice_area(points, f);
      verify_detail::Q sum = 0;
      for (int k = d.triangle_offsets[t]; k < d.triangle_offsets[t + 1] && covered; ++k) {
        const CellPolygon& cp = d.polygons[k];
        const SymbolicVertex* q = d.polygon_vertices(cp);
        ids.resize(cp.vertex_count);
        for (int j = 0; j < cp.vertex_count; ++j) ids[j] = exact->index(q[j]);
        points.clear();
        for (int id : ids) {
          covered = covered && (*exact)[id].valid;
          points.push_back(&(*exact)[id]);
        }
        if (covered) sum += verify_detail::twice_area(points, f);
      }
      covered = covered && sum == whole;
    }
    if (!covered)
      out.diagram_covers.fail(fmt::format("triangle {}: polygons cover {:.9g} of area {:.9g}", t, area_sum[t], a));
  }
}

// Maximality: every point p of the surface is covered — it lies in the ball of the sample whose
// LRPD cell holds it (the paper's test: cell minus disk), or in the disk of a sample whose local
// region reaches p's triangle t (the conflict rule: no dart may go there). Triangle by triangle:
// - when every LRPD polygon of t lies in its cell's ball, t is covered;
// - otherwise t is decided on the power diagram of A(t) = the cells with a polygon in t plus the
//   samples whose disk reaches t, clipped exactly: a point lies in one of these balls iff it lies
//   in the ball of the one whose power cell holds it, so they cover t iff every such polygon lies
//   in its own ball. Since the cell holding p in the LRPD is the least of t's candidates in power
//   distance, the least of A(t) at p is the less of it and of the disks reaching t: A(t)'s balls
//   hold p iff p is covered in the sense above.
// The second case is where a point of a cell outside its ball lies in the disk of a sample that
// is no LRPD candidate of t (its cell was kept connected, or its power cell has a piece there the
// LRPD does not have).
void check_maximality(const SurfaceMesh& mesh, const Samples& s, const Diagram& d, const SampleDisks& disks,
                      const std::vector<std::vector<int>>& sample_triangles, const MpsVerifyOptions& options,
                      MpsVerification& out) {
  std::vector<double> area_sum;
  const std::vector<int> undecided = scan_polygons(mesh, s, d, disks, options, area_sum, out);
  out.maximal.checked = mesh.triangle_count();
  decide_undecided(mesh, s, d, disks, sample_triangles, options, undecided, out);
  check_diagram_covers(mesh, d, area_sum, out);
}

}  // namespace

nlohmann::json MpsVerification::to_json() const {
  return {{"passed", passed},
          {"time_s", time_s},
          {"min_distance_ratio", min_distance_ratio},
          {"close_pairs_not_local", close_pairs_not_local},
          {"one_sided_close_pairs", one_sided_close_pairs},
          {"conflict", facing_cut ? "close-across-turns" : "reach"},
          {"close_pairs_local_past_facing_cut", facing_cut ? nlohmann::json(close_pairs_local_past_facing_cut) : nlohmann::json(nullptr)},
          {"exact_vertex_tests", exact_vertex_tests},
          {"polygons_outside_own_ball", polygons_outside_own_ball},
          {"triangles_covered_by_other_disks", triangles_covered_by_other_disks},
          {"polygons_of_remote_balls", polygons_of_remote_balls},
          {"polygons_covered_from_spot_side", polygons_covered_from_spot_side},
          {"properties",
           {{"min_distance", min_distance.to_json()},
            {"maximal", maximal.to_json()},
            {"diagram_covers", diagram_covers.to_json()}}}};
}

std::string MpsVerification::summary() const {
  return min_distance.summary_line("min_distance") + maximal.summary_line("maximal") +
         diagram_covers.summary_line("diagram_covers");
}

namespace {

void check_mps_samples(const SurfaceMesh& mesh, const Samples& samples) {
  if (samples.size() == 0) throw InputError("no samples to verify");
  if (static_cast<int>(samples.weights.size()) != samples.size())
    throw InputError("a Poisson-disk sampling needs a weight (radius²) for every sample");
  lrvd::check_samples(mesh, samples);
  for (int i = 0; i < samples.size(); ++i)
    if (!(samples.weights[i] >= 0)) throw InputError(fmt::format("sample {} has a negative weight (radius²)", i));
}

}  // namespace

MpsVerification verify_mps(const SurfaceMesh& mesh, const Samples& samples, const Diagram& lrpd,
                           const MpsVerifyOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  check_mps_samples(mesh, samples);
  if (!is_power(lrpd.kind) || lrpd.sample_count != samples.size() || static_cast<int>(lrpd.sites.size()) != samples.size())
    throw InputError("the maximality check needs a power diagram (LRPD) of these samples");
  if (const std::string error = diagram_layout_error(lrpd, mesh); !error.empty())
    throw InputError("verify_mps: the LRPD does not fit the mesh: " + error);
  MpsVerification out;
  out.facing_cut = options.facing_cut;
  LocalRegions regions(mesh);
  const std::vector<std::vector<int>> triangles = sample_triangles(samples, regions);
  const SampleDisks disks(samples, regions, options.facing_cut);
  check_min_distance(mesh, samples, disks, regions, triangles, options.facing_cut, out);
  check_maximality(mesh, samples, lrpd, disks, triangles, options, out);
  out.passed = out.min_distance.passed && out.maximal.passed && out.diagram_covers.passed;
  out.time_s = seconds_since(start);
  return out;
}

MpsVerification verify_mps(const SurfaceMesh& mesh, const Samples& samples, const std::function<Diagram()>& compute_lrpd,
                           const MpsVerifyOptions& options, Diagram* lrpd_out) {
  const auto start = std::chrono::steady_clock::now();
  check_mps_samples(mesh, samples);
  MpsVerification out;
  out.facing_cut = options.facing_cut;
  Diagram lrpd;
  LocalRegions regions(mesh);
  const std::vector<std::vector<int>> triangles = sample_triangles(samples, regions);
  std::optional<SampleDisks> disks;
  // The diagram and the distance checks read only the mesh and the samples.
  tbb::parallel_invoke(
      [&] { lrpd = compute_lrpd(); },
      [&] {
        disks.emplace(samples, regions, options.facing_cut);
        check_min_distance(mesh, samples, *disks, regions, triangles, options.facing_cut, out);
      });
  check_maximality(mesh, samples, lrpd, *disks, triangles, options, out);
  out.passed = out.min_distance.passed && out.maximal.passed && out.diagram_covers.passed;
  if (lrpd_out) *lrpd_out = std::move(lrpd);
  out.time_s = seconds_since(start);
  return out;
}

}  // namespace lrvd
