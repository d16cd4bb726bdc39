// Polygon-minus-disk geometry of the MPS gap pieces (mps_gaps.cpp): the area of a convex polygon
// outside a ball, a cheap lower bound of it, clipping, and whether a ball meets a polygon.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "mesh/closest_point.h"
#include "predicates/vec3.h"

namespace lrvd::mps_detail {

// Area of polygon q (convex, in the plane with unit normal n, of area `area` = polygon_area(q))
// outside the ball (x, w).
double uncovered_area(const std::vector<Vec3>& q, const Vec3& n, const Vec3& x, double w, double area);

// Internal linkage, as when they were private to mps_gaps.cpp: adding and splitting pieces call
// them for every piece, each from one place, and the compiler inlines them there only so.
namespace {

inline double polygon_area(const std::vector<Vec3>& q) {
  Vec3 s{};
  for (size_t k = 1; k + 1 < q.size(); ++k) s += cross(q[k] - q[0], q[k + 1] - q[0]);
  return 0.5 * norm(s);
}

// A lower bound of the area of polygon q (convex, in the plane with unit normal n, of area `area`)
// outside the ball (x, w), without the sector formula: where the centre o of the circle (the ball
// in the plane) lies beyond the line of an edge of q, at distance d from it on the side away from
// q, q ∩ ball is within the circular segment on q's side, itself within a rectangle of its chord
// 2√(r² − d²) by its height r − d; d >= r: q misses the ball. The least such bound over the edges
// is taken (πr² when none applies).
inline double uncovered_area_lower_bound(const std::vector<Vec3>& q, const Vec3& n, const Vec3& x, double w, double area) {
  const double h = dot(x - q[0], n);
  const double r2 = w - h * h;
  if (!(r2 > 0)) return area;
  const double r = std::sqrt(r2);
  const Vec3 o = x - h * n;
  Vec3 c{};
  for (const Vec3& y : q) c += y;
  c = c / static_cast<double>(q.size());
  double inside = M_PI * r2;
  for (size_t k = 0; k < q.size(); ++k) {
    const Vec3& a = q[k];
    const Vec3 m = cross(q[(k + 1) % q.size()] - a, n);  // in the plane, across edge k, |m| = its length
    const double sc = dot(c - a, m), so = dot(o - a, m);
    if (sc > 0 ? so >= 0 : so <= 0) continue;  // o on q's side of the edge's line (or on it)
    const double m2 = dot(m, m);
    if (!(sc * sc > 1e-12 * r2 * m2)) continue;  // the centroid too close to the line to tell q's side
    const double d = std::abs(so) / std::sqrt(m2);  // o beyond the edge's line, away from q
    if (d >= r) return area;
    inside = std::min(inside, 2 * std::sqrt(r2 - d * d) * (r - d));
  }
  return area - inside;
}

// Keeps the part of convex polygon `in` where h <= 0, h affine (given at the vertices).
template <class H>
void clip(const std::vector<Vec3>& in, H h, std::vector<Vec3>& out) {
  out.clear();
  const size_t n = in.size();
  if (n == 0) return;
  double ha = h(in[n - 1]);
  for (size_t k = 0; k < n; ++k) {
    const Vec3& a = in[(k + n - 1) % n];
    const Vec3& b = in[k];
    const double hb = h(b);
    if ((ha <= 0) != (hb <= 0)) out.push_back(a + (ha / (ha - hb)) * (b - a));
    if (hb <= 0) out.push_back(b);
    ha = hb;
  }
  if (out.size() < 3) out.clear();
}

// The plane across convex polygon q's longest diagonal, at its middle: halves are the parts where
// side(y) <= 0 and -side(y) <= 0.
struct Halving {
  Vec3 mid, dir;
  double operator()(const Vec3& y) const { return dot(y - mid, dir); }
};
inline Halving longest_diagonal_halving(const std::vector<Vec3>& q) {
  size_t a = 0, b = 0;
  double best = -1;
  for (size_t i = 0; i < q.size(); ++i)
    for (size_t j = i + 1; j < q.size(); ++j)
      if (squared_distance(q[i], q[j]) > best) best = squared_distance(q[i], q[j]), a = i, b = j;
  return {0.5 * (q[a] + q[b]), q[b] - q[a]};
}

// The ball (x, w) meets the convex polygon q[0..count).
inline bool ball_meets_polygon(const Vec3* q, int count, const Vec3& x, double w) {
  for (int k = 0; k < count; ++k)
    if (squared_distance(x, q[k]) < w) return true;  // a corner inside: no closest point needed
  // Far outside the polygon's bounding sphere (with room for rounding): no closest point needed.
  Vec3 c{};
  for (int k = 0; k < count; ++k) c += q[k];
  c = c / static_cast<double>(count);
  double radius2 = 0;
  for (int k = 0; k < count; ++k) radius2 = std::max(radius2, squared_distance(c, q[k]));
  const double reach = std::sqrt(w) + std::sqrt(radius2);
  if (squared_distance(x, c) > reach * reach * (1 + 1e-9)) return false;
  for (int k = 1; k + 1 < count; ++k)
    if (squared_distance(x, closest_point_on_triangle(x, q[0], q[k], q[k + 1]).point) < w) return true;
  return false;
}

}  // namespace

}  // namespace lrvd::mps_detail
