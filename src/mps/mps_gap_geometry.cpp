// The area of a convex polygon outside a ball, by the sector formula (see mps_gap_geometry.h).
#include "mps/mps_gap_geometry.h"

#include <algorithm>
#include <cmath>

namespace lrvd::mps_detail {

namespace {

struct P2 {
  double x, y;
};
double cross2(const P2& a, const P2& b) { return a.x * b.y - a.y * b.x; }
double dot2(const P2& a, const P2& b) { return a.x * b.x + a.y * b.y; }

// Signed area of (triangle (0, a, b)) ∩ (disk of squared radius r2 centred at 0).
double triangle_disk_area(const P2& a, const P2& b, double r2) {
  const P2 d{b.x - a.x, b.y - a.y};
  const double A = dot2(d, d);
  if (!(A > 0)) return 0;
  const double B = dot2(a, d), C = dot2(a, a) - r2;
  double s[4];
  int n = 0;
  s[n++] = 0;
  const double disc = B * B - A * C;
  if (disc > 0) {
    const double sq = std::sqrt(disc);
    const double s1 = (-B - sq) / A, s2 = (-B + sq) / A;
    if (s1 > 0 && s1 < 1) s[n++] = s1;
    if (s2 > 0 && s2 < 1) s[n++] = s2;
  }
  s[n++] = 1;
  double area = 0;
  for (int k = 0; k + 1 < n; ++k) {
    const P2 p{a.x + s[k] * d.x, a.y + s[k] * d.y}, q{a.x + s[k + 1] * d.x, a.y + s[k + 1] * d.y};
    const double sm = 0.5 * (s[k] + s[k + 1]);
    const P2 m{a.x + sm * d.x, a.y + sm * d.y};
    if (dot2(m, m) <= r2)
      area += 0.5 * cross2(p, q);
    else
      area += 0.5 * r2 * std::atan2(cross2(p, q), dot2(p, q));
  }
  return area;
}

}  // namespace

// Area of polygon q (convex, in the plane with unit normal n, of area `area` = polygon_area(q))
// outside the ball (x, w).
double uncovered_area(const std::vector<Vec3>& q, const Vec3& n, const Vec3& x, double w, double area) {
  const double h = dot(x - q[0], n);
  const double r2 = w - h * h;
  if (!(r2 > 0)) return area;
  const Vec3 o = x - h * n;
  Vec3 u = std::abs(n.x) < 0.9 ? cross(n, Vec3{1, 0, 0}) : cross(n, Vec3{0, 1, 0});
  u = u / norm(u);
  const Vec3 v = cross(n, u);
  double inside = 0;
  for (size_t k = 0; k < q.size(); ++k) {
    const Vec3 a = q[k] - o, b = q[(k + 1) % q.size()] - o;
    inside += triangle_disk_area({dot(a, u), dot(a, v)}, {dot(b, u), dot(b, v)}, r2);
  }
  return std::max(0.0, area - std::min(std::abs(inside), area));
}

}  // namespace lrvd::mps_detail
