// Sutherland-Hodgman clipping on symbolic vertices. The symbolic perturbation guarantees no vertex
// lies on a clipping bisector, so each vertex is strictly kept or strictly dropped.
#include "diagram/clip.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "mesh/surface_mesh.h"
#include "predicates/predicates.h"

namespace lrvd {

namespace {

[[noreturn]] void throw_on_bisector() {
  throw std::logic_error("clip: a polygon vertex already lies on the clipping bisector");
}

// One Sutherland-Hodgman step: cell k's polygon `in` (not empty) clipped by bisector(k, l) into
// `out`. kept(a) is called after in[a] is copied to `out`, born() after each new vertex. Returns
// whether a vertex was dropped (if not, `out` is `in`).
template <class Kept, class Born>
bool clip_step(const std::array<int, 3>& triangle, int k, int l, const SymbolicContext& ctx,
               const std::vector<SymbolicVertex>& in, std::vector<SymbolicVertex>& out, Kept&& kept, Born&& born) {
  const std::size_t n = in.size();
  out.clear();
  const Sign first = side(in[0], k, l, ctx);
  if (first == Sign::Zero) throw_on_bisector();
  bool dropped = false;
  Sign su = first;
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t b = a + 1 == n ? 0 : a + 1;
    const Sign sw = b == 0 ? first : side(in[b], k, l, ctx);
    if (sw == Sign::Zero) throw_on_bisector();
    if (su == Sign::Positive) {
      out.push_back(in[a]);
      kept(a);
    } else {
      dropped = true;
    }
    if (su != sw) {
      out.push_back(intersect(in[a], in[b], k, l, triangle));
      born();
    }
    su = sw;
  }
  return dropped;
}

}  // namespace

void clip_by_bisector(const std::array<int, 3>& triangle, int k, int l, const SymbolicContext& ctx,
                      std::vector<SymbolicVertex>& polygon, std::vector<SymbolicVertex>& scratch) {
  if (polygon.empty()) return;
  clip_step(triangle, k, l, ctx, polygon, scratch, [](std::size_t) {}, [] {});
  polygon.swap(scratch);
}

unsigned along_in_the_limit(const SymbolicVertex* v, int count, const std::array<int, 3>& triangle,
                            const SymbolicContext& ctx) {
  unsigned along = 0;
  for (int a = 0; a < count; ++a) {
    const SymbolicVertex &u = v[a], &w = v[a + 1 == count ? 0 : a + 1];
    const unsigned edge = edge_mask(u, triangle) & edge_mask(w, triangle);
    if (edge && !(along & edge) && !coincide_unperturbed(u, w, ctx)) along |= edge;
  }
  return along;
}

void clip_triangle(const SurfaceMesh& mesh, int t, int k, const int* others, int other_count,
                   const SymbolicContext& ctx, std::vector<SymbolicVertex>& polygon,
                   std::vector<SymbolicVertex>& scratch) {
  const Triangle& tri = mesh.triangle(t);
  polygon.clear();
  for (int c = 0; c < 3; ++c) polygon.push_back(SymbolicVertex::mesh_vertex(tri[c]));
  for (int a = 0; a < other_count && !polygon.empty(); ++a)
    if (others[a] != k) clip_by_bisector(tri, k, others[a], ctx, polygon, scratch);
}

namespace {

constexpr std::uint8_t kNoLabel = 0xff;
// The edge mask of corner c: edges c - 1 and c (edge e joins corners e and e + 1).
constexpr std::uint8_t kCornerMask[3] = {0b101, 0b011, 0b110};
constexpr std::uint32_t kMaxEpoch = 1u << 30;

}  // namespace

void CellClipper::begin_triangle(const std::array<int, 3>& tri, const int* labels, int m, const SymbolicContext& ctx) {
  triangle_ = &tri;
  labels_ = labels;
  m_ = m;
  vertices_ = ctx.vertices;
  in_range_ = ctx.in_range;
  corner_distance_known_ = 0;
  for (int a = 0; a < m; ++a) site_[a] = &ctx.sites[labels[a]];
  for (int c = 0; c < 3; ++c) {
    corner_[c] = &ctx.vertices[tri[c]];
    const int a = tri[c], b = tri[c == 2 ? 0 : c + 1];
    edge_lo_[c] = std::min(a, b);
    edge_hi_[c] = std::max(a, b);
  }
}

// Corner c's bounded power distance to local cell a, computed on first use in the triangle.
inline const predicates::BoundedPowerDistance& CellClipper::corner_distance(int a, int c) {
  const int slot = 3 * a + c;
  if (!(corner_distance_known_ >> slot & 1)) {
    corner_distance_[slot] = predicates::bounded_power_distance(*site_[a], *corner_[c]);
    corner_distance_known_ |= std::uint64_t{1} << slot;
  }
  return corner_distance_[slot];
}

// side1 of corner c for cells k and l: from the corner's shared power distances when the
// context's inputs are in the filters' range (the same answer, fewer operations), else directly.
inline Sign CellClipper::corner_side(int c, int k, int l) {
  if (!in_range_) return predicates::side1(*site_[k], *site_[l], *corner_[c], false);
  return predicates::side1(*site_[k], *site_[l], *corner_[c], corner_distance(k, c), corner_distance(l, c), &tally_);
}

// side(q; k, l) of corner c, by side1, stored for (k, l) and (l, k).
[[gnu::always_inline]] inline Sign CellClipper::evaluate_corner(int c, int k, int l) {
  const Sign r = corner_side(c, k, l);
  corner_sign_[3 * (k * m_ + l) + c] = static_cast<std::int8_t>(r);
  corner_sign_[3 * (l * m_ + k) + c] = static_cast<std::int8_t>(-static_cast<int>(r));
  return r;
}

// side(q; k, l) of a type B or C vertex, by side2 or side3 as side() calls them, stored for l.
Sign CellClipper::evaluate_vertex(const LocalVertex& q, int k, int l) {
  Sign r;
  if (q.type == SymbolicVertex::Type::B) {
    const int other = q.label[0] == k ? q.label[1] : q.label[0];
    const Vec3 &q1 = vertices_[edge_lo_[q.where]], &q2 = vertices_[edge_hi_[q.where]];
    if (in_range_) {
      // The edge's ends are corners: side2 from their power distances, shared with the corner tests.
      const int c = q.where, next = c == 2 ? 0 : c + 1;
      const int c1 = (*triangle_)[c] == edge_lo_[c] ? c : next, c2 = c1 == c ? next : c;
      r = predicates::side2(*site_[k], *site_[other], *site_[l], q1, q2, corner_distance(k, c1),
                            corner_distance(other, c1), corner_distance(l, c1), corner_distance(k, c2),
                            corner_distance(other, c2), corner_distance(l, c2), &tally_);
    } else {
      r = predicates::side2(*site_[k], *site_[other], *site_[l], q1, q2, false);
    }
    edge_sign_[q.key + l] = (epoch_ << 2) | static_cast<std::uint32_t>(static_cast<int>(r) + 1);
  } else {
    int others[2], n = 0;
    for (std::uint8_t x : q.label)
      if (x != k) others[n++] = x;
    r = predicates::side3(*site_[k], *site_[others[0]], *site_[others[1]], *site_[l], *corner_[0], *corner_[1], *corner_[2],
                          in_range_);
    inner_sign_[q.key + l] = (epoch_ << 2) | static_cast<std::uint32_t>(static_cast<int>(r) + 1);
  }
  return r;
}

// side(q; k, l) of the symbolic vertex, as side() evaluates it, through the memo; corner_signs
// points at the corners' entries for (k, l). The vertices of cell k's polygon, clipped in label
// order, carry k and labels already clipped by, never l: side() is never Zero here.
inline Sign CellClipper::side_of(const LocalVertex& q, int k, int l, const std::int8_t* corner_signs) {
  if (q.type == SymbolicVertex::Type::A) {
    const std::int8_t memo = corner_signs[q.where];
    return memo != 0 ? static_cast<Sign>(memo) : evaluate_corner(q.where, k, l);
  }
  const std::uint32_t memo = (q.type == SymbolicVertex::Type::B ? edge_sign_ : inner_sign_)[q.key + l];
  return (memo >> 2) == epoch_ ? static_cast<Sign>(static_cast<int>(memo & 3u) - 1) : evaluate_vertex(q, k, l);
}

// intersect() on local vertices: type B on the mesh edge u and w share, else type C with the
// label they share besides k.
[[gnu::always_inline]] inline CellClipper::LocalVertex CellClipper::intersection(const LocalVertex& u, const LocalVertex& w, int k, int l) const {
  LocalVertex q;
  if (const unsigned common = u.mask & w.mask) {
    const int e = common & 1u ? 0 : (common & 2u ? 1 : 2);
    const int a = std::min(k, l), b = std::max(k, l);
    q.type = SymbolicVertex::Type::B;
    q.mask = static_cast<std::uint8_t>(1u << e);
    q.where = static_cast<std::uint8_t>(e);
    q.label[0] = static_cast<std::uint8_t>(a);
    q.label[1] = static_cast<std::uint8_t>(b);
    q.label[2] = kNoLabel;
    q.key = static_cast<std::uint16_t>(((e * m_ + a) * m_ + b) * m_);
    return q;
  }
  for (std::uint8_t x : u.label) {
    if (x == kNoLabel || x == k) continue;
    if (w.label[0] != x && w.label[1] != x && w.label[2] != x) continue;
    int a = k, b = x, c = l;
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    q.type = SymbolicVertex::Type::C;
    q.mask = 0;
    q.where = 0;
    q.label[0] = static_cast<std::uint8_t>(a);
    q.label[1] = static_cast<std::uint8_t>(b);
    q.label[2] = static_cast<std::uint8_t>(c);
    q.key = static_cast<std::uint16_t>(((a * m_ + b) * m_ + c) * m_);
    return q;
  }
  throw std::logic_error("intersect: polygon edge is on no mesh edge and its ends share no bisector");
}

// One Sutherland-Hodgman step, as clip_by_bisector: `in` clipped by bisector(k, l) into `out`.
// Exact signs along a convex polygon change at most twice, so `out` has at most one vertex more;
// the bound on `in` keeps even inconsistent signs (twice as many vertices) inside the arrays.
void CellClipper::clip_local(const LocalPolygon& in, int k, int l, LocalPolygon& out) {
  const int n = in.n;
  if (2 * n > kMaxVertices) throw std::logic_error("clip: polygon outgrew its bound");
  int count = 0;
  const std::int8_t* corner_signs = corner_sign_ + 3 * (k * m_ + l);
  const Sign first = side_of(in.v[0], k, l, corner_signs);
  if (first == Sign::Zero) throw_on_bisector();
  Sign su = first;
  for (int a = 0; a < n; ++a) {
    const LocalVertex& u = in.v[a];
    const bool last = a + 1 == n;
    const LocalVertex& w = in.v[last ? 0 : a + 1];
    const Sign sw = last ? first : side_of(w, k, l, corner_signs);
    if (sw == Sign::Zero) throw_on_bisector();
    if (su == Sign::Positive) out.v[count++] = u;
    if (su != sw) out.v[count++] = intersection(u, w, k, l);
    su = sw;
  }
  out.n = count;
}

// Two candidates: one pass over the corners gives both polygons (the second is the first's
// complement, cut at the same edge points), in the order the general loop lists them.
void CellClipper::clip_two(std::vector<TrianglePolygon>& polygons, std::vector<PackedVertex>& verts) {
  Sign s[3];
  for (int c = 0; c < 3; ++c) {
    s[c] = corner_side(c, 0, 1);
    if (s[c] == Sign::Zero) throw_on_bisector();
  }
  for (int k = 0; k < 2; ++k) {
    const Sign inside = k == 0 ? Sign::Positive : Sign::Negative;
    if (s[0] != inside && s[1] != inside && s[2] != inside) continue;
    unsigned reach = 0, along = 0, first_mask = 0, previous = 0;
    bool any = false;
    auto add = [&](unsigned mask) {
      if (any) along |= previous & mask; else first_mask = mask;
      reach |= mask;
      previous = mask;
      any = true;
    };
    for (int c = 0; c < 3; ++c) {
      const int next = c == 2 ? 0 : c + 1;
      const auto where = static_cast<std::uint8_t>(c);
      if (s[c] == inside) {
        verts.push_back({SymbolicVertex::Type::A, where, {kNoLabel, kNoLabel, kNoLabel}});
        add(kCornerMask[c]);
      }
      if (s[c] != s[next]) {
        verts.push_back({SymbolicVertex::Type::B, where, {0, 1, kNoLabel}});
        add(1u << c);
      }
    }
    along |= previous & first_mask;
    polygons.push_back({labels_[k], static_cast<int>(verts.size()), static_cast<std::uint8_t>(reach),
                        static_cast<std::uint8_t>(along)});
  }
}

// Cell k's polygon among many candidates, as clip_triangle gives it, vertex for vertex. A long
// triangle (a needle, a sliver along a cylinder) can meet dozens of cells, and each cell's polygon
// would be tested against every other cell's bisector: m^2 clips per triangle, again after each
// label the propagation adds. Most of those bisectors are far from the polygon. When every vertex
// lies within a distance of site k that the bisector of k and l cannot reach
// (predicates::ball_clear_of_bisector, certified), the clip by it would keep every vertex and
// return the polygon unchanged: it is skipped, and the polygons are exactly the unpruned loop's.
//
// A bound for a polygon stays a bound after a clip: each new vertex is the exact crossing of a side
// of the polygon before it with the bisector, inside any ball that holds the side's ends. So the
// new vertices' own bounds are measured only when the looser one fails to clear a bisector.
void CellClipper::clip_many(const std::array<int, 3>& tri, int k, const int* labels, int m, const SymbolicContext& ctx) {
  constexpr double kUnknown = -1;  // a vertex whose bound is not measured yet
  std::vector<SymbolicVertex>& polygon = fallback_polygon_;
  std::vector<SymbolicVertex>& next = fallback_scratch_;
  const Site& site = ctx.sites[k];
  polygon.clear();
  for (int c = 0; c < 3; ++c) polygon.push_back(SymbolicVertex::mesh_vertex(tri[c]));
  reach2_.assign(3, kUnknown);
  // Outside the filters' range no bound is taken, and every bisector is clipped by.
  double reach2 = std::numeric_limits<double>::infinity();
  bool tight = !ctx.in_range;  // reach2 is the largest of the vertices' bounds
  auto clear = [&](const Site& other) {
    if (predicates::ball_clear_of_bisector(site, other, reach2)) return true;
    if (tight) return false;
    const int n = static_cast<int>(polygon.size());
    for (int a = 0; a < n; ++a) {
      if (reach2_[a] != kUnknown) continue;
      int b = a;  // the unmeasured run a..b-1, measured at once
      while (b < n && reach2_[b] == kUnknown) ++b;
      distance_bounds2(polygon.data() + a, b - a, site.p, ctx, reach2_.data() + a);
      a = b - 1;
    }
    reach2 = *std::max_element(reach2_.begin(), reach2_.end());
    tight = true;
    return predicates::ball_clear_of_bisector(site, other, reach2);
  };
  for (int a = 0; a < m && !polygon.empty(); ++a) {
    const int l = labels[a];
    if (l == k || clear(ctx.sites[l])) continue;
    // clip_by_bisector, carrying each vertex's bound along.
    next_reach2_.clear();
    const bool dropped = clip_step(
        tri, k, l, ctx, polygon, next, [&](std::size_t u) { next_reach2_.push_back(reach2_[u]); },
        [&] { next_reach2_.push_back(kUnknown); });
    if (!dropped) continue;
    polygon.swap(next);
    reach2_.swap(next_reach2_);
    tight = !ctx.in_range;
  }
}

void CellClipper::clip(const SurfaceMesh& mesh, int t, const int* labels, int m, const SymbolicContext& ctx,
                       std::vector<TrianglePolygon>& polygons, std::vector<PackedVertex>& verts,
                       std::vector<SymbolicVertex>& wide) {
  // The calls the doubles decided are counted here and go to the thread's counters once.
  struct AddCalls {
    predicates::CallTally& tally;
    ~AddCalls() {
      if (tally.side1 != 0 || tally.side2 != 0) predicates::add_calls(tally);
    }
  } add_calls{tally_};
  const Triangle& tri = mesh.triangle(t);
  if (m == 1) {  // the whole triangle: no vertices
    polygons.push_back({labels[0], static_cast<int>(verts.size()), 7, 7});
    return;
  }
  if (m > kMaxLabels) {  // the memo tables (m^3 and m^4 entries) would outgrow the cache
    for (int a = 0; a < m; ++a) {
      const int k = labels[a];
      clip_many(tri, k, labels, m, ctx);
      if (fallback_polygon_.empty()) continue;
      const PolygonEdges pe = polygon_edges(fallback_polygon_.data(), static_cast<int>(fallback_polygon_.size()), tri);
      wide.insert(wide.end(), fallback_polygon_.begin(), fallback_polygon_.end());
      polygons.push_back({k, static_cast<int>(wide.size()), static_cast<std::uint8_t>(pe.reach),
                          static_cast<std::uint8_t>(pe.along)});
    }
    return;
  }
  begin_triangle(tri, labels, m, ctx);
  if (m == 2) {
    clip_two(polygons, verts);
    return;
  }
  if (++epoch_ == kMaxEpoch) {  // the stamps would wrap around: forget them all
    std::fill(edge_sign_.begin(), edge_sign_.end(), 0);
    std::fill(inner_sign_.begin(), inner_sign_.end(), 0);
    epoch_ = 1;
  }
  const std::size_t m2 = static_cast<std::size_t>(m) * m;
  std::fill(corner_sign_, corner_sign_ + 3 * m2, 0);
  if (edge_sign_.size() < 3 * m2 * m) edge_sign_.resize(3 * m2 * m, 0);
  if (inner_sign_.size() < m2 * m2) inner_sign_.resize(m2 * m2, 0);

  for (int k = 0; k < m; ++k) {
    LocalPolygon* current = &polygon_;
    LocalPolygon* next = &scratch_;
    current->n = 3;
    for (int c = 0; c < 3; ++c) {
      LocalVertex& q = current->v[c];
      q.type = SymbolicVertex::Type::A;
      q.mask = kCornerMask[c];
      q.where = static_cast<std::uint8_t>(c);
      q.label[0] = q.label[1] = q.label[2] = kNoLabel;
      q.key = 0;
    }
    for (int l = 0; l < m && current->n > 0; ++l) {
      if (l == k) continue;
      clip_local(*current, k, l, *next);
      std::swap(current, next);
    }
    if (current->n == 0) continue;
    unsigned reach = 0, along = 0, previous = current->v[current->n - 1].mask;  // as polygon_edges
    for (int a = 0; a < current->n; ++a) {
      const LocalVertex& q = current->v[a];
      reach |= q.mask;
      along |= previous & q.mask;
      previous = q.mask;
      verts.push_back({q.type, q.where, {q.label[0], q.label[1], q.label[2]}});
    }
    polygons.push_back({labels[k], static_cast<int>(verts.size()), static_cast<std::uint8_t>(reach),
                        static_cast<std::uint8_t>(along)});
  }
}

}  // namespace lrvd
