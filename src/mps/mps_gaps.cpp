// Gap pieces of maximal Poisson-disk sampling (paper §4.2, third change): the parts of the LRPD
// cells their own disks leave uncovered, kept exact under later insertions by splitting each
// piece along the power bisector of its owner and the new disk, and drawn from uniformly by area.
#include <algorithm>
#include <cmath>

#include "mps/mps_gap_geometry.h"
#include "mps/mps_gaps.h"
#include "mps/mps_lrpd_part.h"
#include "predicates/exact.h"

namespace lrvd::mps_detail {

namespace {

constexpr int kMaxBisections = 6;        // depth of the halving that tightens a loose piece polygon
constexpr double kLooseRatio = 0.25;     // halve when the gap is below this fraction of the polygon
constexpr double kNoiseRatio = 1e-13;    // a gap below this fraction of its polygon is rounding noise
constexpr double kDustMargin = 1e-12;    // a dropped piece's corner this·w outside its owner's disk is tried
constexpr double kVertexMargin = 1e-6;   // |d| <= this·w: decide a cell vertex's coverage exactly
constexpr int kMaxRefusals = 64;         // darts a piece may see refused before it is given up

}  // namespace

GapSet::GapSet(const SurfaceMesh& mesh, const DiskIndex& disks, bool local_updates, double min_piece_area)
    : mesh_(mesh), disks_(disks), local_(local_updates), head_(mesh.triangle_count(), -1), drop_area_(min_piece_area) {}

void GapSet::clear() {
  for (const Piece& p : pieces_) head_[p.triangle] = -1;
  pieces_.clear();
  points_.clear();
  fenwick_.clear();
  dust_.clear();
  total_ = 0;
  alive_ = 0;
  dead_since_rebuild_ = 0;
}

void GapSet::begin_extract() {
  clear();
  open_.clear();
  uncovered_polygons_ = 0;
  remote_claims_ = 0;
  given_up_ = 0;
  required_pieces_ = 0;
  deferred_.clear();
  deferred_points_.clear();
  given_up_pieces_.clear();
  given_up_points_.clear();
  extract_disks_ = disks_.size();
}

bool GapSet::place_polygon(const SymbolicVertex* q, int count, const Site& site, const SymbolicContext& ctx,
                           std::vector<Vec3>& polygon) {
  polygon.resize(count);
  bool covered = true;  // by the site's ball: all corners inside (the ball ∩ plane is convex)
  for (int k = 0; k < count; ++k) {
    polygon[k] = position(q[k], ctx);
    if (!covered) continue;
    const double d = squared_distance(polygon[k], site.p) - site.w;
    if (std::abs(d) <= kVertexMargin * site.w)
      covered = CGAL::sign(exact_power_distance(exact_position(q[k], ctx), site)) != CGAL::POSITIVE;
    else
      covered = d < 0;
  }
  return covered;
}

void GapSet::extract(const Diagram& lrpd, const std::vector<char>* focus) {
  extract(lrpd, mesh_, nullptr, nullptr, focus);
}

void GapSet::extract(const GapLrpd& lrpd, const std::vector<char>* focus) {
  if (lrpd.on_part)
    extract(lrpd.diagram, lrpd.part, &lrpd.triangle_of, &lrpd.sample_of, focus);
  else
    extract(lrpd.diagram, mesh_, nullptr, nullptr, focus);
}

void GapSet::extract(const Diagram& lrpd, const SurfaceMesh& diagram_mesh, const std::vector<int>* triangle_of,
                     const std::vector<int>* sample_of, const std::vector<char>* focus) {
  begin_extract();
  const SymbolicContext ctx = lrpd.context(diagram_mesh);
  // Room for the pieces' corners at once: on a large mesh, growing into fresh memory step by step
  // costs more than the pieces themselves. The LRPD lists vertices only on the triangles no disk
  // covers (mps.cpp), and the pieces have fewer corners in all (Gargoyle, r = 0.005: 1.2M against
  // 2.0M); unused room is never touched. The pieces, likewise, are fewer than the polygons
  // (dragon_100k, adaptive r_min = 0.004: 101k against 300k).
  points_.reserve(lrpd.vertices.size());
  pieces_.reserve(lrpd.polygons.size());
  std::vector<Vec3> polygon;
  for (const CellPolygon& cp : lrpd.polygons) {
    const int t = triangle_of ? (*triangle_of)[cp.triangle] : cp.triangle;
    const int i = sample_of ? (*sample_of)[cp.cell] : cp.cell;
    if (focus && !(*focus)[t]) continue;
    // A disk reaching t covers all of it: nothing here is a gap, whichever cell the polygon is of.
    if (disks_.fully_covered(t)) continue;
    const bool covered = place_polygon(lrpd.polygon_vertices(cp), cp.vertex_count, lrpd.sites[cp.cell], ctx, polygon);
    bool own = false;  // the cell's disk reaches t (t is in its local region)
    disks_.for_each_disk(t, [&](int j) { own |= j == i; });
    if (covered && own) continue;  // inside the cell's own disk
    if (covered) {
      // Covered through a ball whose disk does not reach t (another sheet, past a notch): a later
      // insertion may hand the spot to another cell. With local updates the spot is treated as a
      // gap of the disks that do reach t, which cover it for good once the darts are done; it is
      // not *required*: where no dart fits (adaptive radius), the cell's ball covers it.
      ++remote_claims_;
      if (!local_ || required_only_) continue;
    } else {
      ++uncovered_polygons_;
    }
    // The gap of an uncovered polygon is the part outside the cell's ball that no disk reaching t
    // covers: a spot there may lie in the disk of a sample that is no LRPD candidate of t (its
    // cell was kept connected, or its power cell has a piece here the LRPD does not have), where
    // no dart can go. So, in both modes: the polygon minus the cell's ball, split by every disk
    // reaching t. Those pieces are *required*: the sampling is maximal once none is left.
    if (covered) {
      add_split(polygon, t, -1);
    } else if (own || !local_ || required_only_) {
      required_ = true;
      required_pieces_ += add_split(polygon, t, i);
      required_ = false;
    } else {
      // Local updates, a polygon of a remote ball that does not cover it: as for a remote claim
      // the darts go to the whole polygon minus the disks reaching t, so that this side gets its
      // own samples where it can; what must close is the part outside the ball.
      // Its required pieces are counted only if asked (required_pieces()).
      deferred_.push_back({t, i, static_cast<int>(deferred_points_.size()), static_cast<int>(polygon.size())});
      deferred_points_.insert(deferred_points_.end(), polygon.begin(), polygon.end());
      add_split(polygon, t, -1);
    }
  }
  rebuild();
}

int GapSet::required_pieces() {
  if (deferred_.empty()) return required_pieces_;
  // Count as extract() would have: the pieces of (polygon minus the cell's ball), split by the
  // disks reaching t then; then put everything back as it was (pieces, lists, Fenwick tree, counts).
  const size_t pieces = pieces_.size(), points = points_.size(), dust = dust_.size();
  const double total = total_;
  const int alive = alive_, created = created_, dropped = dropped_, dead = dead_since_rebuild_;
  std::vector<double> fenwick;
  fenwick.swap(fenwick_);  // no Fenwick updates meanwhile
  std::vector<Vec3> polygon;
  for (const Deferred& d : deferred_) {
    const int head = head_[d.triangle];
    polygon.assign(deferred_points_.begin() + d.first, deferred_points_.begin() + d.first + d.count);
    required_pieces_ += add_split(polygon, d.triangle, d.cell, extract_disks_);
    head_[d.triangle] = head;
    pieces_.resize(pieces);
    points_.resize(points);
  }
  fenwick.swap(fenwick_);
  dust_.resize(dust);
  total_ = total;
  alive_ = alive;
  created_ = created;
  dropped_ = dropped;
  dead_since_rebuild_ = dead;
  deferred_.clear();
  deferred_points_.clear();
  return required_pieces_;
}

int GapSet::add_split(const std::vector<Vec3>& polygon, int t, int owner, int disk_limit) {
  const size_t first = pieces_.size();
  add_outside(polygon, t, owner);
  if (pieces_.size() == first) return 0;
  // The pieces lie in the polygon (up to rounding): a ball far outside its bounding sphere (with
  // room for rounding) meets none of them, and split() would leave them alone.
  Vec3 c{};
  for (const Vec3& y : polygon) c += y;
  c = c / static_cast<double>(polygon.size());
  double radius2 = 0;
  for (const Vec3& y : polygon) radius2 = std::max(radius2, squared_distance(c, y));
  const double radius = std::sqrt(radius2);
  disks_.for_each_disk(t, [&](int j) {
    const double reach = radius + std::sqrt(disks_.weight(j));
    if (j == owner || j >= disk_limit || squared_distance(disks_.center(j), c) > reach * reach * (1 + 1e-9)) return;
    fresh_.clear();
    for (size_t p = first; p < pieces_.size(); ++p)
      if (pieces_[p].alive) fresh_.push_back(static_cast<int>(p));
    for (int p : fresh_) split(p, j);
  });
  int alive = 0;
  for (size_t p = first; p < pieces_.size(); ++p) alive += pieces_[p].alive;
  return alive;
}

void GapSet::update_after_insert(int sample, const std::vector<int>& region) {
  const Vec3& x = disks_.center(sample);
  const double w = disks_.weight(sample);
  for (int t : region) {
    scratch_pieces_.clear();
    for (int p = head_[t]; p >= 0; p = pieces_[p].next_in_triangle)
      if (pieces_[p].alive) scratch_pieces_.push_back(p);
    for (int p : scratch_pieces_) {
      if (local_) {
        if (disks_.fully_covered(t))
          kill(p);
        else
          split(p, sample);
      } else {
        const Piece& pc = pieces_[p];
        bool inside = true;
        for (int k = 0; k < pc.count && inside; ++k) inside = squared_distance(points_[pc.first + k], x) < w;
        if (inside) kill(p);
      }
    }
  }
}

void GapSet::add_outside(const std::vector<Vec3>& polygon, int t, int owner) {
  if (polygon.size() < 3) return;
  if (owner < 0) {
    add_piece(polygon, t, owner, 0);
    return;
  }
  switch (walk_boundary(polygon, disks_.center(owner), disks_.weight(owner))) {
    case Boundary::Inside:
      return;
    case Boundary::NotCrossed:  // the gap is the polygon minus (all or none of) the disk
      add_piece(polygon, t, owner, 0);
      return;
    case Boundary::Crossed:
      add_outside_stretches(t, owner);
      return;
  }
}

GapSet::Boundary GapSet::walk_boundary(const std::vector<Vec3>& polygon, const Vec3& x, double w) {
  const size_t m = polygon.size();
  std::vector<Event>& events = events_;
  events.clear();
  bool any_out = false, any_cross = false;
  std::vector<char>& out = outside_;
  out.assign(m, 0);
  for (size_t k = 0; k < m; ++k) any_out |= (out[k] = !(squared_distance(polygon[k], x) < w));
  if (!any_out) return Boundary::Inside;
  for (size_t k = 0; k < m; ++k) {
    const Vec3& a = polygon[k];
    const Vec3& b = polygon[(k + 1) % m];
    events.push_back({a, out[k] ? 1 : 0});
    const bool oa = out[k], ob = out[(k + 1) % m];
    if (!oa && !ob) continue;  // both ends inside: the edge is (the disk is convex)
    const Vec3 d = b - a, ax = a - x;
    const double A = dot(d, d), B = dot(ax, d), C = dot(ax, ax) - w;
    if (!(A > 0) || (oa && ob && !(B * B - A * C > 0))) continue;  // outside, not crossing the circle
    const double sq = std::sqrt(std::max(0.0, B * B - A * C));
    const double s1 = std::clamp((-B - sq) / A, 0.0, 1.0), s2 = std::clamp((-B + sq) / A, 0.0, 1.0);
    if (oa && !ob) {
      events.push_back({a + s1 * d, 2});
    } else if (!oa && ob) {
      events.push_back({a + s2 * d, 3});
    } else if (oa && ob && B * B - A * C > 0 && s1 > 0 && s2 < 1 && s1 < s2) {
      events.push_back({a + s1 * d, 2});
      events.push_back({a + s2 * d, 3});
    } else {
      continue;
    }
    any_cross = true;
  }
  return any_cross ? Boundary::Crossed : Boundary::NotCrossed;
}

void GapSet::add_outside_stretches(int t, int owner) {
  const std::vector<Event>& events = events_;
  size_t start = 0;
  while (events[start].kind != 3) ++start;
  std::vector<Vec3>& run = run_;
  run.clear();
  bool open = false;
  for (size_t k = 0; k < events.size(); ++k) {
    const Event& e = events[(start + k) % events.size()];
    if (e.kind == 3) {
      run.assign(1, e.p);
      open = true;
    } else if (e.kind == 1 && open) {
      run.push_back(e.p);
    } else if (e.kind == 2 && open) {
      run.push_back(e.p);
      open = false;
      if (run.size() >= 3) add_piece(run, t, owner, 0);
    }
  }
}

void GapSet::add_piece(const std::vector<Vec3>& q, int t, int owner, int depth) {
  const Vec3& n = disks_.normal(t);
  const double area = polygon_area(q);
  // Whether the piece is kept as it is (neither rounding noise nor loose) is decided by the
  // exact area outside the owner's disk (sector formula), unless a lower bound of it, less a
  // margin far above the formula's rounding error (~1e-14·r²), already decides: then the piece is
  // kept as the formula would keep it, without it (GapSet::gap_area() computes it when asked).
  if (owner >= 0) {
    const double lower = uncovered_area_lower_bound(q, n, disks_.center(owner), disks_.weight(owner), area) -
                         1e-7 * disks_.weight(owner);
    if (lower > drop_area_ && lower > kNoiseRatio * area && (lower >= kLooseRatio * area || depth >= kMaxBisections)) {
      keep(q, t, owner, area);
      return;
    }
  }
  const double gap = owner < 0 ? area : uncovered_area(q, n, disks_.center(owner), disks_.weight(owner), area);
  if (!(gap > drop_area_) || gap <= kNoiseRatio * area) {
    if (gap > 0) ++dropped_;
    leave_dust(q, t, owner);
    return;
  }
  if (owner >= 0 && gap < kLooseRatio * area && depth < kMaxBisections) {
    // Halve across the polygon's longest diagonal; halves inside the disk vanish.
    const Halving side = longest_diagonal_halving(q);
    std::vector<Vec3> half;
    clip(q, side, half);
    if (!half.empty()) add_piece(half, t, owner, depth + 1);
    clip(q, [&](const Vec3& y) { return -side(y); }, half);
    if (!half.empty()) add_piece(half, t, owner, depth + 1);
    return;
  }
  keep(q, t, owner, area);
}

void GapSet::leave_dust(const std::vector<Vec3>& q, int t, int owner) {
  if (q.empty()) return;
  if (owner < 0) {
    Vec3 c{};
    for (const Vec3& y : q) c += y;
    dust_.push_back({c / static_cast<double>(q.size()), t});
    return;
  }
  const Vec3& x = disks_.center(owner);
  const double w = disks_.weight(owner);
  const Vec3* farthest = nullptr;
  double outside = kDustMargin * w;
  for (const Vec3& y : q)
    if (squared_distance(y, x) - w > outside) outside = squared_distance(y, x) - w, farthest = &y;
  if (farthest) dust_.push_back({*farthest, t});
}

void GapSet::keep(const std::vector<Vec3>& q, int t, int owner, double area) {
  Piece piece;
  piece.triangle = t;
  piece.owner = owner;
  piece.first = static_cast<int>(points_.size());
  piece.count = static_cast<int>(q.size());
  piece.area = area;
  piece.alive = true;
  piece.next_in_triangle = head_[t];
  piece.required = required_;
  points_.insert(points_.end(), q.begin(), q.end());
  const int index = static_cast<int>(pieces_.size());
  pieces_.push_back(piece);
  head_[t] = index;
  ++alive_;
  ++created_;
  total_ += area;
  if (index < static_cast<int>(fenwick_.size())) fenwick_add(index, area);
}

void GapSet::split(int index, int sample) {
  const Piece pc = pieces_[index];
  if (pc.owner == sample) return;
  const Vec3& xe = disks_.center(sample);
  const double we = disks_.weight(sample);
  if (!ball_meets_polygon(points_.data() + pc.first, pc.count, xe, we)) return;
  kill(index);
  // A copy: the new pieces' corners go to the end of points_.
  std::vector<Vec3>& q = split_polygon_;
  q.assign(points_.begin() + pc.first, points_.begin() + pc.first + pc.count);
  const bool required = std::exchange(required_, pc.required);
  if (pc.owner < 0) {
    add_outside(q, pc.triangle, sample);
    required_ = required;
    return;
  }
  // Power cells of {owner, sample} inside q: a point outside the disk of the cell it lies in is
  // outside both disks, and every point outside both lies so.
  const Vec3& xo = disks_.center(pc.owner);
  const double wo = disks_.weight(pc.owner);
  auto h = [&](const Vec3& y) { return (squared_distance(y, xo) - wo) - (squared_distance(y, xe) - we); };
  std::vector<Vec3>& cell = split_cell_;
  clip(q, h, cell);
  add_outside(cell, pc.triangle, pc.owner);
  clip(q, [&](const Vec3& y) { return -h(y); }, cell);
  add_outside(cell, pc.triangle, sample);
  required_ = required;
}

void GapSet::kill(int index) {
  Piece& p = pieces_[index];
  if (!p.alive) return;
  p.alive = false;
  --alive_;
  ++dead_since_rebuild_;
  total_ -= p.area;
  if (index < static_cast<int>(fenwick_.size())) fenwick_add(index, -p.area);
}

void GapSet::fenwick_add(int index, double delta) {
  for (int i = index + 1; i <= static_cast<int>(fenwick_.size()); i += i & -i) fenwick_[i - 1] += delta;
}

void GapSet::rebuild() {
  // Drop dead pieces in place (a piece and its corners only move towards the front: no fresh
  // memory), then rebuild the per-triangle lists and the Fenwick tree (capacity: a power of two
  // with room to grow).
  for (const Piece& p : pieces_) head_[p.triangle] = -1;
  total_ = 0;
  size_t kept = 0, corners = 0;
  for (const Piece& p : pieces_) {
    if (!p.alive) continue;
    Piece q = p;
    if (q.first != static_cast<int>(corners))
      std::copy(points_.begin() + p.first, points_.begin() + p.first + p.count, points_.begin() + corners);
    q.first = static_cast<int>(corners);
    corners += p.count;
    q.next_in_triangle = head_[q.triangle];
    head_[q.triangle] = static_cast<int>(kept);
    pieces_[kept++] = q;
    total_ += q.area;
  }
  pieces_.resize(kept);
  points_.resize(corners);
  alive_ = static_cast<int>(pieces_.size());
  dead_since_rebuild_ = 0;
  size_t capacity = 1024;
  while (capacity < 2 * pieces_.size()) capacity *= 2;
  fenwick_.assign(capacity, 0);
  for (size_t i = 0; i < pieces_.size(); ++i) fenwick_[i] = pieces_[i].area;
  for (size_t i = 1; i <= capacity; ++i) {
    const size_t parent = i + (i & (~i + 1));
    if (parent <= capacity) fenwick_[parent - 1] += fenwick_[i - 1];
  }
}

void GapSet::dart_refused(int piece) {
  if (piece < 0 || piece >= static_cast<int>(pieces_.size()) || !pieces_[piece].alive) return;
  Piece& pc = pieces_[piece];
  if (++pc.refused >= kMaxRefusals) {
    kill(piece);
    ++given_up_;
    open_.push_back(pc.triangle);
    if (pc.required) {
      given_up_pieces_.push_back({pc.triangle, pc.owner, pc.halvings, static_cast<int>(given_up_points_.size()), pc.count});
      given_up_points_.insert(given_up_points_.end(), points_.begin() + pc.first, points_.begin() + pc.first + pc.count);
    }
  }
}

std::vector<int> GapSet::open_triangles() const {
  std::vector<int> t(open_);
  for (const Piece& p : pieces_)
    if (p.alive) t.push_back(p.triangle);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

bool GapSet::draw(Random& random, Vec3& point, int& triangle, int& piece) {
  piece = -1;
  if (pieces_.size() > fenwick_.size() || dead_since_rebuild_ > 2 * alive_ + 1024) rebuild();
  if (alive_ == 0) return false;
  // Fenwick descent to the piece holding the cumulative area u.
  double u = random.uniform() * total_;
  int pos = 0;
  for (int step = static_cast<int>(fenwick_.size()); step > 0; step >>= 1) {
    const int next = pos + step;
    if (next <= static_cast<int>(fenwick_.size()) && fenwick_[next - 1] <= u) {
      u -= fenwick_[next - 1];
      pos = next;
    }
  }
  if (pos >= static_cast<int>(pieces_.size()) || !pieces_[pos].alive) return false;
  const Piece& pc = pieces_[pos];
  piece = pos;
  const Vec3* q = points_.data() + pc.first;
  // A fan triangle by area, then a uniform point in it.
  const int nf = pc.count - 2;
  fan_.resize(nf);
  double sum = 0;
  for (int k = 0; k < nf; ++k) fan_[k] = (sum += norm(cross(q[k + 1] - q[0], q[k + 2] - q[0])));
  const double v = random.uniform() * sum;
  int k = 0;
  while (k + 1 < nf && fan_[k] <= v) ++k;
  const double r = std::sqrt(random.uniform()), s = random.uniform();
  point = (1 - r) * q[0] + (r * (1 - s)) * q[k + 1] + (r * s) * q[k + 2];
  triangle = pc.triangle;
  return pc.owner < 0 || !(squared_distance(point, disks_.center(pc.owner)) < disks_.weight(pc.owner));
}

double GapSet::gap_area() const {
  double sum = 0;
  std::vector<Vec3> q;
  for (const Piece& p : pieces_) {
    if (!p.alive) continue;
    if (p.owner < 0) {
      sum += p.area;
      continue;
    }
    q.assign(points_.begin() + p.first, points_.begin() + p.first + p.count);
    sum += uncovered_area(q, disks_.normal(p.triangle), disks_.center(p.owner), disks_.weight(p.owner), p.area);
  }
  return sum;
}

}  // namespace lrvd::mps_detail
