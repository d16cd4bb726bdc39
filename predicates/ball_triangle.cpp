// Ball–triangle intersection, exactly: the closest point of a triangle lies in the relative
// interior of one of its features (a corner, an edge, the face), so the ball meets the triangle
// iff a corner lies in it, or the foot of x on an edge's line lies strictly inside that edge and
// within the ball, or the foot on the plane lies strictly inside the face and within the ball.
// Each is a conjunction of polynomial signs (no division): doubles with an error bound decide them
// unless a sign is uncertain, intervals then, rationals last.
#include "predicates/ball_triangle.h"

#include <cmath>

#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>

#include "predicates/exact.h"
#include "predicates/exact_vector.h"

namespace lrvd {
namespace {

using Interval = CGAL::Interval_nt<false>;
using Q = CGAL::Gmpq;

using detail::lift;
using detail::V3;

// A double and a bound on its magnitude, evaluated together: the magnitude is the value's
// expression with every input replaced by its absolute value and every difference by a sum. For an
// expression whose inputs are exact or carry one rounding (the corners about x), evaluated in at
// most h rounded operations along any path, |computed - exact| <= γ_h · magnitude, γ_h = h u /
// (1 - h u), u = 2^-53, as long as nothing underflows or overflows (Higham, Accuracy and Stability
// of Numerical Algorithms, §3.1-3.3). The deepest expression below, the face test w|n|² - (n·p)²,
// is 22 operations deep (γ_22 < 2.5e-15); kBoundedError leaves room for the rounding of the
// magnitude itself.
struct Bounded {
  double value, magnitude;
};
constexpr double kBoundedError = 1e-14;
Bounded operator+(const Bounded& a, const Bounded& b) { return {a.value + b.value, a.magnitude + b.magnitude}; }
Bounded operator-(const Bounded& a, const Bounded& b) { return {a.value - b.value, a.magnitude + b.magnitude}; }
Bounded operator-(const Bounded& a) { return {-a.value, a.magnitude}; }
Bounded operator*(const Bounded& a, const Bounded& b) { return {a.value * b.value, a.magnitude * b.magnitude}; }

// Three-valued logic: 1 true, 0 false, -1 not known (an interval holding 0, a double within its
// error bound of 0).
int positive(const Interval& v) { return v.inf() > 0 ? 1 : (v.sup() <= 0 ? 0 : -1); }
int positive(const Bounded& v) {
  const double bound = kBoundedError * v.magnitude;
  return v.value > bound ? 1 : (v.value < -bound ? 0 : -1);  // NaN: not known
}
int positive(const Q& v) { return CGAL::sign(v) == CGAL::POSITIVE ? 1 : 0; }
int both(int a, int b) { return (a == 0 || b == 0) ? 0 : (a == 1 && b == 1 ? 1 : -1); }
int either(int a, int b) { return (a == 1 || b == 1) ? 1 : (a == 0 && b == 0 ? 0 : -1); }

// 1 when B(x, √w) meets the triangle of corners x + p[0], x + p[1], x + p[2], 0 when not, -1 when
// the number type cannot tell (intervals, bounded doubles).
template <class NT>
int meets_about(const V3<NT> (&p)[3], const NT& w) {
  int result = 0;
  for (int k = 0; k < 3 && result != 1; ++k) result = either(result, positive(w - dot(p[k], p[k])));
  for (int k = 0; k < 3 && result != 1; ++k) {
    // Edge p -> q: the foot x + ... at parameter s = -p·e / |e|² strictly inside (0, 1), and the
    // squared distance |p|² - (p·e)²/|e|² below w, i.e. (w - |p|²)|e|² + (p·e)² > 0.
    const V3<NT>& u = p[k];
    const V3<NT>& v = p[(k + 1) % 3];
    const V3<NT> e = v - u;
    const NT ue = dot(u, e), ee = dot(e, e);
    const int inside = both(positive(-ue), positive(ee + ue));
    if (inside == 0) continue;
    result = either(result, both(inside, positive((w - dot(u, u)) * ee + ue * ue)));
  }
  if (result == 1) return 1;
  // The face: the foot of x on the plane strictly inside (x seen from each edge on the side of
  // the normal), and (n·a)² < w |n|².
  const V3<NT> n = cross(p[1] - p[0], p[2] - p[0]);
  int inside = 1;
  for (int k = 0; k < 3 && inside != 0; ++k) inside = both(inside, positive(dot(cross(p[k], p[(k + 1) % 3]), n)));
  if (inside != 0) {
    const NT h = dot(n, p[0]);
    result = either(result, both(inside, positive(w * dot(n, n) - h * h)));
  }
  return result;
}

// 1 when B(x, √w) meets abc, 0 when not, -1 when the number type cannot tell.
template <class NT>
int meets(const V3<NT>& x, const NT& w, const V3<NT>& a, const V3<NT>& b, const V3<NT>& c) {
  const V3<NT> p[3] = {a - x, b - x, c - x};  // the corners about x
  return meets_about(p, w);
}

// A nonzero input of the bounded doubles: from 1e-50 to 1e50 in absolute value, products of up
// to six of them (the face test's degree) neither underflow nor overflow (and a sum or difference
// that underflows is exact), so the error bound holds.
bool in_bounded_range(double v) { return v == 0 || (std::fabs(v) >= 1e-50 && std::fabs(v) <= 1e50); }

// meets() in bounded doubles: the corners about x rounded once each (one operation deep).
int meets_bounded(const Vec3& x, double w, const Vec3& a, const Vec3& b, const Vec3& c) {
  if (!in_bounded_range(w)) return -1;
  V3<Bounded> p[3];
  const Vec3* corners[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const Vec3 d = *corners[k] - x;
    if (!in_bounded_range(d.x) || !in_bounded_range(d.y) || !in_bounded_range(d.z)) return -1;
    p[k] = {{d.x, std::fabs(d.x)}, {d.y, std::fabs(d.y)}, {d.z, std::fabs(d.z)}};
  }
  return meets_about(p, Bounded{w, std::fabs(w)});
}

}  // namespace

bool ball_meets_triangle(const Vec3& x, double w, const Vec3& a, const Vec3& b, const Vec3& c) {
  if (const int r = meets_bounded(x, w, a, b, c); r >= 0) return r == 1;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const int r = meets<Interval>(lift<Interval>(x), Interval(w), lift<Interval>(a), lift<Interval>(b), lift<Interval>(c));
    if (r >= 0) return r == 1;
  }
  return meets<Q>(lift<Q>(x), Q(w), lift<Q>(a), lift<Q>(b), lift<Q>(c)) == 1;
}

bool ball_meets_triangle(const ExactPoint& x, const Q& w, const Vec3& a, const Vec3& b, const Vec3& c) {
  {
    // The rationals' enclosing intervals first.
    CGAL::Protect_FPU_rounding<true> upward;
    const V3<Interval> xi{Interval(CGAL::to_interval(x.x)), Interval(CGAL::to_interval(x.y)), Interval(CGAL::to_interval(x.z))};
    const int r = meets<Interval>(xi, Interval(CGAL::to_interval(w)), lift<Interval>(a), lift<Interval>(b), lift<Interval>(c));
    if (r >= 0) return r == 1;
  }
  return meets<Q>({x.x, x.y, x.z}, w, lift<Q>(a), lift<Q>(b), lift<Q>(c)) == 1;
}

}  // namespace lrvd
