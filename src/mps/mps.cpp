// Maximal Poisson-disk sampling (paper §4.2): initialisation (radius field, edge splitting to
// twice the radius or, as the paper does, to r_min; area table), dart throwing with
// triangle-based conflict checks, then gap detection (with local updates first on the power
// diagrams of the disks reaching each triangle, then with the LRPD) and darts into the gaps until
// none is left. The conflict rule is in docs/algorithms/mps.md.
#include "mps/mps.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <queue>

#include <fmt/format.h>

#include "common/error.h"
#include "common/timing.h"
#include "mesh/closest_point.h"
#include "mesh/curvature.h"
#include "mesh/refine.h"
#include "mps/mps_disks.h"
#include "mps/mps_features.h"
#include "mps/mps_gap_reach.h"
#include "mps/mps_gaps.h"
#include "mps/mps_lrpd_part.h"
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

}  // namespace

void limit_radius_gradation(const SurfaceMesh& mesh, double gradation, std::vector<double>& r) {
  const double g = std::max(gradation, 0.0);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int v = 0; v < mesh.vertex_count(); ++v) queue.emplace(r[v], v);
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
}

double expected_sample_count(const SurfaceMesh& mesh, const std::vector<double>& vertex_radius) {
  double count = 0;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    double r = 0;
    for (int v : mesh.triangle(t)) r += vertex_radius[v] / 3;
    count += mesh.triangle_area(t) / (std::sqrt(3.0) / 2 * r * r);
  }
  return count;
}

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
  limit_radius_gradation(mesh, options.gradation, r);
  return r;
}

namespace {

void check_options(const MpsOptions& options) {
  // Relative to the longest side: past 10 one disk covers any sheet many times over (and a radius
  // whose square overflows would reach the exact tests as infinity).
  if (!(options.radius > 0) || !(options.radius <= kMaxMpsRadius))
    throw InputError(fmt::format("the Poisson-disk radius must be a positive number up to {:g} (relative to the longest "
                                 "bounding-box side), got {}",
                                 kMaxMpsRadius, options.radius));
  if (!(options.split_factor >= 1) || !std::isfinite(options.split_factor))
    throw InputError(fmt::format("the split factor must be a number of at least 1 (got {})", options.split_factor));
  if (!(options.feature_angle > 0 && options.feature_angle < 180))
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
}

//! The stages of one sampling, in the order run() calls them; the state they share is held here.
class PoissonDiskSampling {
 public:
  PoissonDiskSampling(const SurfaceMesh& mesh, const MpsOptions& options)
      : input_(mesh), options_(options), local_(options.gap_update == MpsGapUpdate::Local),
        variable_(options.adaptive || !options.radius_field.empty()), random_(options.seed) {}

  MpsResult run() {
    start_ = Clock::now();
    cpu_start_ = process_cpu_seconds();
    initialise();
    throw_darts();
    fill_gaps();
    return std::move(result_);
  }

 private:
  void progress(const std::string& message) const {
    if (options_.on_progress) options_.on_progress(message);
  }

  //! Radius, radius field, edge splitting (§4.2, first change), the sampler and the area table.
  void initialise() {
    const BoundingBox box = input_.bounding_box();
    result_.scale = std::max({box.max.x - box.min.x, box.max.y - box.min.y, box.max.z - box.min.z});
    const std::vector<double>& field = options_.radius_field;
    if (!field.empty() && field.size() != static_cast<std::size_t>(input_.vertex_count()))
      throw InputError(fmt::format("the radius field has {} values for {} vertices: it needs one per vertex",
                                   field.size(), input_.vertex_count()));
    for (double x : field)
      if (!(x > 0) || !std::isfinite(x))
        throw InputError(fmt::format("the radius field's values must be positive numbers (got {})", x));
    r_min_ = field.empty() ? options_.radius * result_.scale : *std::min_element(field.begin(), field.end());
    result_.radius = r_min_;
    expected_ = field.empty() ? expected_sample_count(input_, r_min_) : expected_sample_count(input_, field);
    if (!(expected_ <= options_.max_expected_samples))
      throw InputError(fmt::format("radius {} is too small for this mesh: about {:.3g} samples would be needed "
                                   "(limit {:.3g}); use a larger radius",
                                   options_.radius, expected_, options_.max_expected_samples));
    std::vector<double> vertex_radius;
    // The field is linear over each input triangle; the refinement carries it to the new vertices.
    if (!field.empty())
      vertex_radius = field;
    else if (options_.adaptive)
      vertex_radius = adaptive_radius_field(input_, r_min_, options_);
    count_features();
    refine(vertex_radius);
    result_.max_radius = variable_ ? *std::max_element(vertex_radius.begin(), vertex_radius.end()) : r_min_;
    sampler_.emplace(result_.mesh, r_min_, std::move(vertex_radius), options_.conflict == MpsConflict::CloseAcrossTurns);
    by_area_.emplace(sampler_->disks().triangle_areas());
    result_.time_s.init = seconds_since(start_);
  }

  //! The input's feature lines, counted on the mesh the user gave (the refinement only splits them).
  void count_features() {
    const FeatureLines f = find_feature_lines(input_, options_.feature_angle);
    result_.feature_edges = static_cast<int>(f.edges.size());
    result_.boundary_edges = f.boundary_edges;
    result_.feature_corners = static_cast<int>(f.corners.size());
  }

  //! result_.mesh = the input with its long edges split. The paper splits to r_min everywhere
  //! (MinRadius), so that a triangle holds at most one sample. The sampler keeps any number per
  //! triangle, and the LRPD, the darts' regions and the gap pieces cost by the triangle, so the
  //! default splits to split_factor times the radius at the edge's ends: a few triangles a sample.
  //! The adaptive radius field goes along to the new vertices.
  void refine(std::vector<double>& vertex_radius) {
    const bool to_field = options_.refinement == MpsRefinement::RadiusField;
    const double factor = to_field ? options_.split_factor : 1.0;
    progress(to_field ? fmt::format("splitting edges longer than {:g} times the radius at their ends (r_min = {:.4g})",
                                    factor, r_min_)
                      : fmt::format("splitting edges longer than r_min = {:.4g}", r_min_));
    // Not `result_.mesh = refine ? refine_long_edges(...) : mesh`: that conditional is a const
    // prvalue, so the refined mesh would be copied into place rather than moved.
    if (input_.max_edge_length() <= factor * r_min_) {
      result_.mesh = input_;
    } else if (to_field && variable_) {
      // Scaled to the lengths and back: with a power of two for the factor (the default) the radii
      // are exactly the field the refinement carries to the new vertices.
      for (double& x : vertex_radius) x *= factor;
      result_.mesh = refine_to_length_field(input_, vertex_radius, options_.refine_order);
      for (double& x : vertex_radius) x /= factor;
    } else {
      result_.mesh = refine_long_edges(input_, factor * r_min_, variable_ ? &vertex_radius : nullptr,
                                       options_.refine_order);
    }
  }

  //! Samples on the features if asked and there are any, then darts until too many consecutive
  //! rejections (§4.2, second change), then a sample in every component the darts missed.
  void throw_darts() {
    progress("dart throwing");
    const auto dart_start = Clock::now();
    const SurfaceMesh& m = result_.mesh;
    place_first_samples();
    if (options_.sample_features && result_.feature_edges > 0) {
      progress(fmt::format("samples on {} feature edges ({} on the boundary, the others' normals more than {:g}° apart) "
                           "and {} corners",
                           result_.feature_edges, result_.boundary_edges, options_.feature_angle,
                           result_.feature_corners));
      result_.feature_samples = sample_features(m, *sampler_, options_.feature_angle, options_.feature_exclusions);
    }
    const double sample_cap = 4 * expected_ + 1000;
    for (int rejections = 0; rejections < options_.max_consecutive_rejections && sampler_->disks().size() < sample_cap;) {
      const int t = by_area_->pick(random_);
      Vec3 bary;
      const Vec3 p = dart_in_triangle(m, t, random_, bary);
      ++result_.darts;
      if (sampler_->try_insert(p, t, bary))
        rejections = 0;
      else
        ++rejections;
    }
    sample_missed_components();
    result_.dart_samples = sampler_->disks().size();
    result_.time_s.dart_throwing = seconds_since(dart_start);
  }

  //! MpsOptions::first_samples, each at its closest point of the refined mesh, through the
  //! sampler's test.
  void place_first_samples() {
    if (options_.first_samples.empty()) return;
    const ClosestPointIndex index(result_.mesh);
    int hint = -1;
    for (const Vec3& p : options_.first_samples) {
      const ClosestPoint c = index.query(p, hint);
      hint = c.triangle;
      result_.first_samples += sampler_->try_insert(c.point, c.triangle, c.barycentric);
    }
  }

  //! Every component needs a sample before the LRPD (a small one may have been missed).
  void sample_missed_components() {
    const SurfaceMesh& m = result_.mesh;
    const DiskIndex& disks = sampler_->disks();
    std::vector<char> has_sample(m.component_count(), 0);
    for (int i = 0; i < disks.size(); ++i) has_sample[m.triangle_components()[disks.triangle(i)]] = 1;
    for (int c = 0; c < m.component_count(); ++c) {
      if (has_sample[c]) continue;
      std::vector<int> tris;
      std::vector<double> weights;
      for (int t = 0; t < m.triangle_count(); ++t)
        if (m.triangle_components()[t] == c) tris.push_back(t), weights.push_back(disks.triangle_areas()[t]);
      const AliasTable in_component(weights);
      for (int attempt = 0; attempt < 10000; ++attempt) {
        const int t = tris[in_component.pick(random_)];
        Vec3 bary;
        const Vec3 p = dart_in_triangle(m, t, random_, bary);
        ++result_.darts;
        if (sampler_->try_insert(p, t, bary)) break;
      }
    }
  }

  //! Gap detection with the LRPD and gap filling (§4.2, third change), round after round until no
  //! gap is left or no dart fits the gaps left; then the result's counts and samples.
  void fill_gaps() {
    const auto gap_start = Clock::now();
    gaps_.emplace(result_.mesh, sampler_->disks(), local_, 1e-15 * r_min_ * r_min_);
    lrpd_options_.weighted = true;
    lrpd_options_.restore_connectivity = true;
    shapeless_.assign(result_.mesh.triangle_count(), 0);
    lrpd_options_.shapeless = &shapeless_;
    for (int round = 0; round < options_.max_gap_rounds; ++round)
      if (gap_round(round)) break;
    result_.dropped_gap_pieces = gaps_->dropped();
    result_.carved_gap_pieces = gaps_->carved();
    result_.clamped_radii = sampler_->clamped();
    result_.radii_below_reach = sampler_->below_reach();
    result_.power_cell_exceptions = sampler_->power_cell_exceptions();
    result_.samples = sampler_->disks().samples();
    result_.radii.resize(result_.samples.size());
    for (int i = 0; i < result_.samples.size(); ++i) result_.radii[i] = std::sqrt(result_.samples.weights[i]);
    result_.time_s.gap_filling = seconds_since(gap_start);
    result_.time_s.total = seconds_since(start_);
    result_.time_s.cpu_total = process_cpu_seconds() - cpu_start_;
  }

  //! One round: an LRPD (unless the last round's still holds), its gap pieces, darts into them and
  //! at the dust of dropped pieces. Returns true when the sampling is done. With local updates the
  //! first round's pieces only show where the gaps are: the darts then close them in disks reaching
  //! their triangles, which is coverage whatever cell a spot is in. Those pieces come from the
  //! power diagrams of the disks reaching each triangle, with no LRPD (GapSet::extract_from_disks);
  //! only a round that places no sample decides through the cells themselves (remote claims:
  //! spots in the ball of their cell), as verify_mps does on the connected LRPD, and only on an
  //! LRPD whose cells are connected.
  bool gap_round(int round) {
    GapSet& gaps = *gaps_;
    if (local_ && round == 0) {
      extract_first_gaps();
    } else {
      if (stale_) compute_gap_lrpd(round);
      gaps.extract(lrpd_, focus_.empty() ? nullptr : &focus_);
    }
    stale_ = true;
    if (round == 0) result_.gap_pieces = gaps.alive();
    // No piece left: every spot of the surface is in the ball of its LRPD cell or in a disk
    // reaching its triangle — also where the LRPD's cells alone do not show it (a polygon outside
    // its ball, inside the disk of a sample that is no candidate of the triangle).
    if (gaps.empty()) {
      result_.gaps_closed = true;
      return true;
    }
    progress(fmt::format("filling {} gap pieces", gaps.alive()));
    const int before = sampler_->disks().size();
    throw_gap_darts();
    place_dust();
    // Local updates that emptied the gaps leave every spot covered by a disk reaching it, which
    // stays so. Pieces given up (darts refused for the adaptive radius) need another LRPD to see
    // whether a disk has covered them since; every spot outside the open triangles is covered
    // for good, so that LRPD is read, and given shapes, only in those.
    if (local_ && gaps.empty() && gaps.given_up() == 0) {
      result_.gaps_closed = true;
      return true;
    }
    if (local_) {
      open_ = gaps.open_triangles();
      focus_.assign(result_.mesh.triangle_count(), 0);
      for (int t : open_) focus_[t] = 1;
    }
    return sampler_->disks().size() == before && decide_without_progress();
  }

  //! With local updates, the first round's pieces: from the power diagrams of the disks reaching
  //! each triangle no disk covers.
  void extract_first_gaps() {
    const DiskIndex& disks = sampler_->disks();
    progress(fmt::format("gap detection: power diagrams of the disks reaching each triangle, {} samples", disks.size()));
    std::vector<Site> sites(disks.size());
    for (int i = 0; i < disks.size(); ++i) sites[i] = Site{disks.center(i), disks.weight(i), i};
    gaps_->extract_from_disks(sites);
    connected_cells_ = false;  // no cells: a round without progress computes the LRPD
  }

  //! The LRPD of the current samples (with the connectivity restoration), of the whole mesh or of
  //! the part around the open triangles.
  void compute_gap_lrpd(int round) {
    const SurfaceMesh& m = result_.mesh;
    DiskIndex& disks = sampler_->disks();
    progress(fmt::format("gap detection {}: LRPD of {} samples", round + 1, disks.size()));
    lrpd_ = {};  // the last round's diagram goes before the next one is built, not after
    // After a round with local updates only the open triangles are looked at: a few, as a rule
    // (pieces no dart fitted), for which the LRPD of the part of the mesh around them will do.
    if (!focus_.empty() && compute_lrpd_around(m, disks, open_, focus_, lrpd_)) {
      result_.part_lrpd_triangles += lrpd_.part.triangle_count();
    } else {
      // Gaps are looked for only in triangles that no disk covers (GapSet::extract), and after a
      // round with local updates only in the open ones: the other triangles' polygons need
      // their cells, not their shapes. A covered triangle stays covered.
      for (int t = 0; t < m.triangle_count(); ++t) shapeless_[t] = disks.fully_covered(t) || (!focus_.empty() && !focus_[t]);
      lrpd_.diagram = compute_lrvd(m, disks.samples(), lrpd_options_);
    }
    connected_cells_ = true;
    ++result_.lrpd_evaluations;
  }

  //! Darts drawn uniformly over the gap pieces until they are used up or too many are refused.
  //! With local updates a point drawn outside its piece's owner disk is a valid dart (uniform
  //! radius) or almost always (adaptive), so the limit only ends hopeless rounds; the paper's
  //! loop recomputes the LRPD after 300 rejections in a row.
  void throw_gap_darts() {
    ReachGapSet& gaps = *gaps_;
    const std::int64_t limit = local_ ? std::max<std::int64_t>(100000, 1000 * std::int64_t(gaps.alive()))
                                      : options_.max_consecutive_rejections;
    for (std::int64_t rejections = 0; !gaps.empty() && rejections < limit;) {
      Vec3 p;
      int t = -1, piece = -1;
      ++result_.darts;
      if (!gaps.draw(random_, p, t, piece)) {
        ++rejections;
        continue;
      }
      if (!sampler_->try_insert(p, t, barycentric_in_triangle(result_.mesh, t, p))) {
        ++rejections;
        // Refused by a sample from the dart's side: where that sample's ball reaches it from
        // the whole piece, the sample covers the piece like a disk reaching it.
        if (sampler_->refused_by() >= 0 && gaps.carve(piece, sampler_->refused_by(), p)) continue;
        if (local_) gaps.dart_refused(piece);
        continue;
      }
      rejections = 0;
      ++result_.gap_samples;
      gaps.update_after_insert(sampler_->disks().size() - 1, sampler_->last_region());
    }
  }

  //! Pieces dropped as too small to tell from rounding can still be real gaps (a sliver triangle
  //! a disk's rim barely misses): a dart at each one's corner outside its disk, decided exactly
  //! like any dart. Insertions split pieces, which may drop more; a few passes take those too.
  //! The rest of such a piece is not tracked, so its triangle stays open, unless the corner lies
  //! in a disk reaching the triangle.
  void place_dust() {
    GapSet& gaps = *gaps_;
    const SurfaceMesh& m = result_.mesh;
    for (int pass = 0; pass < 4; ++pass) {
      const std::vector<GapSet::Dust> dust = gaps.take_dust();
      const int placed = result_.dust_samples;
      for (const GapSet::Dust& d : dust) {
        ++result_.darts;
        if (!sampler_->try_insert(d.point, d.triangle, barycentric_in_triangle(m, d.triangle, d.point))) {
          // A disk reaching the triangle covers the corner: the noise is at that disk's rim, and
          // the triangle closes as it does when no piece was given up. Refused by the radius
          // conditions instead: the corner may be a gap no dart fits.
          if (!sampler_->disks().in_some_disk(d.point, d.triangle) && sampler_->refused_by() < 0) gaps.note_open(d.triangle);
          continue;
        }
        gaps.note_open(d.triangle);
        ++result_.gap_samples;
        ++result_.dust_samples;
        gaps.update_after_insert(sampler_->disks().size() - 1, sampler_->last_region());
      }
      if (result_.dust_samples == placed) break;
    }
    for (const GapSet::Dust& d : gaps.take_dust()) gaps.note_open(d.triangle);  // untried after the passes
  }

  //! A round that placed no sample: this LRPD is that of the final samples. Closed when the pieces
  //! no dart fits are only where the balls of their LRPD cells cover (remote claims). Returns true
  //! when the sampling is done.
  bool decide_without_progress() {
    if (!connected_cells_) return false;  // the next LRPD (of the open triangles' part) decides
    ReachGapSet& gaps = *gaps_;
    const bool reach = !sampler_->disks().facing_cut();
    // Adaptive, spots no dart fits: outside their cells' balls, where the power-cell condition
    // against a sample across (another sheet, a big disk past a fold) leaves no radius. Once, the
    // required pieces of this same LRPD are tried again with that condition kept only against
    // the samples facing alike. By the paper's rule, uniform too: the round on the required pieces
    // alone lets certify_required() see them all.
    if ((variable_ || reach) && gaps.required_pieces() > 0 && !gaps.required_only()) {
      if (variable_) {
        progress(fmt::format("{} gap pieces no dart fits: power-cell condition against samples facing alike only",
                             gaps.required_pieces()));
        sampler_->allow_power_cell_exceptions();
      }
      gaps.set_required_only();
      stale_ = false;
      return false;
    }
    // By the paper's rule the pieces left may lie where a dart is refused from its own side only,
    // closer than r to a sample whose ball reaches round a rim or fold: certified against the
    // samples that refused their darts.
    if (gaps.required_pieces() == 0) {
      result_.gaps_closed = true;
    } else if (reach) {
      const int left = gaps.certify_required(
          [&](int t, const Vec3* q, int count, std::vector<int>& out) { samples_around(t, q, count, out); });
      result_.gaps_closed = left == 0;
      result_.certified_gap_pieces = gaps.certified();
    }
    return true;
  }

  //! The samples whose balls may meet polygon q (of triangle t) along a chain of triangles: those
  //! centred on the triangles that the ball about its centroid, its radius plus the largest
  //! sample radius wide, meets edge-connected to t.
  void samples_around(int t, const Vec3* q, int count, std::vector<int>& out) {
    Vec3 c{};
    for (int k = 0; k < count; ++k) c += q[k];
    c = c / static_cast<double>(count);
    double radius2 = 0;
    for (int k = 0; k < count; ++k) radius2 = std::max(radius2, squared_distance(c, q[k]));
    const double reach = std::sqrt(radius2) + result_.max_radius;
    DiskIndex& disks = sampler_->disks();
    for (int s : disks.met(c, t, reach * reach * (1 + 1e-9))) disks.for_each_center(s, [&](int j) { out.push_back(j); });
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

  const SurfaceMesh& input_;
  const MpsOptions& options_;
  const bool local_;  // MpsGapUpdate::Local
  const bool variable_;  // the radius varies: adaptive, or a radius field given
  Clock::time_point start_;
  double cpu_start_ = 0;
  MpsResult result_;
  double r_min_ = 0, expected_ = 0;  // absolute r_min, and the samples it is expected to take
  std::optional<Sampler> sampler_;   // on result_.mesh
  std::optional<AliasTable> by_area_;
  Random random_;
  // Gap filling.
  std::optional<ReachGapSet> gaps_;
  LrvdOptions lrpd_options_;
  std::vector<char> shapeless_;  // triangles whose LRPD polygons need no shape
  GapLrpd lrpd_;
  bool stale_ = true;  // the LRPD is not that of the current samples
  bool connected_cells_ = true;  // the LRPD's cells went through the connectivity restoration
  // After a round with local updates, the triangles that may still hold a gap (open_triangles()),
  // as a mask and as a list; empty: all of them.
  std::vector<char> focus_;
  std::vector<int> open_;
};

}  // namespace

MpsResult maximal_poisson_disk_sampling(const SurfaceMesh& mesh, const MpsOptions& options) {
  check_options(options);
  if (mesh.triangle_count() == 0) throw InputError("the mesh has no triangles");
  require_workable_model(mesh, "Poisson-disk sampling");
  return PoissonDiskSampling(mesh, options).run();
}

}  // namespace lrvd
