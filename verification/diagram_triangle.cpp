// verify_diagram's pass over the triangles: each triangle's vertices (diagram_vertices.cpp), then
// its checks in order, the polygon sides along its edges listed for the edge pass, and its share
// of the distinct vertices. The checks themselves: diagram_polygons.cpp (4, 5),
// diagram_equidistance.cpp (3), diagram_samples.cpp (1). A triangle whose one polygon is the
// triangle itself takes a short way through all of it.
#include "verification/diagram_triangle.h"

#include <algorithm>

#include <fmt/format.h>

namespace lrvd::verify_detail {

void TriangleChecker::check_triangles(int begin, int end) {
  out_.sides.reserve(6 * (end - begin));  // three sides per triangle, and more where cells meet
  out_.first_side.reserve(3 * (end - begin) + 1);
  out_.b_count.reserve(end - begin);
  for (int t = begin; t < end; ++t) check_triangle(t);
  out_.first_side.push_back(static_cast<int>(out_.sides.size()));
}

void TriangleChecker::check_triangle(int t) {
  begin_ = d_.triangle_offsets[t];
  end_ = d_.triangle_offsets[t + 1];
  const Triangle& tri = in_.mesh.triangle(t);
  const int whole = whole_rotation(tri);
  if (whole >= 0) load_whole(tri, whole);
  else load_vertices(tri);
  for (int c = 0; c < 3; ++c) corner_[c] = &local_[c];
  const Frame f = triangle_frame(in_.mesh, t, corner_);
  if (whole < 0 || !check_whole(f)) check_polygons(t, tri, f);
  check_samples(t, tri, f);
  if (whole >= 0) list_whole_sides(tri, whole);
  else list_sides(tri);
  count_vertices();
  for (int p = begin_; p < end_; ++p)
    in_.polygon_state[p] = static_cast<std::uint8_t>((usable(p) ? kUsable : 0) |
                                                     (usable(p) && area(p) == Sign::Positive ? kPiece : 0));
}

// A triangle whose one polygon is the triangle itself (cell valid, its corners in the triangle's
// order from corner r): r, else -1. Most triangles are so where the mesh is finer than the cells.
int TriangleChecker::whole_rotation(const Triangle& tri) const {
  if (end_ - begin_ != 1) return -1;
  const CellPolygon& poly = d_.polygons[begin_];
  if (poly.vertex_count != 3 || poly.cell < 0 || poly.cell >= d_.sample_count) return -1;
  const SymbolicVertex* q = d_.polygon_vertices(poly);
  if (!is_mesh_vertex(q[0])) return -1;
  const int r = q[0].v[0] == tri[0] ? 0 : (q[0].v[0] == tri[1] ? 1 : (q[0].v[0] == tri[2] ? 2 : -1));
  if (r < 0) return -1;
  for (int k = 1; k < 3; ++k)
    if (!is_mesh_vertex(q[k]) || q[k].v[0] != tri[(r + k) % 3]) return -1;
  return r;
}

// check_polygons for a whole triangle when the filters show its polygon strictly convex: no
// vertex is repeated, outside or of another triangle, the sides are the triangle's boundary, and
// its one cell has no other to be compared with, so (4), (5), (3) hold as check_polygons would
// find. False (nothing counted) when check_polygons has to decide.
bool TriangleChecker::check_whole(const Frame& f) {
  if (!f.valid || !in_.options.exact_geometry) return false;
  load_frame(f);
  bool convex;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    convex = strictly_convex(frame_vertices(begin_), 3, f);
  }
  if (!convex) return false;
  DiagramVerification& out = out_.part;
  ++out.coverage.checked;
  ++out.disjoint.checked;
  out.equidistant.checked += 3;
  area(begin_) = Sign::Positive;
  return true;
}

// list_sides for a whole triangle: along edge e, the polygon's side from corner e to e + 1 (its
// side k = e - r), of positive length.
void TriangleChecker::list_whole_sides(const Triangle& tri, int r) {
  const CellPolygon& poly = d_.polygons[begin_];
  for (int e = 0; e < 3; ++e) {
    out_.first_side.push_back(static_cast<int>(out_.sides.size()));
    const std::uint64_t a = corner_key(tri[e]), b = corner_key(tri[(e + 1) % 3]);
    out_.sides.push_back({std::min(a, b), std::max(a, b), poly.cell, begin_, (e - r + 3) % 3, static_cast<std::uint8_t>(e),
                          SideLength::Positive});
  }
}

// (4) for each polygon, then (5) and (4) pairwise, then (3).
void TriangleChecker::check_polygons(int t, const Triangle& tri, const Frame& f) {
  DiagramVerification& out = out_.part;
  ++out.coverage.checked;
  if (!f.valid) {
    out.coverage.fail(fmt::format("triangle {}: degenerate, it has no 2D frame", t));
    return;
  }
  if (begin_ == end_) {
    out.coverage.fail(fmt::format("triangle {}: no polygon", t));
    return;
  }
  if (!in_.options.exact_geometry) {
    check_structure(t, f);
    return;
  }
  load_frame(f);
  // One switch to upward rounding for the triangle's checks: the intervals need it, and their
  // exact fallbacks (GMP; MPFR with rounding of its own) do not depend on it. What computes in
  // doubles without a certificate (Near's bound) or prints a double switches back to nearest.
  CGAL::Protect_FPU_rounding<true> upward;
  bool areas_known = true, polygons_sound = true;
  for (int p = begin_; p < end_; ++p) {
    ++out.disjoint.checked;
    if (!usable(p)) {
      report_unusable(t, p);
      areas_known = false;
      continue;
    }
    const std::string problem = polygon_problem(p, tri, f);
    if (!problem.empty()) {
      out.disjoint.fail(fmt::format("triangle {}: polygon of cell {} {}", t, d_.polygons[p].cell, problem));
      points_.clear();
      for (int k = 0; k < d_.polygons[p].vertex_count; ++k) points_.push_back(&vertex(p, k));
      area(p) = area_sign(points_, f);
      polygons_sound = false;
    }
  }
  // Sound polygons whose edges add up to the triangle's boundary tile it: (5) and (4) pairwise
  // hold without arithmetic (bounded_by_triangle). Otherwise both are decided in full.
  const bool tiled = areas_known && polygons_sound && bounded_by_triangle(tri);
  if (!areas_known)
    out.coverage.fail(fmt::format("triangle {}: a polygon's area is unknown (malformed vertex)", t));
  else if (!tiled)
    check_area_sum(t, f);
  if (!tiled) check_overlaps(t, f);
  check_equidistance(t);
}

// Without the exact geometry: the polygons' structure, and which are flat ((1) and (2) need it).
void TriangleChecker::check_structure(int t, const Frame& f) {
  for (int p = begin_; p < end_; ++p) {
    ++out_.part.disjoint.checked;
    if (!usable(p)) {
      report_unusable(t, p);
      continue;
    }
    points_.clear();
    for (int k = 0; k < d_.polygons[p].vertex_count; ++k) points_.push_back(&vertex(p, k));
    area(p) = area_sign(points_, f);
  }
}

// A polygon the geometric checks cannot use: a cell that is no sample, or a vertex that is
// malformed (indices out of range) or names no point (e.g. its edge is parallel to its bisector).
void TriangleChecker::report_unusable(int t, int p) {
  const CellPolygon& poly = d_.polygons[p];
  DiagramVerification& out = out_.part;
  if (poly.cell < 0 || poly.cell >= d_.sample_count) {
    out.disjoint.fail(fmt::format("triangle {}: polygon {} names cell {}, which is no sample", t, p, poly.cell));
    return;
  }
  for (int k = 0; k < poly.vertex_count; ++k) {
    const SymbolicVertex& q = d_.vertices[poly.first_vertex + k];
    const int id = local_of(p, k);
    if (id >= 0 && local_[id].valid) continue;
    const std::string what = id < 0 ? "is malformed" : "names no point";
    out.disjoint.fail(fmt::format("triangle {}: polygon of cell {} has vertex {}, which {}", t, poly.cell, describe(q), what));
    if (id >= 0)  // a vertex that does not exist is equidistant from nothing
      out.equidistant.fail(fmt::format("triangle {}: vertex {} of cell {} {}", t, describe(q), poly.cell, what));
    return;
  }
}

// The sides of the usable polygons along the triangle's edges, by edge and in polygon order, each
// with its ends' identities and whether the filter tells it has positive length; marks the type B
// vertices that end one.
void TriangleChecker::list_sides(const Triangle& tri) {
  along_.clear();  // (polygon, k, its ends' local ids, the edges both lie on)
  for (int p = begin_; p < end_; ++p) {
    if (!usable(p)) continue;
    const int n = d_.polygons[p].vertex_count;
    const int* ids = of_.data() + first_[p - begin_];
    for (int k = 0; k < n; ++k) {
      const int a = ids[k], b = ids[k + 1 == n ? 0 : k + 1];
      const int edges = info_[a].edges & info_[b].edges;
      if (!edges) continue;
      along_.push_back({p, k, a, b, edges});
      if (info_[a].kind == kTypeB) info_[a].ends_side = true;
      if (info_[b].kind == kTypeB) info_[b].ends_side = true;
    }
  }
  // A vertex with edge bits is type A (at 0 or 1 along the edge) or a type B vertex of that edge,
  // whose v[0] is the edge's lower end: its parameter_box encloses its position from there. Two
  // positions are apart when their boxes are (compare_filtered, neither reversed).
  auto box = [&](int id, int lo) {
    const SymbolicVertex& q = local_q_[id];
    return q.type == SymbolicVertex::Type::A ? Interval(q.v[0] == lo ? 0 : 1) : local_[id].parameter_box;
  };
  for (int e = 0; e < 3; ++e) {
    out_.first_side.push_back(static_cast<int>(out_.sides.size()));
    const int lo = std::min(tri[e], tri[e == 2 ? 0 : e + 1]);
    for (const auto& [p, k, a, b, edges] : along_) {
      if (!(edges >> e & 1)) continue;
      const std::uint64_t ka = info_[a].key, kb = info_[b].key;
      SideLength length = SideLength::Zero;
      if (ka != kb) {
        const Interval x = box(a, lo), y = box(b, lo);
        length = x.inf() > y.sup() || x.sup() < y.inf() ? SideLength::Positive : SideLength::Undecided;
      }
      out_.sides.push_back({std::min(ka, kb), std::max(ka, kb), d_.polygons[p].cell, p, k, static_cast<std::uint8_t>(e), length});
    }
  }
}

// The triangle's share of the distinct vertices: its type C vertices, and its type B vertices on
// each edge (the edge pass takes each edge's once from its two triangles).
void TriangleChecker::count_vertices() {
  std::array<int, 3> b{0, 0, 0};
  for (const LocalVertex& info : info_) {
    if (info.kind == kTypeC) ++out_.c_count;
    if (info.kind != kTypeB) continue;
    const int e = info.edges == 1 ? 0 : (info.edges == 2 ? 1 : 2);
    if (b[e] >= 0) b[e] = info.ends_side ? b[e] + 1 : -1;
  }
  out_.b_count.push_back(b);
}

}  // namespace lrvd::verify_detail
