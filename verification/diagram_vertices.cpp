// The vertices of one triangle at a time, for verify_diagram's triangle pass (diagram_triangle.cpp):
// each distinct symbolic vertex of the triangle's polygons made once, in the triangle's own copy
// (a type C vertex belongs to one triangle, a type B vertex to the two of its edge: no index over
// the whole diagram), with what the checks ask of it once, and its point: an interval enclosure,
// rationals only where that cannot be formed.
#include "verification/diagram_vertices.h"

#include <algorithm>

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

// The triangle's corners as its local vertices 0, 1, 2 (the mesh has no triangle that repeats a vertex).
void TriangleVertices::load_corners(const Triangle& tri) {
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
void TriangleVertices::load_whole(const Triangle& tri, int r) {
  load_corners(tri);
  first_.push_back(0);
  for (int k = 0; k < 3; ++k) of_.push_back((r + k) % 3);
  make_points(tri);
  usable_.assign(1, 1);
  area_sign_.assign(1, Sign::Zero);
}

// The triangle's distinct vertices (its corners as 0, 1, 2), the local id of each polygon vertex,
// and which polygons the geometric checks can use.
void TriangleVertices::load_vertices(const Triangle& tri) {
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
int TriangleVertices::local_index(const SymbolicVertex& q, const Triangle& tri) {
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
int TriangleVertices::add_local(const SymbolicVertex& q, const Triangle& tri) {
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
void TriangleVertices::make_points(const Triangle& tri) {
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
void TriangleVertices::load_frame(const Frame& f) {
  for (int c = 0; c < 3; ++c) corner_frame_[c] = {local_[c].box[f.u], local_[c].box[f.v], &local_[c], info_[c].edges};
  frame_.resize(of_.size());
  for (std::size_t j = 0; j < of_.size(); ++j) {
    const int id = of_[j];
    frame_[j] = id < 0 ? FrameVertex{} : FrameVertex{local_[id].box[f.u], local_[id].box[f.v], &local_[id], info_[id].edges};
  }
}

}  // namespace lrvd::verify_detail
