// Symbolic vertices (paper §3.4, §3.6): dispatch of side() to side1/side2/side3, the birth rule of
// a vertex on a clipped polygon edge, and double positions.
#include "predicates/symbolic_vertex.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

#include "predicates/exact.h"

namespace lrvd {

SymbolicVertex SymbolicVertex::mesh_vertex(int vertex) {
  SymbolicVertex q;
  q.type = Type::A;
  q.v[0] = vertex;
  return q;
}

SymbolicVertex SymbolicVertex::on_edge(int v0, int v1, int a, int b) {
  SymbolicVertex q;
  q.type = Type::B;
  q.v[0] = std::min(v0, v1);
  q.v[1] = std::max(v0, v1);
  q.label[0] = std::min(a, b);
  q.label[1] = std::max(a, b);
  return q;
}

SymbolicVertex SymbolicVertex::in_triangle(const std::array<int, 3>& triangle, int a, int b, int c) {
  SymbolicVertex q;
  q.type = Type::C;
  q.v = triangle;
  q.label = {a, b, c};
  std::sort(q.label.begin(), q.label.end());
  return q;
}

bool SymbolicVertex::on_mesh_edge(int a, int b) const {
  if (type == Type::A) return v[0] == a || v[0] == b;
  if (type == Type::B) return v[0] == std::min(a, b) && v[1] == std::max(a, b);
  return false;
}

SymbolicContext checked_context(const Vec3* vertices, std::size_t vertex_count, const Site* sites,
                                std::size_t site_count) {
  SymbolicContext ctx{vertices, sites, true};
  for (std::size_t v = 0; v < vertex_count && ctx.in_range; ++v) ctx.in_range = predicates::in_filter_range(vertices[v]);
  for (std::size_t s = 0; s < site_count && ctx.in_range; ++s) ctx.in_range = predicates::in_filter_range(sites[s]);
  return ctx;
}

Sign side(const SymbolicVertex& q, int i, int l, const SymbolicContext& ctx) {
  using Type = SymbolicVertex::Type;
  const Site* s = ctx.sites;
  const Vec3* p = ctx.vertices;
  switch (q.type) {
    case Type::A:
      return predicates::side1(s[i], s[l], p[q.v[0]], ctx.in_range);
    case Type::B: {
      assert(q.has_label(i));
      if (q.has_label(l)) return Sign::Zero;
      const int j = q.label[0] == i ? q.label[1] : q.label[0];
      return predicates::side2(s[i], s[j], s[l], p[q.v[0]], p[q.v[1]], ctx.in_range);
    }
    case Type::C: {
      assert(q.has_label(i));
      if (q.has_label(l)) return Sign::Zero;
      int others[2], n = 0;
      for (int x : q.label)
        if (x != i) others[n++] = x;
      return predicates::side3(s[i], s[others[0]], s[others[1]], s[l], p[q.v[0]], p[q.v[1]], p[q.v[2]],
                                ctx.in_range);
    }
  }
  return Sign::Zero;
}

bool coincide_unperturbed(const SymbolicVertex& u, const SymbolicVertex& w, const SymbolicContext& ctx) {
  using Type = SymbolicVertex::Type;
  if (u == w) return true;
  if (u.type == Type::A && w.type == Type::A) return false;  // two ends of a mesh edge
  const Site* s = ctx.sites;
  const Vec3* p = ctx.vertices;
  if (u.type == Type::A || w.type == Type::A) {
    // A corner and a point of bisector(a, b) on its edge: one point iff the bisector runs through it.
    const SymbolicVertex& corner = u.type == Type::A ? u : w;
    const SymbolicVertex& b = u.type == Type::A ? w : u;
    return predicates::side1_unperturbed(s[b.label[0]], s[b.label[1]], p[corner.v[0]], ctx.in_range) == Sign::Zero;
  }
  assert(u.type == Type::B && w.type == Type::B && u.v == w.v);
  // u on bisector(i, j), w on bisector(i, m): one point iff u is as close to m as to i.
  for (int i : {u.label[0], u.label[1]}) {
    if (!w.has_label(i)) continue;
    const int j = u.label[0] == i ? u.label[1] : u.label[0];
    const int m = w.label[0] == i ? w.label[1] : w.label[0];
    return predicates::side2_unperturbed(s[i], s[j], s[m], p[u.v[0]], p[u.v[1]], ctx.in_range) == Sign::Zero;
  }
  throw std::logic_error("coincide_unperturbed: two edge points without a common label");
}

SymbolicVertex intersect(const SymbolicVertex& u, const SymbolicVertex& w, int i, int l,
                         const std::array<int, 3>& triangle) {
  for (int e = 0; e < 3; ++e) {
    const int a = triangle[e], b = triangle[(e + 1) % 3];
    if (u.on_mesh_edge(a, b) && w.on_mesh_edge(a, b)) return SymbolicVertex::on_edge(a, b, i, l);
  }
  // Inside the triangle the edge lies on bisector(i, m): m is the label u and w share besides i.
  for (int m : u.label)
    if (m >= 0 && m != i && w.has_label(m)) return SymbolicVertex::in_triangle(triangle, i, m, l);
  throw std::logic_error("intersect: polygon edge is on no mesh edge and its ends share no bisector");
}

namespace {

// f_ab(q) = d_a(q) - d_b(q) in doubles.
double bisector_value(const Vec3& q, const Site& a, const Site& b) {
  return (squared_distance(q, a.p) - squared_distance(q, b.p)) - (a.w - b.w);
}

// r within the triangle's bounding box grown by the box's largest extent on every side.
bool near_triangle(const Vec3& r, const Vec3* vertices, const std::array<int, 3>& t) {
  Vec3 lo, hi;
  double size = 0;
  for (int c = 0; c < 3; ++c) {
    lo[c] = std::min({vertices[t[0]][c], vertices[t[1]][c], vertices[t[2]][c]});
    hi[c] = std::max({vertices[t[0]][c], vertices[t[1]][c], vertices[t[2]][c]});
    size = std::max(size, hi[c] - lo[c]);
  }
  for (int c = 0; c < 3; ++c)
    if (!(r[c] >= lo[c] - size && r[c] <= hi[c] + size)) return false;
  return true;
}

}  // namespace

Vec3 position(const SymbolicVertex& q, const SymbolicContext& ctx) {
  using Type = SymbolicVertex::Type;
  if (q.type == Type::A) return ctx.vertices[q.v[0]];
  const Site& a = ctx.sites[q.label[0]];
  const Site& b = ctx.sites[q.label[1]];
  if (q.type == Type::B) {
    const Vec3& q1 = ctx.vertices[q.v[0]];
    const Vec3& q2 = ctx.vertices[q.v[1]];
    const double F1 = bisector_value(q1, a, b), F2 = bisector_value(q2, a, b);
    const double t = F1 / (F1 - F2);
    if (std::isfinite(t)) {
      const Vec3 r = q1 + std::clamp(t, 0.0, 1.0) * (q2 - q1);
      if (is_finite(r)) return r;
    }
    return to_double(exact_position(q, ctx));
  }
  // Type C by Cramer's rule, relative to p1: rows n, 2(p_b - p_a), 2(p_c - p_a); rhs 0, -f_ab(p1),
  // -f_ac(p1). x = (s1 (r2 x r0) + s2 (r0 x r1)) / det.
  const Site& c = ctx.sites[q.label[2]];
  const Vec3& p1 = ctx.vertices[q.v[0]];
  const Vec3 r0 = cross(ctx.vertices[q.v[1]] - p1, ctx.vertices[q.v[2]] - p1);
  const Vec3 r1 = 2.0 * (b.p - a.p), r2 = 2.0 * (c.p - a.p);
  const double s1 = -bisector_value(p1, a, b), s2 = -bisector_value(p1, a, c);
  const double det = dot(r0, cross(r1, r2));
  if (det != 0 && std::isfinite(det)) {
    const Vec3 r = p1 + (s1 / det) * cross(r2, r0) + (s2 / det) * cross(r0, r1);
    // A polygon's type C vertex lies in its triangle; far outside means the double system was
    // too ill-conditioned, so take the exact point.
    if (is_finite(r) && near_triangle(r, ctx.vertices, q.v)) return r;
  }
  return to_double(exact_position(q, ctx));
}

namespace {

// Slot of q in a table of mask + 1 slots (a power of two): the fields paired into three 64-bit
// words, each multiplied by its own odd constant, summed, and the high half of the sum taken (its
// low bits alone would repeat along runs of consecutive indices).
std::size_t home_slot(const SymbolicVertex& q, std::size_t mask) {
  auto pair = [](int a, int b) { return std::uint64_t(std::uint32_t(a)) | std::uint64_t(std::uint32_t(b)) << 32; };
  const std::uint64_t h = (pair(q.v[0], q.v[1]) ^ static_cast<std::uint64_t>(q.type)) * 0x9E3779B97F4A7C15ull +
                          pair(q.v[2], q.label[0]) * 0xC2B2AE3D27D4EB4Full + pair(q.label[1], q.label[2]) * 0x165667B19E3779F9ull;
  return static_cast<std::size_t>(h >> 32) & mask;
}

}  // namespace

void SymbolicVertexIndex::reserve(std::size_t n) {
  vertices_.reserve(n);
  std::size_t slots = 1024;
  while (slots < 2 * n) slots *= 2;
  if (slots > slots_.size()) rehash(slots);
}

int SymbolicVertexIndex::insert(const SymbolicVertex& q) {
  if (2 * (vertices_.size() + 1) > slots_.size()) rehash(std::max<std::size_t>(1024, 2 * slots_.size()));
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t k = home_slot(q, mask);; k = (k + 1) & mask) {
    const int id = slots_[k];
    if (id < 0) {
      slots_[k] = static_cast<int>(vertices_.size());
      vertices_.push_back(q);
      return slots_[k];
    }
    if (vertices_[id] == q) return id;
  }
}

void SymbolicVertexIndex::rehash(std::size_t slots) {
  slots_.assign(slots, -1);
  const std::size_t mask = slots - 1;
  for (int id = 0; id < static_cast<int>(vertices_.size()); ++id) {
    std::size_t k = home_slot(vertices_[id], mask);
    while (slots_[k] >= 0) k = (k + 1) & mask;
    slots_[k] = id;
  }
}

}  // namespace lrvd
