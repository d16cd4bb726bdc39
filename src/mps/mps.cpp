// Maximal Poisson-disk sampling (paper §4.2): initialisation (radius field, edge splitting to
// twice the radius or, as the paper does, to r_min; area table), dart throwing with
// triangle-based conflict checks, then gap detection with the LRPD and darts into the gaps until
// none is left. The conflict rule is in docs/algorithms/mps.md.
#include "mps/mps.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <queue>
#include <unordered_map>

#include <fmt/format.h>

#include "common/error.h"
#include "common/timing.h"
#include "mesh/curvature.h"
#include "mps/mps_gaps.h"
#include "mps/mps_sampler.h"
#include "voronoi/lrvd.h"

namespace lrvd {

using namespace mps_detail;

namespace {

using Clock = std::chrono::steady_clock;

//! Walker's alias table: an index with probability proportional to its weight in O(1).
class AliasTable {
 public:
  explicit AliasTable(const std::vector<double>& weights) : probability_(weights.size()), alias_(weights.size()) {
    const size_t n = weights.size();
    double sum = 0;
    for (double w : weights) sum += w;
    // The scaled weights live in probability_: an index's weight is final once it leaves `small`.
    std::vector<double>& scaled = probability_;
    std::vector<int> small, large;
    small.reserve(n);
    large.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      scaled[i] = weights[i] * static_cast<double>(n) / sum;
      (scaled[i] < 1 ? small : large).push_back(static_cast<int>(i));
    }
    while (!small.empty() && !large.empty()) {
      const int s = small.back(), l = large.back();
      small.pop_back();
      alias_[s] = l;
      scaled[l] -= 1 - scaled[s];
      if (scaled[l] < 1) {
        large.pop_back();
        small.push_back(l);
      }
    }
    for (int i : large) probability_[i] = 1, alias_[i] = i;
    for (int i : small) probability_[i] = 1, alias_[i] = i;
  }
  int pick(Random& random) const {
    const double u = random.uniform() * static_cast<double>(probability_.size());
    const int i = std::min(static_cast<int>(u), static_cast<int>(probability_.size()) - 1);
    return (u - i) < probability_[i] ? i : alias_[i];
  }

 private:
  std::vector<double> probability_;
  std::vector<int> alias_;
};

// A dart: a point of triangle t, uniform by area.
Vec3 dart_in_triangle(const SurfaceMesh& mesh, int t, Random& random, Vec3& bary) {
  const double u1 = random.uniform(), u2 = random.uniform();
  return point_in_triangle(mesh, t, u1, u2, bary);
}

//! Feature-first sampling: samples on the mesh's corners and along its feature lines (boundary
//! edges, and edges whose triangles' normals are more than `angle` apart) before any dart on the
//! surface (docs/algorithms/mps.md, "Features"). Along a line between corners the samples are spread evenly
//! at kFeatureSpacing times the local radius: two neighbours on a line less than √2 r apart meet
//! at their midpoint whatever sample lies off the line (one at least r from both is farther from
//! it), so each feature sample's cell reaches its neighbours' along the line and the LRRT follows
//! it. Every one goes through the sampler's own test, so the minimum distance holds as for any
//! other sample; a line too short for the spacing keeps the gap for the surface's darts. Returns
//! the samples placed.
constexpr double kFeatureSpacing = 1.2;
constexpr double kFeatureSlide = 0.5, kFeatureSlideStep = 0.05;  // in radii
int sample_features(const SurfaceMesh& m, Sampler& sampler, double angle_deg) {
  const double cos_limit = std::cos(angle_deg * M_PI / 180.0);
  const DiskIndex& disks = sampler.disks();
  struct Edge {
    int t, e, a, b;
  };
  std::vector<Edge> edges;
  std::vector<std::vector<int>> at_vertex(m.vertex_count());  // the feature edges at each vertex
  for (int t = 0; t < m.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int n = m.neighbor(t, e);
      if (n >= 0 && (n < t || dot(disks.normal(t), disks.normal(n)) >= cos_limit)) continue;
      const Triangle& tri = m.triangle(t);
      const int a = tri[e], b = tri[(e + 1) % 3];
      at_vertex[a].push_back(static_cast<int>(edges.size()));
      at_vertex[b].push_back(static_cast<int>(edges.size()));
      edges.push_back({t, e, a, b});
    }
  if (edges.empty()) return 0;
  const int before = disks.size();
  // A point of edge k at `u` from its end a to its end b (exactly on the edge: its region grows on
  // both sides, Sampler::region_of).
  auto insert_on = [&](int k, double u) {
    const Edge& g = edges[k];
    Vec3 bary;
    bary[g.e] = 1 - u;
    bary[(g.e + 1) % 3] = u;
    return sampler.try_insert((1 - u) * m.position(g.a) + u * m.position(g.b), g.t, bary);
  };
  // Corners, the sharpest first: a vertex with other than two feature edges, or with two that
  // turn by more than the feature angle.
  std::vector<char> corner(m.vertex_count(), 0);
  std::vector<std::pair<double, int>> corners;  // (cosine of the angle between the two edges, vertex)
  for (int v = 0; v < m.vertex_count(); ++v) {
    if (at_vertex[v].empty()) continue;
    double c = 1;
    if (at_vertex[v].size() == 2) {
      Vec3 dir[2];
      for (int k = 0; k < 2; ++k) {
        const Edge& g = edges[at_vertex[v][k]];
        const Vec3 d = m.position(g.a == v ? g.b : g.a) - m.position(v);
        dir[k] = d / norm(d);
      }
      c = dot(dir[0], dir[1]);
      if (c <= -cos_limit) continue;  // nearly straight on
    }
    corner[v] = 1;
    corners.push_back({-c, v});
  }
  std::sort(corners.begin(), corners.end());
  for (const auto& [c, v] : corners) insert_on(at_vertex[v][0], edges[at_vertex[v][0]].a == v ? 0.0 : 1.0);
  // The lines: from each corner along each of its edges to the next corner, then the closed loops
  // without one. Each is cut into pieces of kFeatureSpacing radii, the radius linear along edges.
  std::vector<char> used(edges.size(), 0);
  std::vector<std::pair<int, bool>> line;  // edges, and whether each is walked from b to a
  auto walk = [&](int v, int k) {
    line.clear();
    while (!used[k]) {
      used[k] = 1;
      const bool reverse = edges[k].b == v;
      line.push_back({k, reverse});
      v = reverse ? edges[k].a : edges[k].b;
      if (corner[v] || at_vertex[v].size() != 2) break;
      k = at_vertex[v][0] == k ? at_vertex[v][1] : at_vertex[v][0];
    }
    // Length in radii of each edge: the integral of 1/r, r linear from r0 to r1.
    std::vector<double> span(line.size());
    double total = 0;
    for (size_t i = 0; i < line.size(); ++i) {
      const Edge& g = edges[line[i].first];
      const double r0 = sampler.radius_at(g.a), r1 = sampler.radius_at(g.b);
      const double length = distance(m.position(g.a), m.position(g.b));
      span[i] = std::abs(r1 - r0) > 1e-12 * r0 ? length * std::log(r1 / r0) / (r1 - r0) : length / r0;
      total += span[i];
    }
    const bool closed = !corner[v];  // a loop back to its first vertex, which is no corner
    // The point `at` radii along the line, by the same integral inverted in its edge.
    auto insert_at = [&](double at) {
      size_t i = 0;
      double start = 0;  // radii walked before edge i
      while (i + 1 < line.size() && start + span[i] < at) start += span[i++];
      const Edge& g = edges[line[i].first];
      const double x = std::clamp(at - start, 0.0, span[i]);
      const double r0 = sampler.radius_at(line[i].second ? g.b : g.a), r1 = sampler.radius_at(line[i].second ? g.a : g.b);
      const double length = distance(m.position(g.a), m.position(g.b));
      if (!(span[i] > 0)) return insert_on(line[i].first, line[i].second ? 1.0 : 0.0);  // an edge of length 0
      double f = x / span[i];  // fraction of the edge, from its walked start
      if (std::abs(r1 - r0) > 1e-12 * r0) f = r0 * std::expm1(x * (r1 - r0) / length) / (r1 - r0);
      f = std::clamp(f, 0.0, 1.0);
      return insert_on(line[i].first, line[i].second ? 1 - f : f);
    };
    // One sample after the other, each at an even share of what is left; one refused (too close
    // to a sample of another line at a sharp corner) slides on by small steps.
    double at = 0;
    if (closed) insert_at(0);
    for (;;) {
      const double left = total - at;
      const long pieces = std::lround(left / kFeatureSpacing);
      if (pieces <= 1) break;
      const double target = at + left / static_cast<double>(pieces);
      at = target;
      for (double slide = 0; slide <= kFeatureSlide; slide += kFeatureSlideStep)
        if (insert_at(target + slide)) {
          at = target + slide;
          break;
        }
    }
  };
  for (const auto& [c, v] : corners)
    for (int k : at_vertex[v])
      if (!used[k]) walk(v, k);
  for (int k = 0; k < static_cast<int>(edges.size()); ++k)
    if (!used[k]) walk(edges[k].a, k);
  return disks.size() - before;
}

}  // namespace

double expected_sample_count(const SurfaceMesh& mesh, double radius) {
  return mesh.area() / (std::sqrt(3.0) / 2 * radius * radius);
}

std::vector<double> adaptive_radius_field(const SurfaceMesh& mesh, double r_min, const MpsOptions& options) {
  const int nv = mesh.vertex_count();
  const double r_max = r_min * std::max(1.0, options.max_radius_ratio);
  std::vector<double> kappa = mean_curvature(mesh);
  // Two passes of neighbour averaging: the cotangent estimate is noisy on scanned meshes.
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<double> next(nv);
    for (int v = 0; v < nv; ++v) {
      double sum = kappa[v];
      for (const int* u = mesh.vertex_neighbors_begin(v); u != mesh.vertex_neighbors_end(v); ++u) sum += kappa[*u];
      next[v] = sum / (1.0 + (mesh.vertex_neighbors_end(v) - mesh.vertex_neighbors_begin(v)));
    }
    kappa.swap(next);
  }
  std::vector<double> r(nv);
  const double f = std::max(options.curvature_fraction, 1e-6);
  for (int v = 0; v < nv; ++v) {
    const double c = kappa[v] * r_max / f;
    r[v] = std::max(r_min, r_max / std::sqrt(1 + c * c));
  }
  // Gradation: r(v) <= r(u) + g·|uv| along every edge (Dijkstra from the smallest radii).
  const double g = std::max(options.gradation, 0.0);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int v = 0; v < nv; ++v) queue.emplace(r[v], v);
  while (!queue.empty()) {
    const auto [rv, v] = queue.top();
    queue.pop();
    if (rv > r[v]) continue;
    for (const int* u = mesh.vertex_neighbors_begin(v); u != mesh.vertex_neighbors_end(v); ++u) {
      const double cand = rv + g * distance(mesh.position(*u), mesh.position(v));
      if (cand < r[*u]) {
        r[*u] = cand;
        queue.emplace(cand, *u);
      }
    }
  }
  return r;
}

MpsResult maximal_poisson_disk_sampling(const SurfaceMesh& mesh, const MpsOptions& options) {
  // Relative to the longest side: past 10 one disk covers any sheet many times over (and a radius
  // whose square overflows would reach the exact tests as infinity).
  if (!(options.radius > 0) || !(options.radius <= kMaxMpsRadius))
    throw InputError(fmt::format("the Poisson-disk radius must be a positive number up to {:g} (relative to the longest "
                                 "bounding-box side), got {}",
                                 kMaxMpsRadius, options.radius));
  if (!(options.split_factor >= 1) || !std::isfinite(options.split_factor))
    throw InputError(fmt::format("the split factor must be a number of at least 1 (got {})", options.split_factor));
  if (options.sample_features && !(options.feature_angle > 0 && options.feature_angle < 180))
    throw InputError(fmt::format("the feature angle must be between 0 and 180 degrees (got {})", options.feature_angle));
  if (options.adaptive) {
    if (!(options.max_radius_ratio >= 1) || !(options.max_radius_ratio <= 1e6))
      throw InputError(fmt::format("the adaptive radius ratio r_max / r_min must be a number from 1 to 1e6 (got {})",
                                   options.max_radius_ratio));
    if (!(options.curvature_fraction > 0) || !std::isfinite(options.curvature_fraction))
      throw InputError(fmt::format("the adaptive curvature fraction must be a positive number (got {})",
                                   options.curvature_fraction));
    if (!(options.gradation > 0) || !std::isfinite(options.gradation))
      throw InputError(fmt::format("the adaptive gradation must be a positive number (got {})", options.gradation));
  }
  if (options.max_consecutive_rejections < 1)
    throw InputError(fmt::format("max_consecutive_rejections must be at least 1 (got {})",
                                 options.max_consecutive_rejections));
  if (options.max_gap_rounds < 0)
    throw InputError(fmt::format("max_gap_rounds may not be negative (got {})", options.max_gap_rounds));
  if (!(options.max_expected_samples > 0))
    throw InputError(fmt::format("max_expected_samples must be a positive number (got {})", options.max_expected_samples));
  if (mesh.triangle_count() == 0) throw InputError("the mesh has no triangles");
  require_workable_model(mesh, "Poisson-disk sampling");
  auto progress = [&](const std::string& message) {
    if (options.on_progress) options.on_progress(message);
  };
  const auto start = Clock::now();
  MpsResult result;
  const BoundingBox box = mesh.bounding_box();
  result.scale = std::max({box.max.x - box.min.x, box.max.y - box.min.y, box.max.z - box.min.z});
  const double r_min = options.radius * result.scale;
  result.radius = r_min;
  const double expected = expected_sample_count(mesh, r_min);
  if (!(expected <= options.max_expected_samples))
    throw InputError(fmt::format("radius {} is too small for this mesh: about {:.3g} samples would be needed "
                                 "(limit {:.3g}); use a larger radius",
                                 options.radius, expected, options.max_expected_samples));

  // Initialisation: split long edges (§4.2, first change). The paper splits to r_min everywhere
  // (MinRadius), so that a triangle holds at most one sample. The sampler keeps any number per
  // triangle, and the LRPD, the darts' regions and the gap pieces cost by the triangle, so the
  // default splits to split_factor times the radius at the edge's ends: a few triangles a sample.
  const bool to_field = options.refinement == MpsRefinement::RadiusField;
  const double factor = to_field ? options.split_factor : 1.0;
  progress(to_field ? fmt::format("splitting edges longer than {:g} times the radius at their ends (r_min = {:.4g})",
                                  factor, r_min)
                    : fmt::format("splitting edges longer than r_min = {:.4g}", r_min));
  std::vector<double> vertex_radius;
  // The field is linear over each input triangle; the refinement carries it to the new vertices.
  if (options.adaptive) vertex_radius = adaptive_radius_field(mesh, r_min, options);
  // Not `result.mesh = refine ? refine_long_edges(...) : mesh`: that conditional is a const
  // prvalue, so the refined mesh would be copied into place rather than moved.
  if (mesh.max_edge_length() <= factor * r_min) {
    result.mesh = mesh;
  } else if (to_field && options.adaptive) {
    // Scaled to the lengths and back: with a power of two for the factor (the default) the radii
    // are exactly the field the refinement carries to the new vertices.
    for (double& x : vertex_radius) x *= factor;
    result.mesh = refine_to_length_field(mesh, vertex_radius, options.refine_order);
    for (double& x : vertex_radius) x /= factor;
  } else {
    result.mesh = refine_long_edges(mesh, factor * r_min, options.adaptive ? &vertex_radius : nullptr,
                                    options.refine_order);
  }
  result.max_radius = options.adaptive ? *std::max_element(vertex_radius.begin(), vertex_radius.end()) : r_min;
  const SurfaceMesh& m = result.mesh;
  Sampler sampler(m, r_min, std::move(vertex_radius), options.conflict == MpsConflict::Facing);
  const std::vector<double>& areas = sampler.disks().triangle_areas();
  const AliasTable by_area(areas);
  Random random(options.seed);
  result.time_s.init = seconds_since(start);

  // Dart throwing until too many consecutive rejections.
  progress("dart throwing");
  const auto dart_start = Clock::now();
  if (options.sample_features) {
    progress(fmt::format("samples on the corners and feature lines (edges with normals more than {:g}° apart, and the boundary)",
                         options.feature_angle));
    result.feature_samples = sample_features(m, sampler, options.feature_angle);
  }
  const double sample_cap = 4 * expected + 1000;
  for (int rejections = 0; rejections < options.max_consecutive_rejections && sampler.disks().size() < sample_cap;) {
    const int t = by_area.pick(random);
    Vec3 bary;
    const Vec3 p = dart_in_triangle(m, t, random, bary);
    ++result.darts;
    if (sampler.try_insert(p, t, bary))
      rejections = 0;
    else
      ++rejections;
  }
  // Every component needs a sample before the LRPD (a small one may have been missed).
  {
    std::vector<char> has_sample(m.component_count(), 0);
    for (int i = 0; i < sampler.disks().size(); ++i) has_sample[m.triangle_components()[sampler.disks().triangle(i)]] = 1;
    for (int c = 0; c < m.component_count(); ++c) {
      if (has_sample[c]) continue;
      std::vector<int> tris;
      std::vector<double> weights;
      for (int t = 0; t < m.triangle_count(); ++t)
        if (m.triangle_components()[t] == c) tris.push_back(t), weights.push_back(areas[t]);
      const AliasTable in_component(weights);
      for (int attempt = 0; attempt < 10000; ++attempt) {
        const int t = tris[in_component.pick(random)];
        Vec3 bary;
        const Vec3 p = dart_in_triangle(m, t, random, bary);
        ++result.darts;
        if (sampler.try_insert(p, t, bary)) break;
      }
    }
  }
  result.dart_samples = sampler.disks().size();
  result.time_s.dart_throwing = seconds_since(dart_start);

  // Gap detection with the LRPD and gap filling (§4.2, third change).
  const auto gap_start = Clock::now();
  const bool local = options.gap_update == MpsGapUpdate::Local;
  GapSet gaps(m, sampler.disks(), local, 1e-15 * r_min * r_min);
  LrvdOptions lrpd_options;
  lrpd_options.weighted = true;
  std::vector<char> shapeless(m.triangle_count());  // triangles whose LRPD polygons need no shape
  lrpd_options.shapeless = &shapeless;
  GapLrpd lrpd;
  bool stale = true;  // the LRPD is not that of the current samples
  // With local updates the first LRPD only shows where the gaps are: the darts then close them
  // in disks reaching their triangles, which is coverage whatever cell a spot is in, so that LRPD
  // is computed without the connectivity restoration (on dragon_100k one or two rounds of it, each
  // a pass over the whole mesh). Only a round that places no sample decides through the cells
  // themselves (remote claims: spots in the ball of their cell), as verify_mps does on the
  // connected LRPD; such a decision is made only on an LRPD whose cells are connected.
  bool connected_cells = true;  // the LRPD's cells went through the connectivity restoration
  // After a round with local updates, the triangles that may still hold a gap (open_triangles()),
  // as a mask and as a list; empty: all of them.
  std::vector<char> focus;
  std::vector<int> open;
  for (int round = 0; round < options.max_gap_rounds; ++round) {
    if (stale) {
      progress(fmt::format("gap detection {}: LRPD of {} samples", round + 1, sampler.disks().size()));
      lrpd = {};  // the last round's diagram goes before the next one is built, not after
      // After a round with local updates only the open triangles are looked at: a few, as a rule
      // (pieces no dart fitted), for which the LRPD of the part of the mesh around them will do.
      if (!focus.empty() && compute_lrpd_around(m, sampler.disks(), open, focus, lrpd)) {
        result.part_lrpd_triangles += lrpd.part.triangle_count();
      } else {
        // Gaps are looked for only in triangles that no disk covers (GapSet::extract), and after a
        // round with local updates only in the open ones: the other triangles' polygons need
        // their cells, not their shapes. A covered triangle stays covered.
        for (int t = 0; t < m.triangle_count(); ++t)
          shapeless[t] = sampler.disks().fully_covered(t) || (!focus.empty() && !focus[t]);
        lrpd_options.restore_connectivity = !(local && round == 0);
        lrpd.diagram = compute_lrvd(m, sampler.disks().samples(), lrpd_options);
      }
      connected_cells = lrpd_options.restore_connectivity || lrpd.on_part;
      ++result.lrpd_evaluations;
    }
    stale = true;
    gaps.extract(lrpd, focus.empty() ? nullptr : &focus);
    if (round == 0) result.gap_pieces = gaps.alive();
    // No piece left: every spot of the surface is in the ball of its LRPD cell or in a disk
    // reaching its triangle — also where the LRPD's cells alone do not show it (a polygon outside
    // its ball, inside the disk of a sample that is no candidate of the triangle).
    if (gaps.empty()) {
      result.gaps_closed = true;
      break;
    }
    progress(fmt::format("filling {} gap pieces", gaps.alive()));
    // With local updates a point drawn outside its piece's owner disk is a valid dart (uniform
    // radius) or almost always (adaptive), so the limit only ends hopeless rounds; the paper's
    // loop recomputes the LRPD after 300 rejections in a row.
    const std::int64_t limit = local ? std::max<std::int64_t>(100000, 1000 * std::int64_t(gaps.alive()))
                                     : options.max_consecutive_rejections;
    const int before = sampler.disks().size();
    for (std::int64_t rejections = 0; !gaps.empty() && rejections < limit;) {
      Vec3 p;
      int t = -1, piece = -1;
      ++result.darts;
      if (!gaps.draw(random, p, t, piece)) {
        ++rejections;
        continue;
      }
      if (!sampler.try_insert(p, t, barycentric_in_triangle(m, t, p))) {
        ++rejections;
        // Refused by a sample from the dart's side: where that sample's ball reaches it from
        // the whole piece, the sample covers the piece like a disk reaching it.
        if (sampler.refused_by() >= 0 && gaps.carve(piece, sampler.refused_by())) continue;
        if (local) gaps.dart_refused(piece);
        continue;
      }
      rejections = 0;
      ++result.gap_samples;
      gaps.update_after_insert(sampler.disks().size() - 1, sampler.last_region());
    }
    // Pieces dropped as too small to tell from rounding can still be real gaps (a sliver triangle
    // a disk's rim barely misses): a dart at each one's corner outside its disk, decided exactly
    // like any dart. Insertions split pieces, which may drop more; a few passes take those too.
    // The rest of such a piece is not tracked, so its triangle stays open, unless the corner lies
    // in a disk reaching the triangle.
    for (int pass = 0; pass < 4; ++pass) {
      const std::vector<GapSet::Dust> dust = gaps.take_dust();
      const int placed = result.dust_samples;
      for (const GapSet::Dust& d : dust) {
        ++result.darts;
        if (!sampler.try_insert(d.point, d.triangle, barycentric_in_triangle(m, d.triangle, d.point))) {
          // A disk reaching the triangle covers the corner: the noise is at that disk's rim, and
          // the triangle closes as it does when no piece was given up. Refused by the radius
          // conditions instead: the corner may be a gap no dart fits.
          if (!sampler.disks().in_some_disk(d.point, d.triangle) && sampler.refused_by() < 0) gaps.note_open(d.triangle);
          continue;
        }
        gaps.note_open(d.triangle);
        ++result.gap_samples;
        ++result.dust_samples;
        gaps.update_after_insert(sampler.disks().size() - 1, sampler.last_region());
      }
      if (result.dust_samples == placed) break;
    }
    for (const GapSet::Dust& d : gaps.take_dust()) gaps.note_open(d.triangle);  // untried after the passes
    // Local updates that emptied the gaps leave every spot covered by a disk reaching it, which
    // stays so. Pieces given up (darts refused for the adaptive radius) need another LRPD to see
    // whether a disk has covered them since; every spot outside the open triangles is covered
    // for good, so that LRPD is read, and given shapes, only in those.
    if (local && gaps.empty() && gaps.given_up() == 0) {
      result.gaps_closed = true;
      break;
    }
    if (local) {
      open = gaps.open_triangles();
      focus.assign(m.triangle_count(), 0);
      for (int t : open) focus[t] = 1;
    }
    // No progress: this LRPD is that of the final samples. Closed when the pieces no dart fits
    // are only where the balls of their LRPD cells cover (remote claims).
    if (sampler.disks().size() == before) {
      if (!connected_cells) continue;  // the next LRPD (of the open triangles' part) decides
      // Adaptive, spots no dart fits: outside their cells' balls, where the power-cell condition
      // against a sample across (another sheet, a big disk past a fold) leaves no radius. Once, the
      // required pieces of this same LRPD are tried again with that condition kept only against
      // the samples facing alike.
      if (options.adaptive && gaps.required_pieces() > 0 && !gaps.required_only()) {
        progress(fmt::format("{} gap pieces no dart fits: power-cell condition against samples facing alike only",
                             gaps.required_pieces()));
        sampler.allow_power_cell_exceptions();
        gaps.set_required_only();
        stale = false;
        continue;
      }
      result.gaps_closed = gaps.required_pieces() == 0;
      break;
    }
  }
  result.dropped_gap_pieces = gaps.dropped();
  result.carved_gap_pieces = gaps.carved();
  result.clamped_radii = sampler.clamped();
  result.power_cell_exceptions = sampler.power_cell_exceptions();
  result.samples = sampler.disks().samples();
  result.radii.resize(result.samples.size());
  for (int i = 0; i < result.samples.size(); ++i) result.radii[i] = std::sqrt(result.samples.weights[i]);
  result.time_s.gap_filling = seconds_since(gap_start);
  result.time_s.total = seconds_since(start);
  return result;
}

}  // namespace lrvd
