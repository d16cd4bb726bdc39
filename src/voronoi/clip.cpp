// Sutherland-Hodgman clipping on symbolic vertices. The symbolic perturbation guarantees no vertex
// lies on a clipping bisector, so each vertex is strictly kept or strictly dropped.
#include "voronoi/clip.h"

#include <algorithm>
#include <stdexcept>

#include "mesh/surface_mesh.h"
#include "predicates/predicates.h"

namespace lrvd {

void clip_by_bisector(const std::array<int, 3>& triangle, int k, int l, const SymbolicContext& ctx,
                      std::vector<SymbolicVertex>& polygon, std::vector<SymbolicVertex>& scratch) {
  const size_t n = polygon.size();
  if (n == 0) return;
  scratch.clear();
  const Sign first = side(polygon[0], k, l, ctx);
  if (first == Sign::Zero) throw std::logic_error("clip: a polygon vertex already lies on the clipping bisector");
  Sign su = first;
  for (size_t a = 0; a < n; ++a) {
    const SymbolicVertex& u = polygon[a];
    const SymbolicVertex& w = polygon[(a + 1) % n];
    const Sign sw = a + 1 == n ? first : side(w, k, l, ctx);
    if (sw == Sign::Zero) throw std::logic_error("clip: a polygon vertex already lies on the clipping bisector");
    if (su == Sign::Positive) scratch.push_back(u);
    if (su != sw) scratch.push_back(intersect(u, w, k, l, triangle));
    su = sw;
  }
  polygon.swap(scratch);
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

// Beyond this many candidates the memo tables (m^3 and m^4 entries) would outgrow the cache;
// such triangles are clipped cell by cell.
constexpr int kMaxMemoLabels = 16;
constexpr std::uint8_t kNoLabel = 0xff;
constexpr std::uint32_t kMaxEpoch = 1u << 30;

}  // namespace

// Written in place: a vertex assembled field by field on the stack and copied right away stalls
// the copy (the wide loads cannot take the narrow stores' data).
void CellClipper::append_symbolic(const LocalVertex& q, std::vector<SymbolicVertex>& verts) const {
  const std::array<int, 3>& tri = *triangle_;
  SymbolicVertex& out = verts.emplace_back();  // as mesh_vertex, on_edge and in_triangle build it
  out.type = q.type;
  switch (q.type) {
    case SymbolicVertex::Type::A:
      out.v[0] = tri[q.where];
      break;
    case SymbolicVertex::Type::B: {
      const int a = tri[q.where], b = tri[q.where == 2 ? 0 : q.where + 1];
      out.v[0] = std::min(a, b);
      out.v[1] = std::max(a, b);
      out.label[0] = labels_[q.label[0]];
      out.label[1] = labels_[q.label[1]];
      break;
    }
    case SymbolicVertex::Type::C:
      out.v = tri;
      out.label = {labels_[q.label[0]], labels_[q.label[1]], labels_[q.label[2]]};
      break;
  }
}

// side(q; k, l) of a corner, by side1, stored for (k, l) and (l, k).
Sign CellClipper::evaluate_corner(const LocalVertex& q, int k, int l) {
  const Sign r = predicates::side1(ctx_.sites[labels_[k]], ctx_.sites[labels_[l]], ctx_.vertices[(*triangle_)[q.where]],
                                    ctx_.in_range);
  corner_sign_[(q.where * m_ + k) * m_ + l] = static_cast<std::int8_t>(r);
  corner_sign_[(q.where * m_ + l) * m_ + k] = static_cast<std::int8_t>(-r);
  return r;
}

// side(q; k, l) of a type B or C vertex, by side2 or side3 as side() calls them, stored for l.
Sign CellClipper::evaluate_vertex(const LocalVertex& q, int k, int l) {
  const Site* s = ctx_.sites;
  const std::array<int, 3>& tri = *triangle_;
  int others[2], n = 0;
  for (std::uint8_t x : q.label)
    if (x != kNoLabel && x != k) others[n++] = labels_[x];
  Sign r;
  if (q.type == SymbolicVertex::Type::B) {
    const int a = tri[q.where], b = tri[q.where == 2 ? 0 : q.where + 1];
    r = predicates::side2(s[labels_[k]], s[others[0]], s[labels_[l]], ctx_.vertices[std::min(a, b)],
                          ctx_.vertices[std::max(a, b)], ctx_.in_range);
    edge_sign_[static_cast<std::size_t>(q.key) * m_ + l] = (epoch_ << 2) | static_cast<std::uint32_t>(static_cast<int>(r) + 1);
  } else {
    r = predicates::side3(s[labels_[k]], s[others[0]], s[others[1]], s[labels_[l]], ctx_.vertices[tri[0]],
                          ctx_.vertices[tri[1]], ctx_.vertices[tri[2]], ctx_.in_range);
    inner_sign_[static_cast<std::size_t>(q.key) * m_ + l] = (epoch_ << 2) | static_cast<std::uint32_t>(static_cast<int>(r) + 1);
  }
  return r;
}

// side(q; k, l) of the symbolic vertex, as side() evaluates it, through the memo.
inline Sign CellClipper::side_of(const LocalVertex& q, int k, int l) {
  if (q.type == SymbolicVertex::Type::A) {
    const std::int8_t memo = corner_sign_[(q.where * m_ + k) * m_ + l];
    return memo != 0 ? static_cast<Sign>(memo) : evaluate_corner(q, k, l);
  }
  if (q.label[0] == l || q.label[1] == l || q.label[2] == l) return Sign::Zero;
  const std::uint32_t memo =
      (q.type == SymbolicVertex::Type::B ? edge_sign_ : inner_sign_)[static_cast<std::size_t>(q.key) * m_ + l];
  return (memo >> 2) == epoch_ ? static_cast<Sign>(static_cast<int>(memo & 3u) - 1) : evaluate_vertex(q, k, l);
}

// intersect() on local vertices: type B on the mesh edge u and w share, else type C with the
// label they share besides k. Appended to `out` in place (see append_symbolic).
void CellClipper::append_intersection(const LocalVertex& u, const LocalVertex& w, int k, int l,
                                      std::vector<LocalVertex>& out) const {
  if (const unsigned common = u.mask & w.mask) {
    const int e = common & 1u ? 0 : (common & 2u ? 1 : 2);
    LocalVertex& q = out.emplace_back();
    q.type = SymbolicVertex::Type::B;
    q.mask = static_cast<std::uint8_t>(1u << e);
    q.where = static_cast<std::uint8_t>(e);
    q.label[0] = static_cast<std::uint8_t>(std::min(k, l));
    q.label[1] = static_cast<std::uint8_t>(std::max(k, l));
    q.label[2] = kNoLabel;
    q.key = (e * m_ + q.label[0]) * m_ + q.label[1];
    return;
  }
  for (std::uint8_t x : u.label) {
    if (x == kNoLabel || x == k) continue;
    if (w.label[0] != x && w.label[1] != x && w.label[2] != x) continue;
    int a = k, b = x, c = l;
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    LocalVertex& q = out.emplace_back();
    q.type = SymbolicVertex::Type::C;
    q.mask = 0;
    q.where = 0;
    q.label[0] = static_cast<std::uint8_t>(a);
    q.label[1] = static_cast<std::uint8_t>(b);
    q.label[2] = static_cast<std::uint8_t>(c);
    q.key = (a * m_ + b) * m_ + c;
    return;
  }
  throw std::logic_error("intersect: polygon edge is on no mesh edge and its ends share no bisector");
}

void CellClipper::clip(const SurfaceMesh& mesh, int t, const int* labels, int m, const SymbolicContext& ctx,
                       std::vector<TrianglePolygon>& polygons, std::vector<SymbolicVertex>& verts) {
  const Triangle& tri = mesh.triangle(t);
  if (m == 1) {  // the whole triangle
    for (int c = 0; c < 3; ++c) verts.push_back(SymbolicVertex::mesh_vertex(tri[c]));
    polygons.push_back({labels[0], static_cast<int>(verts.size()), 7, 7});
    return;
  }
  if (m > kMaxMemoLabels) {
    for (int a = 0; a < m; ++a) {
      const int k = labels[a];
      clip_triangle(mesh, t, k, labels, m, ctx, fallback_polygon_, fallback_scratch_);
      if (fallback_polygon_.empty()) continue;
      const PolygonEdges pe = polygon_edges(fallback_polygon_.data(), static_cast<int>(fallback_polygon_.size()), tri);
      verts.insert(verts.end(), fallback_polygon_.begin(), fallback_polygon_.end());
      polygons.push_back({k, static_cast<int>(verts.size()), static_cast<std::uint8_t>(pe.reach),
                          static_cast<std::uint8_t>(pe.along)});
    }
    return;
  }
  triangle_ = &tri;
  labels_ = labels;
  m_ = m;
  ctx_ = ctx;
  if (++epoch_ == kMaxEpoch) {  // the stamps would wrap around: forget them all
    std::fill(edge_sign_.begin(), edge_sign_.end(), 0);
    std::fill(inner_sign_.begin(), inner_sign_.end(), 0);
    epoch_ = 1;
  }
  const std::size_t m2 = static_cast<std::size_t>(m) * m;
  corner_sign_.assign(3 * m2, 0);
  if (edge_sign_.size() < 3 * m2 * m) edge_sign_.resize(3 * m2 * m, 0);
  if (inner_sign_.size() < m2 * m2) inner_sign_.resize(m2 * m2, 0);

  // The triangle's corners, built once (see append_symbolic).
  static const LocalVertex corners[3] = {{SymbolicVertex::Type::A, 0b101, 0, {kNoLabel, kNoLabel, kNoLabel}, -1},
                                         {SymbolicVertex::Type::A, 0b011, 1, {kNoLabel, kNoLabel, kNoLabel}, -1},
                                         {SymbolicVertex::Type::A, 0b110, 2, {kNoLabel, kNoLabel, kNoLabel}, -1}};
  for (int k = 0; k < m; ++k) {
    polygon_.assign(corners, corners + 3);
    // Sutherland-Hodgman, as clip_by_bisector.
    for (int l = 0; l < m && !polygon_.empty(); ++l) {
      if (l == k) continue;
      const size_t n = polygon_.size();
      scratch_.clear();
      const Sign first = side_of(polygon_[0], k, l);
      if (first == Sign::Zero) throw std::logic_error("clip: a polygon vertex already lies on the clipping bisector");
      Sign su = first;
      for (size_t a = 0; a < n; ++a) {
        const LocalVertex& u = polygon_[a];
        const LocalVertex& w = polygon_[a + 1 == n ? 0 : a + 1];
        const Sign sw = a + 1 == n ? first : side_of(w, k, l);
        if (sw == Sign::Zero) throw std::logic_error("clip: a polygon vertex already lies on the clipping bisector");
        if (su == Sign::Positive) scratch_.push_back(u);
        if (su != sw) append_intersection(u, w, k, l, scratch_);
        su = sw;
      }
      polygon_.swap(scratch_);
    }
    if (polygon_.empty()) continue;
    PolygonEdges pe;  // as polygon_edges
    unsigned previous = polygon_.back().mask;
    for (const LocalVertex& q : polygon_) {
      pe.reach |= q.mask;
      pe.along |= previous & q.mask;
      previous = q.mask;
      append_symbolic(q, verts);
    }
    polygons.push_back({labels[k], static_cast<int>(verts.size()), static_cast<std::uint8_t>(pe.reach),
                        static_cast<std::uint8_t>(pe.along)});
  }
}

}  // namespace lrvd
