// Exact rational positions of symbolic vertices (paper §3.6), used by verification and as the
// fallback of position() when doubles overflow.
#include "predicates/exact.h"
#include "predicates/exact_vector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace lrvd {
namespace {

using Q = CGAL::Gmpq;
using Interval = CGAL::Interval_nt<false>;

using detail::lift;
using detail::V3;
using QV = V3<Q>;

// f_ab(q) = d_a(q) - d_b(q).
template <class NT>
NT bisector_value(const V3<NT>& q, const Site& a, const Site& b) {
  const V3<NT> u = q - lift<NT>(a.p), v = q - lift<NT>(b.p);
  return dot(u, u) - dot(v, v) - NT(a.w) + NT(b.w);
}

// The defining formula of a type B or C vertex as origin + (numerator / denominator), in one
// number type: type B, q = q1 + t (q2 - q1) with t = F1 / (F1 - F2), f_ab being affine along the
// edge; type C, relative to p1: n.x = 0 and 2 (p_m - p_a).x = -f_am(p1) for m = b, c (Cramer).
template <class NT>
struct Formula {
  V3<NT> origin;
  V3<NT> direction;  // type B: q2 - q1, with numerator F1
  V3<NT> numerator;  // type C: times 1 / denominator
  NT edge_numerator, denominator;
};

template <class NT>
Formula<NT> formula(const SymbolicVertex& q, const SymbolicContext& ctx) {
  const Site& a = ctx.sites[q.label[0]];
  const Site& b = ctx.sites[q.label[1]];
  Formula<NT> f;
  if (q.type == SymbolicVertex::Type::B) {
    f.origin = lift<NT>(ctx.vertices[q.v[0]]);
    const V3<NT> q2 = lift<NT>(ctx.vertices[q.v[1]]);
    f.direction = q2 - f.origin;
    f.edge_numerator = bisector_value(f.origin, a, b);
    f.denominator = f.edge_numerator - bisector_value(q2, a, b);
    return f;
  }
  const Site& c = ctx.sites[q.label[2]];
  f.origin = lift<NT>(ctx.vertices[q.v[0]]);
  const V3<NT> r0 = cross(lift<NT>(ctx.vertices[q.v[1]]) - f.origin, lift<NT>(ctx.vertices[q.v[2]]) - f.origin);
  const V3<NT> r1 = NT(2) * (lift<NT>(b.p) - lift<NT>(a.p)), r2 = NT(2) * (lift<NT>(c.p) - lift<NT>(a.p));
  const NT s1 = -bisector_value(f.origin, a, b), s2 = -bisector_value(f.origin, a, c);
  f.denominator = dot(r0, cross(r1, r2));
  f.numerator = s1 * cross(r2, r0) + s2 * cross(r0, r1);
  return f;
}

ExactPoint exact_point(const QV& r) { return {r.x, r.y, r.z}; }

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
  const Formula<Q> f = formula<Q>(q, ctx);
  if (CGAL::is_zero(f.denominator))
    throw std::domain_error(q.type == Type::B ? "exact_position: edge parallel to its bisector"
                                              : "exact_position: plane and bisectors do not meet in one point");
  if (q.type == Type::B) return exact_point(f.origin + (f.edge_numerator / f.denominator) * f.direction);
  return exact_point(f.origin + (Q(1) / f.denominator) * f.numerator);
}

CGAL::Gmpq exact_edge_parameter(const SymbolicVertex& q, const SymbolicContext& ctx) {
  if (q.type != SymbolicVertex::Type::B) throw std::invalid_argument("exact_edge_parameter: not a type B vertex");
  const Formula<Q> f = formula<Q>(q, ctx);
  if (CGAL::is_zero(f.denominator)) throw std::domain_error("exact_edge_parameter: edge parallel to its bisector");
  return f.edge_numerator / f.denominator;
}

namespace {

// enclose_position's body, with the rounding mode already upward (Protect_FPU_rounding).
std::optional<PositionEnclosure> enclose_upward(const SymbolicVertex& q, const SymbolicContext& ctx) {
  PositionEnclosure e{};
  if (q.type == SymbolicVertex::Type::A) {
    const Vec3& p = ctx.vertices[q.v[0]];
    e.box = {Interval(p.x), Interval(p.y), Interval(p.z)};
    return e;
  }
  const Formula<Interval> f = formula<Interval>(q, ctx);
  // The denominator's sign must be known: an interval that holds zero (or is not a number, after
  // an overflow) leaves the vertex to the exact formula.
  if (!(f.denominator.inf() > 0 || f.denominator.sup() < 0)) return std::nullopt;
  V3<Interval> r;
  if (q.type == SymbolicVertex::Type::B) {
    e.parameter = f.edge_numerator / f.denominator;
    r = f.origin + e.parameter * f.direction;
  } else {
    r = f.origin + (Interval(1) / f.denominator) * f.numerator;
  }
  e.box = {r.x, r.y, r.z};
  // Past the doubles' range (an overflow gives infinite or undefined bounds): the exact formula.
  auto finite = [](const Interval& i) { return std::isfinite(i.inf()) && std::isfinite(i.sup()); };
  if (!finite(e.box[0]) || !finite(e.box[1]) || !finite(e.box[2])) return std::nullopt;
  if (q.type == SymbolicVertex::Type::B && !finite(e.parameter)) return std::nullopt;
  return e;
}

// Encloses the squared distance from an enclosed position to c, the rounding mode upward.
Interval squared_distance_upward(const PositionEnclosure& e, const V3<Interval>& c) {
  return CGAL::square(e.box[0] - c.x) + CGAL::square(e.box[1] - c.y) + CGAL::square(e.box[2] - c.z);
}

}  // namespace

std::optional<CGAL::Sign> enclosed_power_sign(const SymbolicVertex& q, const Site& s, const SymbolicContext& ctx) {
  CGAL::Protect_FPU_rounding<true> upward;
  const std::optional<PositionEnclosure> e = enclose_upward(q, ctx);
  if (!e) return std::nullopt;
  const Interval power = squared_distance_upward(*e, lift<Interval>(s.p)) - Interval(s.w);
  if (power.inf() > 0) return CGAL::POSITIVE;
  if (power.sup() < 0) return CGAL::NEGATIVE;
  if (power.inf() == 0 && power.sup() == 0) return CGAL::ZERO;
  return std::nullopt;
}

std::optional<PositionEnclosure> enclose_position(const SymbolicVertex& q, const SymbolicContext& ctx) {
  CGAL::Protect_FPU_rounding<true> upward;
  return enclose_upward(q, ctx);
}

void distance_bounds2(const SymbolicVertex* v, int count, const Vec3& center, const SymbolicContext& ctx, double* bound2) {
  CGAL::Protect_FPU_rounding<true> upward;
  const V3<Interval> c = lift<Interval>(center);
  for (int k = 0; k < count; ++k) {
    bound2[k] = std::numeric_limits<double>::infinity();
    const std::optional<PositionEnclosure> e = enclose_upward(v[k], ctx);
    if (!e) continue;
    const Interval d2 = squared_distance_upward(*e, c);
    if (std::isfinite(d2.sup())) bound2[k] = d2.sup();
  }
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
