// verify_diagram's pass over the triangles: each triangle's distinct vertices made once, in the
// triangle's own copy (a type C vertex belongs to one triangle, a type B vertex to the two of its
// edge: no index over the whole diagram), then its checks in order, and the polygon sides along
// its edges listed for the edge pass. The checks themselves: diagram_polygons.cpp (4, 5),
// diagram_equidistance.cpp (3), diagram_samples.cpp (1).
#include <algorithm>

#include <fmt/format.h>

#include "verification/diagram_checker.h"

namespace lrvd::verify_detail {

namespace {

// Whether q is by definition a point of triangle `tri`: one of its corners, a point of one of its
// edges, or a point of its plane defined by this triangle.
bool defined_on_triangle(const SymbolicVertex& q, const Triangle& tri) {
  auto corner = [&](int v) { return v == tri[0] || v == tri[1] || v == tri[2]; };
  switch (q.type) {
    case SymbolicVertex::Type::A: return corner(q.v[0]);
    case SymbolicVertex::Type::B: return corner(q.v[0]) && corner(q.v[1]) && q.v[0] != q.v[1];
    case SymbolicVertex::Type::C: {
      if (q.v == tri) return true;  // the corners as the builder stores them, in the triangle's order
      std::array<int, 3> a = q.v, b = tri;
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      return a == b;
    }
  }
  return false;
}

// Equal to SymbolicVertex::mesh_vertex(q.v[0]), field by field.
bool is_mesh_vertex(const SymbolicVertex& q) {
  return q.type == SymbolicVertex::Type::A && q.v[1] == -1 && q.v[2] == -1 && q.label[0] == -1 && q.label[1] == -1 &&
         q.label[2] == -1;
}

// Up to this many distinct vertices besides the corners, a vertex is looked for among them one by
// one; beyond, in an open-addressing table.
constexpr std::size_t kLinearUpTo = 24;

}  // namespace

bool well_formed(const SymbolicVertex& q, int vertex_count, int sample_count) {
  // One unsigned comparison per index: a negative one wraps to a large value.
  auto vertex = [&](int v) { return static_cast<unsigned>(v) < static_cast<unsigned>(vertex_count); };
  auto sample = [&](int s) { return static_cast<unsigned>(s) < static_cast<unsigned>(sample_count); };
  if (q.type == SymbolicVertex::Type::A) return vertex(q.v[0]);
  if (q.type == SymbolicVertex::Type::B)
    return vertex(q.v[0]) && vertex(q.v[1]) && sample(q.label[0]) && sample(q.label[1]) && q.label[0] != q.label[1];
  return vertex(q.v[0]) && vertex(q.v[1]) && vertex(q.v[2]) && sample(q.label[0]) && sample(q.label[1]) &&
         sample(q.label[2]) && q.label[0] != q.label[1] && q.label[0] != q.label[2] && q.label[1] != q.label[2];
}

void TriangleChecker::check_triangles(int begin, int end) {
  out_.sides.reserve(4 * (end - begin));  // three sides per triangle and about one more
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

// The triangle's corners as its local vertices 0, 1, 2 (the mesh has no triangle that repeats a vertex).
void TriangleChecker::load_corners(const Triangle& tri) {
  local_q_.clear();
  info_.clear();
  lookup_.clear();
  of_.clear();
  first_.clear();
  for (int c = 0; c < 3; ++c) {
    local_q_.push_back(SymbolicVertex::mesh_vertex(tri[c]));
    LocalVertex info;  // as add_local makes it
    info.key = corner_key(tri[c]);
    info.edges = static_cast<std::uint8_t>((1 << c) | (1 << (c + 2) % 3));
    info.kind = kMeshVertex;
    info.defined = true;
    info_.push_back(info);
  }
}

// load_vertices for a whole triangle (whole_rotation r): its polygon's vertices are the corners
// r, r + 1, r + 2.
void TriangleChecker::load_whole(const Triangle& tri, int r) {
  load_corners(tri);
  first_.push_back(0);
  for (int k = 0; k < 3; ++k) of_.push_back((r + k) % 3);
  make_points(tri);
  usable_.assign(1, 1);
  area_sign_.assign(1, Sign::Zero);
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

// The triangle's distinct vertices (its corners as 0, 1, 2), the local id of each polygon vertex,
// and which polygons the geometric checks can use.
void TriangleChecker::load_vertices(const Triangle& tri) {
  load_corners(tri);
  for (int p = begin_; p < end_; ++p) {
    const CellPolygon& poly = d_.polygons[p];
    first_.push_back(static_cast<int>(of_.size()));
    for (int k = 0; k < poly.vertex_count; ++k) of_.push_back(local_index(d_.vertices[poly.first_vertex + k], tri));
  }
  make_points(tri);
  usable_.assign(end_ - begin_, 0);
  area_sign_.assign(end_ - begin_, Sign::Zero);
  for (int p = begin_; p < end_; ++p) {
    const CellPolygon& poly = d_.polygons[p];
    bool ok = poly.cell >= 0 && poly.cell < d_.sample_count;
    for (int k = 0; ok && k < poly.vertex_count; ++k) {
      const int id = local_of(p, k);
      ok = id >= 0 && local_[id].valid;
    }
    usable_[p - begin_] = ok;
  }
}

// The local id of q, made the first time the triangle meets it; -1 when q is malformed. Equal
// symbolic vertices, and only those, get one id: one point each.
int TriangleChecker::local_index(const SymbolicVertex& q, const Triangle& tri) {
  if (is_mesh_vertex(q))  // the triangle's corners first: most type A vertices are
    for (int c = 0; c < 3; ++c)
      if (q.v[0] == tri[c]) return c;
  if (!well_formed(q, in_.mesh.vertex_count(), d_.sample_count)) return -1;
  if (lookup_.empty()) {
    for (std::size_t id = 3; id < local_q_.size(); ++id)
      if (local_q_[id] == q) return static_cast<int>(id);
    if (local_q_.size() < 3 + kLinearUpTo) return add_local(q, tri);
    lookup_.assign(128, -1);  // a power of two, more than twice kLinearUpTo
    for (std::size_t id = 3; id < local_q_.size(); ++id) {
      std::size_t k = SymbolicVertexHash()(local_q_[id]) & (lookup_.size() - 1);
      while (lookup_[k] >= 0) k = (k + 1) & (lookup_.size() - 1);
      lookup_[k] = static_cast<int>(id);
    }
  }
  const std::size_t mask = lookup_.size() - 1;
  std::size_t k = SymbolicVertexHash()(q) & mask;
  for (; lookup_[k] >= 0; k = (k + 1) & mask)
    if (local_q_[lookup_[k]] == q) return lookup_[k];
  const int id = add_local(q, tri);
  lookup_[k] = id;
  if (2 * local_q_.size() > lookup_.size()) {  // at most half full
    std::vector<int> ids;
    for (int x : lookup_)
      if (x >= 0) ids.push_back(x);
    lookup_.assign(2 * lookup_.size(), -1);
    for (int x : ids) {
      std::size_t j = SymbolicVertexHash()(local_q_[x]) & (lookup_.size() - 1);
      while (lookup_[j] >= 0) j = (j + 1) & (lookup_.size() - 1);
      lookup_[j] = x;
    }
  }
  return id;
}

// A new distinct vertex, and what the checks ask of it once: its edges, whether it is defined on
// the triangle, its identity along an edge, and what kind of vertex the distinct count takes it for.
int TriangleChecker::add_local(const SymbolicVertex& q, const Triangle& tri) {
  const int id = static_cast<int>(local_q_.size());
  local_q_.push_back(q);
  LocalVertex info;
  info.edges = edges_of(q, tri);
  info.defined = defined_on_triangle(q, tri);
  if (is_mesh_vertex(q)) {
    info.kind = kMeshVertex;
    info.key = corner_key(q.v[0]);
  } else if (q.type == SymbolicVertex::Type::B && info.edges) {
    info.kind = kTypeB;
    info.key = edge_key(q);
  } else if (q.type == SymbolicVertex::Type::C && info.defined) {
    info.kind = kTypeC;
  } else {
    out_.irregular = true;
    if (info.edges) info.key = in_.irregular_key(q);
  }
  info_.push_back(info);
  return id;
}

// The points of the triangle's distinct vertices: interval enclosures, all under one switch of the
// rounding mode, and rationals only for a vertex whose enclosure cannot be formed.
void TriangleChecker::make_points(const Triangle& tri) {
  const std::size_t n = local_q_.size();
  if (local_.size() < n) local_.resize(n);  // reused from triangle to triangle, made in place
  for (std::size_t id = 0; id < n; ++id) local_[id].reset(local_q_[id], in_.context, &in_.rationals);
  for (int c = 0; c < 3; ++c) {  // a mesh vertex: its coordinates, as enclose_position gives them
    const Vec3& x = in_.context.vertices[tri[c]];
    local_[c].box = {Interval(x.x), Interval(x.y), Interval(x.z)};
    local_[c].valid = true;
  }
  if (n == 3) return;
  enclosures_.reset(tri, in_.context);
  {
    CGAL::Protect_FPU_rounding<true> upward;
    for (std::size_t id = 3; id < n; ++id)
      local_[id].valid = enclosures_.enclose(local_q_[id], local_[id].box, local_[id].parameter_box);
  }
  for (std::size_t id = 3; id < n; ++id)
    if (!local_[id].valid) local_[id].enclose_from_rationals();
}

// The triangle's corners and its polygons' vertices as FrameVertex, side by side:
// frame_[first_[p - begin_] + k] is vertex k of polygon p (null x for a malformed one).
void TriangleChecker::load_frame(const Frame& f) {
  for (int c = 0; c < 3; ++c) corner_frame_[c] = {local_[c].box[f.u], local_[c].box[f.v], &local_[c], info_[c].edges};
  frame_.resize(of_.size());
  for (std::size_t j = 0; j < of_.size(); ++j) {
    const int id = of_[j];
    frame_[j] = id < 0 ? FrameVertex{} : FrameVertex{local_[id].box[f.u], local_[id].box[f.v], &local_[id], info_[id].edges};
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
  // A vertex with edge bits is type A (at 0 or 1 along the edge) or a type B vertex of that edge,
  // whose v[0] is the edge's lower end: its parameter_box encloses its position from there. Two
  // positions are apart when their boxes are (compare_filtered, neither reversed).
  auto box = [&](int id, int lo) {
    const SymbolicVertex& q = local_q_[id];
    return q.type == SymbolicVertex::Type::A ? Interval(q.v[0] == lo ? 0 : 1) : local_[id].parameter_box;
  };
  for (auto& list : sides_) list.clear();
  for (int p = begin_; p < end_; ++p) {
    if (!usable(p)) continue;
    const CellPolygon& poly = d_.polygons[p];
    const int* ids = of_.data() + first_[p - begin_];
    for (int k = 0; k < poly.vertex_count; ++k) {
      const int a = ids[k], b = ids[k + 1 == poly.vertex_count ? 0 : k + 1];
      const int along = info_[a].edges & info_[b].edges;
      if (!along) continue;
      const std::uint64_t ka = info_[a].key, kb = info_[b].key;
      for (int e = 0; e < 3; ++e) {
        if (!(along >> e & 1)) continue;
        SideLength length = SideLength::Zero;
        if (ka != kb) {
          const int lo = std::min(tri[e], tri[e == 2 ? 0 : e + 1]);
          const Interval x = box(a, lo), y = box(b, lo);
          length = x.inf() > y.sup() || x.sup() < y.inf() ? SideLength::Positive : SideLength::Undecided;
        }
        sides_[e].push_back({std::min(ka, kb), std::max(ka, kb), poly.cell, p, k, static_cast<std::uint8_t>(e), length});
      }
      if (info_[a].kind == kTypeB) info_[a].ends_side = true;
      if (info_[b].kind == kTypeB) info_[b].ends_side = true;
    }
  }
  for (const auto& list : sides_) {
    out_.first_side.push_back(static_cast<int>(out_.sides.size()));
    out_.sides.insert(out_.sides.end(), list.begin(), list.end());
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
