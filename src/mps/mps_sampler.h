// The dart test and the insertion of maximal Poisson-disk sampling (paper §4.2, second change),
// internal to mps.cpp: the Sampler and the grid of centres its adaptive rule reads. Not part of
// the public API.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mps/mps_disks.h"

namespace lrvd::mps_detail {

//! Sample centres in a hash grid of cells as wide as the largest radius: near() gives every
//! centre within that radius of a point (and some farther), cell by cell, each cell's in the order
//! inserted. Open addressing (linear probing, at most half full) over the occupied cells, each a
//! list threaded through the samples: near() looks up 27 cells for every adaptive insertion.
class CentreGrid {
 public:
  void reset(double cell) {
    cell_ = cell;
    slots_.assign(cell > 0 ? 1024 : 0, Slot{});
    occupied_ = 0;
    next_.clear();
  }
  //! Adds sample i, i being one more than the last sample added.
  void insert(const Vec3& p, int i) {
    if (!(cell_ > 0)) return;
    if (2 * (occupied_ + 1) > slots_.size()) grow();
    next_.resize(std::max<std::size_t>(next_.size(), i + 1), -1);
    const std::uint64_t k = key(coordinate(p.x), coordinate(p.y), coordinate(p.z));
    Slot& s = slots_[find(k)];
    if (s.key == kEmpty) {
      s.key = k;
      s.head = i;
      ++occupied_;
    } else {
      next_[s.tail] = i;
    }
    s.tail = i;
  }
  //! Returns whether `out` surely holds every centre closer to p than the cell width (times
  //! 1 + 1e-13): false when p lies so close to a cell's side that rounding may have put a centre
  //! that near two cells away.
  bool near(const Vec3& p, std::vector<int>& out) const {
    if (slots_.empty()) return false;
    const std::int64_t x = coordinate(p.x), y = coordinate(p.y), z = coordinate(p.z);
    for (std::int64_t a = x - 1; a <= x + 1; ++a)
      for (std::int64_t b = y - 1; b <= y + 1; ++b)
        for (std::int64_t c = z - 1; c <= z + 1; ++c) {
          const Slot& s = slots_[find(key(a, b, c))];
          if (s.key == kEmpty) continue;
          for (int i = s.head; i >= 0; i = next_[i]) out.push_back(i);
        }
    return inside_cell(p.x) && inside_cell(p.y) && inside_cell(p.z);
  }

 private:
  // A key packs three 21-bit coordinates into 63 bits: no key has the top bit.
  static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
  struct Slot {
    std::uint64_t key = kEmpty;
    int head = -1, tail = -1;  // first and last sample of the cell; next_ links them
  };
  std::int64_t coordinate(double v) const { return static_cast<std::int64_t>(std::floor(v / cell_)); }
  //! v / cell_ lies far enough inside its unit interval that a coordinate within 1 + 1e-13 cells
  //! of it, each quotient rounded (relative error 2^-53), falls in the interval or a neighbour.
  bool inside_cell(double v) const {
    const double a = v / cell_, f = a - std::floor(a), margin = 1e-12 + 1e-15 * std::abs(a);
    return f >= margin && f <= 1 - margin;
  }
  static std::uint64_t key(std::int64_t a, std::int64_t b, std::int64_t c) {
    return (static_cast<std::uint64_t>(a & 0x1fffff) << 42) | (static_cast<std::uint64_t>(b & 0x1fffff) << 21) |
           static_cast<std::uint64_t>(c & 0x1fffff);
  }
  //! The index of the slot holding `key`, or of the empty one where it would go.
  std::size_t find(std::uint64_t key) const {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t h = (key * 0x9e3779b97f4a7c15ull) >> 20 & mask;; h = (h + 1) & mask)
      if (slots_[h].key == key || slots_[h].key == kEmpty) return h;
  }
  void grow() {
    std::vector<Slot> old(2 * slots_.size());
    old.swap(slots_);
    for (const Slot& s : old)
      if (s.key != kEmpty) slots_[find(s.key)] = s;
  }
  double cell_ = 0;
  std::vector<Slot> slots_;  // a power of two of them
  std::size_t occupied_ = 0;
  std::vector<int> next_;    // per sample: the next sample of its cell, -1 at the end
};

//! The dart test and the insertion (paper §4.2, second change). Two samples are *local* to each
//! other when each one's triangle lies in the local region of the other's ball of radius
//! ρ = max(r_i, r_j); local samples must be at least ρ apart. A dart p in triangle t is rejected
//! when it lies in the disk of a sample (the disks are what the gaps are made of). With a uniform
//! radius nothing else can conflict. Adaptive: p's radius r(p) is cut to just below the distance
//! of every local sample closer than that (which is at least that sample's radius, so never below
//! r_min; a local sample closer than its own radius rejects the dart); and against every sample
//! around, local or not (another sheet, past a notch), it keeps |r_p² − r_j²| <= |p − x_j|², so
//! that no sample falls into another's power cell and the LRPD keeps one cell per sample. Where no
//! radius meets that against every sample around (a sheet thinner than r, a big disk across it)
//! and the spot would otherwise stay uncovered, the condition is kept only against the samples on
//! triangles facing like p's: the dart goes in, and a sample across may then lie outside its power
//! cell (`power_cell_exceptions`). Where even that leaves no radius (a sample past a sharp fold,
//! on a triangle at right angles to p's, whose ball holds p but whose disk does not reach it), the
//! condition is kept only against the samples local to p.
class Sampler {
 public:
  Sampler(const SurfaceMesh& mesh, double r_min, std::vector<double> vertex_radius, bool facing_cut)
      : mesh_(mesh), r_min2_(r_min * r_min), vertex_radius_(std::move(vertex_radius)), disks_(mesh, facing_cut) {
    max_weight_ = r_min2_;
    for (double r : vertex_radius_) max_weight_ = std::max(max_weight_, r * r);
    if (!vertex_radius_.empty() && !facing_cut) grid_.reset(std::sqrt(max_weight_));
  }

  DiskIndex& disks() { return disks_; }
  const std::vector<int>& last_region() const { return region_; }
  int clamped() const { return clamped_; }
  int below_reach() const { return below_reach_; }
  int power_cell_exceptions() const { return power_cell_exceptions_; }
  //! The sample that refused the last dart though the dart lay in no disk reaching its triangle
  //! (its centre lies in the dart's region, closer than its radius: the paper's rule read from the
  //! dart's side); -1 when none did.
  int refused_by() const { return refused_by_; }
  //! From now on, a dart no radius admits against every sample around is tried against those
  //! facing like it only (the sampler turns this on for spots that would stay uncovered).
  void allow_power_cell_exceptions() { allow_exceptions_ = true; }

  double weight_at(int t, const Vec3& bary) const {
    if (vertex_radius_.empty()) return r_min2_;
    const Triangle& tri = mesh_.triangle(t);
    const double r = bary.x * vertex_radius_[tri[0]] + bary.y * vertex_radius_[tri[1]] + bary.z * vertex_radius_[tri[2]];
    return std::max(r * r, r_min2_);
  }

  //! Radius at vertex v of the mesh.
  double radius_at(int v) const { return vertex_radius_.empty() ? std::sqrt(r_min2_) : std::max(vertex_radius_[v], std::sqrt(r_min2_)); }

  //! Inserts the dart if it is accepted; its local region is then last_region(). A dart exactly on
  //! an edge or a corner (a feature sample, a dust dart at a polygon's corner) lies on every
  //! triangle there: a disk reaching any of them holds it, and a sample local to any is local to it.
  bool try_insert(const Vec3& p, int t, const Vec3& bary) {
    seeds_.clear();
    refused_by_ = -1;
    mesh_.triangles_at(t, bary, seeds_);  // t first
    for (int s : seeds_)
      if (disks_.in_some_disk(p, s)) return false;
    const double w = weight_at(t, bary);
    if (vertex_radius_.empty()) {
      region_of(p, w);
      // The other half of locality: a sample whose triangle p's region reaches, closer than r.
      if (!disks_.facing_cut())
        for (int s : region_) {
          disks_.for_each_center(s, [&](int j) {
            if (refused_by_ < 0 && inside_disk(disks_.center(j), p, w)) refused_by_ = j;
          });
          if (refused_by_ >= 0) return false;
        }
      disks_.insert(p, t, bary, w, region_);
      return true;
    }
    // Adaptive: the samples around p. When none of those within the largest radius constrains
    // p (most accepted darts), it takes its full radius; otherwise admit_met() decides.
    cut_below_reach_ = false;
    near_.clear();
    const bool all_near = grid_.near(p, near_);
    double hi = w;
    if (!all_near || !none_constrains(p, w)) {
      const Admission admitted = admit_met(p, t, w, hi);
      if (admitted == Admission::Rejected) return false;
      if (admitted == Admission::NoRadius) {
        if (!allow_exceptions_) return false;
        if (admit(p, w, Against::Facing, hi) != Admission::Radius && admit(p, w, Against::Local, hi) != Admission::Radius)
          return false;
        ++power_cell_exceptions_;
      }
      if (refused_by_others(p, hi)) return false;
    }
    if (hi < w) ++clamped_;
    below_reach_ += cut_below_reach_;
    region_of(p, hi);
    grid_.insert(p, disks_.insert(p, t, bary, hi, region_));
    return true;
  }

 private:
  static constexpr double kScan = 1.5;  // adaptive: scan radius / r(p) for the power-cell condition

  //! region_ = the local region of (p, w): grown from each triangle p lies on (seeds_: one, or on
  //! an edge or a corner every triangle there), so that on a sharp edge or corner the darts on
  //! every face around keep their distance. Without the facing cut a triangle's membership does
  //! not depend on the triangle grown from: one growth from all of them gives the union.
  void region_of(const Vec3& p, double w) {
    if (seeds_.size() == 1 || !disks_.facing_cut()) {
      region_ = disks_.grow(p, seeds_.data(), static_cast<int>(seeds_.size()), w);  // each triangle once
    } else {
      region_ = disks_.grow(p, seeds_[0], w);
      for (size_t k = 1; k < seeds_.size(); ++k) {
        const std::vector<int>& more = disks_.grow(p, seeds_[k], w);
        region_.insert(region_.end(), more.begin(), more.end());
      }
    }
    if (seeds_.size() == 1) return;
    std::sort(region_.begin(), region_.end());
    region_.erase(std::unique(region_.begin(), region_.end()), region_.end());
  }

  //! Triangle s faces like one of the triangles p lies on (seeds_).
  bool faces_dart(int s) const {
    for (int t : seeds_)
      if (disks_.faces_like(s, t)) return true;
    return false;
  }
  //! Sample j's region at weight w reaches one of the triangles p lies on.
  bool reaches_dart(int j, double w) {
    // At j's own weight its region is its disk, which the triangles list.
    if (w == disks_.weight(j)) {
      bool found = false;
      for (int t : seeds_) disks_.for_each_disk(t, [&](int k) { found = found || k == j; });
      return found;
    }
    for (int t : seeds_)
      if (disks_.sample_reaches(j, w, t)) return true;
    return false;
  }
  //! p and sample j (centred on triangle s) are local at weight w: j's region reaches p's
  //! triangle, or (the paper's rule; the facing cut asks for the first only) p's reaches s.
  bool local_to_dart(const Vec3& p, int j, int s, double w) {
    if (reaches_dart(j, w)) return true;
    if (disks_.facing_cut()) return false;
    j_triangles_.clear();
    mesh_.triangles_at(disks_.triangle(j), disks_.barycentric(j), j_triangles_);  // s among them
    (void)s;
    for (int t : seeds_)
      for (int u : j_triangles_)
        if (disks_.reaches(p, t, w, u)) return true;
    return false;
  }

  //! Adaptive, the paper's rule: the largest weight below `hi` that p may take against sample j
  //! (centred on triangle s, d2 = |p - x_j|² below hi), when the two are local at max(hi, w_j).
  //! Either they keep apart (below d2), or p's radius stays at or below the one from which they
  //! are local, whichever allows more: locality only grows with the radius (a region holds the
  //! triangles closer than it), so below that radius the pair is not local whatever its distance.
  //! The threshold is computed in doubles (DiskIndex::reach_threshold) and confirmed exactly;
  //! where it is not, d2. Cutting to d2 alone would leave no radius for spots deep in the ball of
  //! a sample across a thin sheet whose region reaches them only round the rim at p's radius.
  double weight_against(const Vec3& p, int j, int s, double d2, double hi) {
    const double apart = d2 * (1 - 1e-14);
    const double wj = disks_.weight(j), cap = std::max(hi, wj);
    targets_.clear();
    mesh_.triangles_at(disks_.triangle(j), disks_.barycentric(j), targets_);
    // The threshold from x_j's side only when p's side leaves one above the distance (1 in 200
    // calls on dragon_100k): else b <= apart either way.
    double b = disks_.reach_threshold(p, seeds_, targets_, cap);
    if (b > apart) b = std::min(b, disks_.reach_threshold(disks_.center(j), targets_, seeds_, cap));
    for (int attempt = 0; attempt < 3 && b > apart; ++attempt, b *= 1 - 1e-12)
      if (!local_to_dart(p, j, s, std::max(b, wj))) {
        cut_below_reach_ = true;
        return b;
      }
    return apart;
  }

  //! Adaptive, the paper's rule, the samples admit() does not see (it scans p's region at
  //! 1.5·r(p)): x_j within max(r_p, r_j) of p whose region reaches p's triangle from its side (an
  //! asymmetric notch) or whose radius is far above p's (across a sheet). Local at r_j and closer
  //! than r_j: rejected; local at max(r_p, r_j) and closer than r_p: p's radius cut below the
  //! distance (again until no sample cuts it). Every centre within the largest radius is looked at
  //! (near_, filled by try_insert()).
  bool refused_by_others(const Vec3& p, double& hi) {
    if (disks_.facing_cut()) return false;
    for (bool cut = true; cut;) {
      cut = false;
      for (int j : near_) {
        const Vec3& x = disks_.center(j);
        const double wj = disks_.weight(j);
        if (!inside_disk(p, x, std::max(hi, wj))) continue;
        const int s = disks_.triangle(j);
        if (inside_disk(p, x, wj) && local_to_dart(p, j, s, wj)) {
          refused_by_ = j;
          return true;
        }
        if (!(hi > wj) || !local_to_dart(p, j, s, hi)) continue;
        hi = weight_against(p, j, s, squared_distance(p, x), hi);
        cut = true;
      }
    }
    return hi < r_min2_;
  }

  enum class Admission { Radius, NoRadius, Rejected };
  //! admit(p, w, All) over the samples in every triangle a ball somewhat larger than r(p) meets
  //! (edge-connected to t, so to every triangle p lies on).
  Admission admit_met(const Vec3& p, int t, double w, double& hi) {
    met_ = disks_.met(p, t, kScan * kScan * w);
    return admit(p, w, Against::All, hi);
  }
  //! No sample of near_ would reject p, cut its weight w or leave it no radius in admit_reach()
  //! (Against::All): each test there, made here in the same arithmetic, fails. A sample on which
  //! one of them holds lies closer than max(r_p, r_j), so when near_ holds every centre within
  //! the largest radius, admit_met() would find p admitted at w whichever of them it met, and
  //! refused_by_others() would find no centre closer than max(w, w_j): the growth at 1.5·r(p),
  //! most of an accepted dart's cost, is then left out.
  bool none_constrains(const Vec3& p, double w) const {
    for (int j : near_) {
      const Vec3& x = disks_.center(j);
      const double d2 = squared_distance(x, p), wj = disks_.weight(j);
      if ((d2 + wj) * (1 - 1e-14) < w || (wj - d2) * (1 + 1e-14) > w) return false;
      if (inside_disk(p, x, wj) || inside_disk(x, p, w)) return false;
    }
    return true;
  }
  //! The samples around p whose power cells p's radius must keep apart from its own.
  enum class Against { All, Facing, Local };
  //! Adaptive: the largest weight `hi` ≤ w that p (on the triangles seeds_) may take against the
  //! samples around (met_): below the squared distance of every local sample within reach, and
  //! keeping both in their power cells against every sample around (All), only against those on
  //! triangles facing like p's (Facing), or only against the samples local to p (Local: one of p's
  //! triangles lies in the sample's region at radius max(r(p), r_j)). Rejected: a local sample is
  //! closer than its own radius. A sample on an edge or corner is met on each of its triangles.
  Admission admit(const Vec3& p, double w, Against against, double& hi) {
    return disks_.facing_cut() ? admit_facing_cut(p, w, against, hi) : admit_reach(p, w, against, hi);
  }
  //! admit() by the paper's rule: a sample closer than its own radius and local to p at that radius
  //! rejects p; any other sample closer than p's radius and local at max(r_p, r_j) cuts p's radius
  //! to below the distance. The power-cell conditions are kept against the samples `against` names.
  Admission admit_reach(const Vec3& p, double w, Against against, double& hi) {
    double lo = r_min2_;  // the allowed range of p's weight
    hi = w;
    for (int s : met_) {
      const bool faces = against != Against::Facing || faces_dart(s);
      disks_.for_each_center(s, [&](int j) {
        if (refused_by_ >= 0) return;
        const Vec3& x = disks_.center(j);
        const double d2 = squared_distance(x, p), wj = disks_.weight(j);
        if (inside_disk(p, x, wj) && local_to_dart(p, j, s, wj)) {
          refused_by_ = j;  // no radius for p helps
          return;
        }
        if (against == Against::All || (against == Against::Facing ? faces : local_to_dart(p, j, s, std::max(w, wj)))) {
          hi = std::min(hi, (d2 + wj) * (1 - 1e-14));  // x_j stays in its own power cell
          lo = std::max(lo, (wj - d2) * (1 + 1e-14));  // and so does p
        }
        if (inside_disk(x, p, hi) && local_to_dart(p, j, s, std::max(hi, wj))) hi = weight_against(p, j, s, d2, hi);
      });
      if (refused_by_ >= 0) return Admission::Rejected;
    }
    return lo > hi ? Admission::NoRadius : Admission::Radius;
  }
  //! admit() with the facing cut: locality is read from x_j's side (one of p's triangles in its
  //! region at max(r_p, r_j); on p's side meeting the ball and facing alike is taken as enough:
  //! cutting more is safe); a local sample closer than its own radius rejects the dart.
  Admission admit_facing_cut(const Vec3& p, double w, Against against, double& hi) {
    double lo = r_min2_;  // the allowed range of p's weight
    hi = w;
    bool reject = false;
    for (int s : met_) {
      const bool faces = faces_dart(s);
      if (against != Against::All && !faces) continue;
      disks_.for_each_center(s, [&](int j) {
        if (reject) return;
        const double d2 = squared_distance(disks_.center(j), p), wj = disks_.weight(j);
        if (against == Against::Local && !reaches_dart(j, std::max(w, wj))) return;
        hi = std::min(hi, (d2 + wj) * (1 - 1e-14));  // x_j stays in its own power cell
        lo = std::max(lo, (wj - d2) * (1 + 1e-14));  // and so does p
        if (!faces || !inside_disk(disks_.center(j), p, hi)) return;
        if (!reaches_dart(j, std::max(hi, wj))) return;
        if (inside_disk(p, disks_.center(j), wj)) {
          reject = true;  // closer than r_j: no radius for p helps
          return;
        }
        hi = d2 * (1 - 1e-14);  // |p - x_j|² > hi exactly
      });
      if (reject) return Admission::Rejected;
    }
    return lo > hi ? Admission::NoRadius : Admission::Radius;
  }

  const SurfaceMesh& mesh_;
  double r_min2_;
  std::vector<double> vertex_radius_;
  std::vector<int> seeds_;  // the triangles the dart of try_insert() lies on, t first
  DiskIndex disks_;
  std::vector<int> region_, met_, near_, j_triangles_, targets_;
  CentreGrid grid_;  // adaptive, the paper's rule: every centre, in cells of the largest radius
  double max_weight_;  // the largest weight of the radius field
  int clamped_ = 0, power_cell_exceptions_ = 0, refused_by_ = -1, below_reach_ = 0;
  bool allow_exceptions_ = false, cut_below_reach_ = false;
};

}  // namespace lrvd::mps_detail
