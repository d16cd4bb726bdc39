// (4) the polygons of a triangle are convex, counterclockwise, inside it and pairwise
// interior-disjoint, and (5) they cover it: exact area sums, or, when their sides add up to the
// triangle's boundary on exact vertex identities, no arithmetic at all. Part of verify_diagram's
// triangle pass (diagram_triangle.cpp).
#include "verification/diagram_polygons.h"

#include <algorithm>
#include <optional>
#include <tuple>

#include <fmt/format.h>

namespace lrvd::verify_detail {

namespace {

// Whether a and b hold the same values as often (b reordered; a sorted when they are long).
template <class T>
bool same_multiset(std::vector<T>& a, std::vector<T>& b) {
  if (a.size() != b.size()) return false;
  if (a.size() > 32) {
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    return a == b;
  }
  std::uint32_t used = 0;
  for (const T& x : a) {
    std::size_t k = 0;
    while (k < b.size() && ((used >> k & 1) || b[k] != x)) ++k;
    if (k == b.size()) return false;
    used |= std::uint32_t{1} << k;
  }
  return true;
}

}  // namespace

// Whether the interval filters alone show the polygon strictly convex and counterclockwise:
// every turn strictly left, and its edges' directions turning once around (two changes of the
// sign of their v component, each decided; a turn is less than a half turn, so the directions
// cross v = 0 twice per round). Such a polygon has every vertex strictly left of every edge it
// does not end, which is what polygon_problem checks; false leaves the decision to that check.
// \pre the rounding mode is upward.
bool strictly_convex(const FrameVertex* fv, int n, const Frame& f) {
  // The turn at vertex k is cross(d_{k-1}, d_k), d_k = fv[k + 1] - fv[k]: (b - a) x (c - a) = (b - a) x (c - b).
  Interval du = fv[0].u - fv[n - 1].u, dv = fv[0].v - fv[n - 1].v;
  Sign previous = filtered_sign(dv);
  if (previous == Sign::Zero) return false;
  int changes = 0;
  for (int k = 0; k < n; ++k) {
    const FrameVertex &b = fv[k], &c = fv[k + 1 == n ? 0 : k + 1];
    const Interval eu = c.u - b.u, ev = c.v - b.v;
    const Sign turn = filtered_sign(du * ev - dv * eu);
    if (turn == Sign::Zero || (f.sign > 0) != (turn == Sign::Positive)) return false;
    const Sign direction = filtered_sign(ev);
    if (direction == Sign::Zero) return false;
    changes += direction != previous;
    previous = direction;
    du = eu;
    dv = ev;
  }
  return changes == 2;
}

// (4) for one polygon: at least three distinct vertices, each a point of the triangle (by
// definition and exactly inside it), convex and counterclockwise (every vertex on the closed left
// side of every edge). Zero turns are allowed: at a degenerate input the unperturbed limit of a
// polygon may have collinear or coincident vertices. Sets its area sign when there is no problem
// (positive iff some turn is strictly left). \pre the rounding mode is upward.
std::string PolygonChecks::polygon_problem(int p, const Triangle& tri, const Frame& f) {
  const CellPolygon& poly = d_.polygons[p];
  const SymbolicVertex* verts = d_.polygon_vertices(poly);
  const FrameVertex* fv = frame_vertices(p);
  const int n = poly.vertex_count;
  if (n < 3) return fmt::format("has {} vertices", n);
  // One exact vertex per distinct symbolic vertex: equal points are equal vertices.
  for (int k = 0; k < n; ++k)
    for (int m = 0; m < k; ++m)
      if (fv[k].x == fv[m].x) return fmt::format("repeats vertex {}", describe(verts[k]));
  for (int k = 0; k < n; ++k) {
    const int id = local_of(p, k);
    if (!info_[id].defined) return fmt::format("has vertex {} of another triangle", describe(verts[k]));
    if (!vertex_inside(id, fv[k], f)) return fmt::format("has vertex {} outside the triangle", describe(verts[k]));
  }
  return convexity_problem(p, f);
}

// Whether the vertex (local id, in the frame) lies exactly inside the triangle, decided once per
// triangle: type B on its edge's line, inside iff within the edge; type C against the triangle's
// three edges. \pre it is defined on the triangle; the rounding mode is upward.
bool PolygonChecks::vertex_inside(int id, const FrameVertex& x, const Frame& f) {
  LocalVertex& info = info_[id];
  if (info.inside < 0) {
    bool inside = true;
    const SymbolicVertex& q = local_[id].symbolic();
    if (q.type == SymbolicVertex::Type::B) {
      inside = within_edge(local_[id]);
    } else if (q.type == SymbolicVertex::Type::C) {
      for (int c = 0; c < 3 && inside; ++c)
        inside = orient_upward(corner_frame_[c], corner_frame_[(c + 1) % 3], x, f) != Sign::Negative;
    }
    info.inside = inside;
  }
  return info.inside;
}

// (4) convex and counterclockwise: the filters' strict convexity, else every vertex against every
// edge. Sets the polygon's area sign. \pre the rounding mode is upward.
std::string PolygonChecks::convexity_problem(int p, const Frame& f) {
  const SymbolicVertex* verts = d_.polygon_vertices(d_.polygons[p]);
  const FrameVertex* fv = frame_vertices(p);
  const int n = d_.polygons[p].vertex_count;
  if (strictly_convex(fv, n, f)) {
    area(p) = Sign::Positive;
    return {};
  }
  bool strictly_left = false;
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1) % n;
    for (int m = 0; m < n; ++m) {
      // Three points of one mesh edge by definition are collinear.
      if (m == k || m == k1 || (fv[k].edges & fv[k1].edges & fv[m].edges)) continue;
      const Sign s = orient_upward(fv[k], fv[k1], fv[m], f);
      if (s == Sign::Negative)
        return fmt::format("is not convex and counterclockwise: {} is right of edge {} -> {}", describe(verts[m]),
                           describe(verts[k]), describe(verts[k1]));
      strictly_left = strictly_left || s == Sign::Positive;
    }
  }
  area(p) = strictly_left ? Sign::Positive : Sign::Zero;
  return {};
}

// Whether the polygons' directed edges, as a 1-chain, are the triangle's boundary (a, b) +
// (b, c) + (c, a): every edge off the mesh edges cancels with edges of the same two exact
// vertices in the opposite direction, and along each mesh edge e = (tri[e], tri[e + 1]) the
// edges' ends less their starts are 1 at tri[e + 1], -1 at tri[e] and 0 at every other vertex
// (the edges along one line then add up to that segment). Decided on vertex identities alone: two
// vertices at one point (a degenerate input) make it false, never wrongly true. When it holds and
// the polygons are sound (convex, counterclockwise, inside), the polygons tile the triangle: the
// sum of their winding numbers is the triangle's, 1 inside and 0 outside, and each polygon of
// positive area winds once around its interior, so no two interiors meet (4) and the areas add
// up to the triangle's (5), which is what check_area_sum and check_overlaps would find.
bool PolygonChecks::bounded_by_triangle(const Triangle& tri) {
  const std::size_t n = local_q_.size();
  if (n > kCountsUpTo) return bounded_by_triangle_multisets(tri);
  // net_[u n + w], u < w: the sides u -> w less the sides w -> u, off the mesh edges (all zero
  // between triangles: the entries touched are set back); flow_[e n + v]: the sides along mesh
  // edge e that end at v less those that start at v.
  touched_.clear();
  flow_.fill(0);
  bool bounded = true;
  for (int p = begin_; p < end_ && bounded; ++p) {
    const CellPolygon& poly = d_.polygons[p];
    const FrameVertex* fv = frame_vertices(p);
    const int* ids = of_.data() + first_[p - begin_];
    for (int k = 0; k < poly.vertex_count; ++k) {
      const int k1 = k + 1 == poly.vertex_count ? 0 : k + 1;
      const std::size_t u = ids[k], w = ids[k1];
      int e;
      switch (fv[k].edges & fv[k1].edges) {
        case 0: {
          const std::size_t at = u < w ? u * n + w : w * n + u;
          if (net_[at] == 0) touched_.push_back(at);
          net_[at] += u < w ? 1 : -1;
          continue;
        }
        case 1: e = 0; break;
        case 2: e = 1; break;
        case 4: e = 2; break;
        default: bounded = false; continue;  // one vertex twice: no edge of the boundary
      }
      --flow_[e * n + u];
      ++flow_[e * n + w];
    }
  }
  for (std::size_t at : touched_) {
    bounded = bounded && net_[at] == 0;
    net_[at] = 0;
  }
  // Along mesh edge e: 1 at corner e + 1, -1 at corner e (the local vertices 0, 1, 2), 0 elsewhere.
  for (int e = 0; e < 3 && bounded; ++e)
    for (std::size_t v = 0; v < n; ++v)
      if (flow_[e * n + v] != (v == static_cast<std::size_t>(e == 2 ? 0 : e + 1)) - (v == static_cast<std::size_t>(e)))
        bounded = false;
  return bounded;
}

// bounded_by_triangle for a triangle with many vertices: the sides as multisets.
bool PolygonChecks::bounded_by_triangle_multisets(const Triangle& tri) {
  forward_.clear();
  backward_.clear();
  for (auto& ids : from_) ids.clear();
  for (auto& ids : to_) ids.clear();
  for (int p = begin_; p < end_; ++p) {
    const CellPolygon& poly = d_.polygons[p];
    const FrameVertex* fv = frame_vertices(p);
    for (int k = 0; k < poly.vertex_count; ++k) {
      const int k1 = k + 1 == poly.vertex_count ? 0 : k + 1;
      const int u = local_of(p, k), w = local_of(p, k1);
      switch (fv[k].edges & fv[k1].edges) {
        case 0:  // off the mesh edges: (lower id, higher id), by direction
          if (u < w) forward_.push_back(std::uint64_t(std::uint32_t(u)) << 32 | std::uint32_t(w));
          else backward_.push_back(std::uint64_t(std::uint32_t(w)) << 32 | std::uint32_t(u));
          break;
        case 1: from_[0].push_back(u), to_[0].push_back(w); break;
        case 2: from_[1].push_back(u), to_[1].push_back(w); break;
        case 4: from_[2].push_back(u), to_[2].push_back(w); break;
        default: return false;
      }
    }
  }
  // Each pair of vertices as often in one direction as in the other.
  if (!same_multiset(forward_, backward_)) return false;
  // Along mesh edge e: the edges' ends and corner e are, as a multiset, their starts and corner e + 1.
  for (int e = 0; e < 3; ++e) {
    from_[e].push_back(e == 2 ? 0 : e + 1);
    to_[e].push_back(e);
    if (!same_multiset(from_[e], to_[e])) return false;
  }
  return true;
}

// (5) The polygons' areas sum to the triangle's, exactly. The sum of the shoelace formulas with
// the origin at corner a is the sum over directed polygon edges (u, w) of cross(u - a, w - a):
// an edge used in both directions cancels exactly; an edge along a mesh edge through a adds 0;
// an edge along (b, c) with parameters s_u, s_w from b adds (s_w - s_u) cross(b - a, c - b), and
// cross(b - a, c - b) is twice the triangle's area. Any other edge left over is summed in full.
// The edges along (b, c) add sum_v n_v s_v, n_v the times v ends such an edge less the times it
// starts one: when only c is left with n_c = 1 (besides b, at s = 0), that is 1 without arithmetic.
// \pre the rounding mode is upward (the rationals do not depend on it).
void PolygonChecks::check_area_sum(int t, const Frame& f) {
  const Triangle& tri = in_.mesh.triangle(t);
  edges_.clear();
  for (int p = begin_; p < end_; ++p) {
    const CellPolygon& poly = d_.polygons[p];
    const FrameVertex* fv = frame_vertices(p);
    for (int k = 0; k < poly.vertex_count; ++k) {
      const int k1 = (k + 1) % poly.vertex_count;
      const int u = poly.first_vertex + k, w = poly.first_vertex + k1;
      const int iu = local_of(p, k), iw = local_of(p, k1);
      const std::uint8_t edges = fv[k].edges & fv[k1].edges;
      if (iu < iw) edges_.push_back({iu, iw, u, w, 1, edges});
      else edges_.push_back({iw, iu, w, u, -1, edges});
    }
  }
  std::sort(edges_.begin(), edges_.end(), [](const DirectedEdge& x, const DirectedEdge& y) {
    return std::tie(x.from, x.to) < std::tie(y.from, y.to);
  });
  std::optional<Q> rest;  // the edges left over, summed in full (made only when there is one)
  along_bc_.clear();      // (local id, index into Diagram::vertices, +-count)
  for (size_t k = 0; k < edges_.size();) {
    size_t m = k;
    int count = 0;
    for (; m < edges_.size() && edges_[m].from == edges_[k].from && edges_[m].to == edges_[k].to; ++m)
      count += edges_[m].direction;
    const DirectedEdge& e = edges_[k];
    k = m;
    if (count == 0) continue;
    if (e.edges & 0b101) continue;  // along (a, b) or (c, a)
    if (e.edges & 0b010) {          // along (b, c)
      along_bc_.push_back({e.to, e.to_vertex, count});
      along_bc_.push_back({e.from, e.from_vertex, -count});
      continue;
    }
    points_ = {corner_[0], &local_[e.from], &local_[e.to]};
    if (!rest) rest.emplace(0);
    *rest += Q(count) * twice_area(points_, f);
  }
  std::sort(along_bc_.begin(), along_bc_.end());
  int n_c = 0;             // n_v at corner c
  bool elsewhere = false;  // a non-zero n_v at a vertex other than the corners b and c
  for (size_t k = 0; k < along_bc_.size();) {
    int n = 0;
    size_t m = k;
    for (; m < along_bc_.size() && along_bc_[m][0] == along_bc_[k][0]; ++m) n += along_bc_[m][2];
    along_bc_[k][2] = n;  // the first entry of each vertex carries its total
    for (size_t j = k + 1; j < m; ++j) along_bc_[j][2] = 0;
    const SymbolicVertex& v = d_.vertices[along_bc_[k][1]];
    const bool corner = v.type == SymbolicVertex::Type::A;
    if (corner && v.v[0] == tri[2]) n_c = n;
    else if (n != 0 && !(corner && v.v[0] == tri[1])) elsewhere = true;
    k = m;
  }
  // With s_b = 0 and s_c = 1: sum = n_c * area + rest = area.
  if ((!rest || CGAL::is_zero(*rest)) && n_c == 1 && !elsewhere) return;
  Q along_bc(0);
  for (const auto& [id, vertex, n] : along_bc_)
    if (n != 0) along_bc += Q(n) * EdgePosition::of(0, d_.vertices[vertex], local_[id], tri[1]).exact();
  points_.assign(corner_.begin(), corner_.end());
  const Q triangle = twice_area(points_, f);
  const Q ratio = rest ? along_bc + *rest / triangle : along_bc;
  if (ratio != Q(1)) {
    CGAL::Protect_FPU_rounding<true> nearest(CGAL_FE_TONEAREST);  // to print a double
    out_.part.coverage.fail(fmt::format("triangle {}: polygon areas sum to {:.6g} of the triangle, not 1", t,
                                        CGAL::to_double(ratio)));
  }
}

// (4) pairwise: two convex polygons with interiors are interior-disjoint iff the line of an edge
// of one of them has the other on its closed outer side.
//
// Many polygons in one triangle (samples crowding a triangle the mesh was not refined for) would
// make that quadratic: then only pairs whose boxes in the frame meet are tested, each box the
// union of its vertices' enclosures (ExactVertex::box), so that boxes apart in u or v hold
// polygons apart. A sweep along u finds those pairs; they are tested in the same order as all.
// \pre the rounding mode is upward.
void PolygonChecks::check_overlaps(int t, const Frame& f) {
  auto test = [&](int p, int q) {
    if (separated(p, q, f) || separated(q, p, f)) return;
    out_.part.disjoint.fail(fmt::format("triangle {}: polygons of cells {} and {} overlap", t, d_.polygons[p].cell,
                                        d_.polygons[q].cell));
  };
  candidates_.clear();
  for (int p = begin_; p < end_; ++p)
    if (usable(p) && area(p) == Sign::Positive) candidates_.push_back(p);
  boxes_.clear();
  for (int p : candidates_) {
    const FrameVertex* fv = frame_vertices(p);
    FrameBox box{p, fv[0].u.inf(), fv[0].u.sup(), fv[0].v.inf(), fv[0].v.sup()};
    for (int k = 1; k < d_.polygons[p].vertex_count; ++k) {
      box.u_lo = std::min(box.u_lo, fv[k].u.inf());
      box.u_hi = std::max(box.u_hi, fv[k].u.sup());
      box.v_lo = std::min(box.v_lo, fv[k].v.inf());
      box.v_hi = std::max(box.v_hi, fv[k].v.sup());
    }
    boxes_.push_back(box);
  }
  if (candidates_.size() <= kAllPairsUpTo) {
    for (std::size_t a = 0; a < candidates_.size(); ++a)
      for (std::size_t b = a + 1; b < candidates_.size(); ++b)
        if (!boxes_[a].apart(boxes_[b])) test(candidates_[a], candidates_[b]);
    return;
  }
  std::sort(boxes_.begin(), boxes_.end(), [](const FrameBox& a, const FrameBox& b) {
    return std::tie(a.u_lo, a.polygon) < std::tie(b.u_lo, b.polygon);
  });
  pairs_.clear();
  for (std::size_t a = 0; a < boxes_.size(); ++a)
    for (std::size_t b = a + 1; b < boxes_.size() && !(boxes_[a].u_hi < boxes_[b].u_lo); ++b)
      if (!(boxes_[a].v_hi < boxes_[b].v_lo || boxes_[b].v_hi < boxes_[a].v_lo))
        pairs_.push_back({std::min(boxes_[a].polygon, boxes_[b].polygon), std::max(boxes_[a].polygon, boxes_[b].polygon)});
  std::sort(pairs_.begin(), pairs_.end());
  for (const auto& [p, q] : pairs_) test(p, q);
}

// Whether the line of some edge of p has q on its closed outer side. \pre the rounding mode is upward.
bool PolygonChecks::separated(int p, int q, const Frame& f) const {
  const CellPolygon &pp = d_.polygons[p], &qq = d_.polygons[q];
  const FrameVertex* pv = frame_vertices(p);
  const FrameVertex* qv = frame_vertices(q);
  // q on the closed outer side of the line of p's edge k, and not all on it: q has positive area,
  // so a line through two distinct points has some vertex of q strictly outside; an edge whose
  // ends coincide in the exact geometry (a degenerate input's limit) has no line and separates
  // nothing, though every orientation against it is zero.
  auto outside = [&](int k) {
    const int k1 = (k + 1) % pp.vertex_count;
    bool strictly = false;
    for (int m = 0; m < qq.vertex_count; ++m) {
      // A shared vertex, or a third point of a mesh edge the polygon edge runs along, is on the line.
      if (qv[m].x == pv[k].x || qv[m].x == pv[k1].x || (pv[k].edges & pv[k1].edges & qv[m].edges)) continue;
      const Sign s = orient_upward(pv[k], pv[k1], qv[m], f);
      if (s == Sign::Positive) return false;
      strictly = strictly || s == Sign::Negative;
    }
    return strictly;
  };
  // Neighbours share an edge, the likeliest to separate them: tried first (the verdict, whether
  // some edge does, is the same in any order).
  int shared = -1;
  for (int k = 0; k < pp.vertex_count && shared < 0; ++k)
    for (int m = 0; m < qq.vertex_count; ++m)
      if (qv[m].x == pv[k].x && qv[(m + qq.vertex_count - 1) % qq.vertex_count].x == pv[(k + 1) % pp.vertex_count].x) {
        shared = k;
        break;
      }
  if (shared >= 0 && outside(shared)) return true;
  for (int k = 0; k < pp.vertex_count; ++k)
    if (k != shared && outside(k)) return true;
  return false;
}

}  // namespace lrvd::verify_detail
