// Exact rational positions of symbolic vertices (paper §3.6), used by verification and as the
// fallback of position() when doubles overflow.
#include "predicates/exact.h"

#include <stdexcept>
#include <vector>

namespace lrvd {
namespace {

using Q = CGAL::Gmpq;

struct QV {
  Q x, y, z;
};

QV qv(const Vec3& a) { return {Q(a.x), Q(a.y), Q(a.z)}; }
QV operator-(const QV& a, const QV& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
QV operator+(const QV& a, const QV& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
QV operator*(const Q& s, const QV& a) { return {s * a.x, s * a.y, s * a.z}; }
Q dot(const QV& a, const QV& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
QV cross(const QV& a, const QV& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// f_ab(q) = d_a(q) - d_b(q).
Q bisector_value(const QV& q, const Site& a, const Site& b) {
  const QV u = q - qv(a.p), v = q - qv(b.p);
  return dot(u, u) - dot(v, v) - Q(a.w) + Q(b.w);
}

}  // namespace

ExactPoint to_exact(const Vec3& p) { return {Q(p.x), Q(p.y), Q(p.z)}; }

Vec3 to_double(const ExactPoint& p) {
  return {CGAL::to_double(p.x), CGAL::to_double(p.y), CGAL::to_double(p.z)};
}

CGAL::Gmpq exact_power_distance(const ExactPoint& q, const Site& s) {
  const Q dx = q.x - Q(s.p.x), dy = q.y - Q(s.p.y), dz = q.z - Q(s.p.z);
  return dx * dx + dy * dy + dz * dz - Q(s.w);
}

ExactPoint exact_position(const SymbolicVertex& q, const SymbolicContext& ctx) {
  using Type = SymbolicVertex::Type;
  if (q.type == Type::A) return to_exact(ctx.vertices[q.v[0]]);
  const Site& a = ctx.sites[q.label[0]];
  const Site& b = ctx.sites[q.label[1]];
  if (q.type == Type::B) {
    // q = q1 + t (q2 - q1), t = F1 / (F1 - F2): f_ab is affine along the edge.
    const QV q1 = qv(ctx.vertices[q.v[0]]), q2 = qv(ctx.vertices[q.v[1]]);
    const Q F1 = bisector_value(q1, a, b), F2 = bisector_value(q2, a, b);
    if (F1 == F2) throw std::domain_error("exact_position: edge parallel to its bisector");
    const QV r = q1 + (F1 / (F1 - F2)) * (q2 - q1);
    return {r.x, r.y, r.z};
  }
  // Type C, relative to p1: n.x = 0, 2 (p_m - p_a).x = -f_am(p1) for m = b, c.
  const Site& c = ctx.sites[q.label[2]];
  const QV p1 = qv(ctx.vertices[q.v[0]]);
  const QV r0 = cross(qv(ctx.vertices[q.v[1]]) - p1, qv(ctx.vertices[q.v[2]]) - p1);
  const QV r1 = Q(2) * (qv(b.p) - qv(a.p)), r2 = Q(2) * (qv(c.p) - qv(a.p));
  const Q s1 = -bisector_value(p1, a, b), s2 = -bisector_value(p1, a, c);
  const Q det = dot(r0, cross(r1, r2));
  if (CGAL::is_zero(det)) throw std::domain_error("exact_position: plane and bisectors do not meet in one point");
  const QV x = (s1 / det) * cross(r2, r0) + (s2 / det) * cross(r0, r1);
  const QV r = p1 + x;
  return {r.x, r.y, r.z};
}

bool zero_area_unperturbed(const SymbolicVertex* v, int count, const SymbolicContext& ctx) {
  if (count < 3) return true;
  // Twice the area times the plane's unit normal: the sum of the fan's cross products, a vector
  // normal to the plane that holds every vertex exactly. Zero iff the vertices are collinear.
  std::vector<QV> p;
  p.reserve(count);
  for (int k = 0; k < count; ++k) {
    const ExactPoint e = exact_position(v[k], ctx);
    p.push_back({e.x, e.y, e.z});
  }
  QV sum{Q(0), Q(0), Q(0)};
  for (int k = 1; k + 1 < count; ++k) sum = sum + cross(p[k] - p[0], p[k + 1] - p[0]);
  return CGAL::is_zero(sum.x) && CGAL::is_zero(sum.y) && CGAL::is_zero(sum.z);
}

}  // namespace lrvd
