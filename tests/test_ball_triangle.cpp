// ball_meets_triangle against an independent rational reference: the squared distance from the
// centre to the closed triangle (nearest corner, edge foot or face foot) computed in Gmpq, compared
// with w. Exact ties on small integer grids, the same grids scaled by powers of two and moved far
// from the origin, near-ties of random doubles, and degenerate triangles.
#include <catch2/catch.hpp>

#include <CGAL/Gmpq.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "predicates/ball_triangle.h"

using lrvd::Vec3;

namespace {

using Q = CGAL::Gmpq;

struct QV {
  Q x, y, z;
};
QV lift(const Vec3& a) { return {Q(a.x), Q(a.y), Q(a.z)}; }
QV operator-(const QV& a, const QV& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
QV scaled(const QV& a, const Q& s) { return {a.x * s, a.y * s, a.z * s}; }
Q dot(const QV& a, const QV& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
QV cross(const QV& a, const QV& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// The exact squared distance from x to the closed triangle abc (a degenerate one is its segments).
Q squared_distance_to_triangle(const Vec3& xd, const Vec3& ad, const Vec3& bd, const Vec3& cd) {
  const QV x = lift(xd), corner[3] = {lift(ad), lift(bd), lift(cd)};
  Q best = dot(corner[0] - x, corner[0] - x);
  for (int k = 0; k < 3; ++k) {
    const QV& u = corner[k];
    const QV& v = corner[(k + 1) % 3];
    const QV e = v - u, xu = x - u;
    best = std::min(best, dot(xu, xu));
    const Q along = dot(xu, e), length2 = dot(e, e);
    if (length2 > 0 && along > 0 && along < length2) best = std::min(best, dot(xu, xu) - along * along / length2);
  }
  const QV n = cross(corner[1] - corner[0], corner[2] - corner[0]);
  const Q nn = dot(n, n);
  if (nn > 0) {
    const Q s = dot(x - corner[0], n);
    const QV foot = x - scaled(n, s / nn);
    bool inside = true;
    for (int k = 0; k < 3; ++k) inside = inside && dot(cross(corner[(k + 1) % 3] - corner[k], foot - corner[k]), n) >= 0;
    if (inside) best = std::min(best, s * s / nn);
  }
  return best;
}

bool reference_meets(const Vec3& x, double w, const Vec3& a, const Vec3& b, const Vec3& c) {
  return squared_distance_to_triangle(x, a, b, c) < Q(w);
}

// Integer points in [-4, 4]³ and integer w: many centres lie exactly on the ball's sphere through
// a corner, an edge or the face.
struct GridCase {
  Vec3 x, a, b, c;
  double w;
};
GridCase grid_case(std::mt19937_64& random) {
  std::uniform_int_distribution<int> coordinate(-4, 4), weight(0, 40);
  auto point = [&] { return Vec3{double(coordinate(random)), double(coordinate(random)), double(coordinate(random))}; };
  GridCase g{point(), point(), point(), point(), 0};
  g.w = weight(random);
  return g;
}

}  // namespace

TEST_CASE("ball_meets_triangle agrees with the exact distance on integer grids with exact ties", "[predicates]") {
  std::mt19937_64 random(7);
  int ties = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const GridCase g = grid_case(random);
    INFO("trial " << trial);
    REQUIRE(lrvd::ball_meets_triangle(g.x, g.w, g.a, g.b, g.c) == reference_meets(g.x, g.w, g.a, g.b, g.c));
    ties += squared_distance_to_triangle(g.x, g.a, g.b, g.c) == Q(g.w);
  }
  CHECK(ties > 50);  // the sphere passes exactly through the triangle's nearest point
}

TEST_CASE("ball_meets_triangle is exact on grids scaled by powers of two and far from the origin", "[predicates]") {
  std::mt19937_64 random(11);
  // Scaled by 2^s and moved by an offset: both exact in doubles, so the ties stay ties.
  const double scales[] = {std::ldexp(1.0, -200), std::ldexp(1.0, -70), std::ldexp(1.0, -20), 1.0, std::ldexp(1.0, 60)};
  for (double scale : scales)
    for (double offset : {0.0, 1e6, -3e3}) {
      const double shift = offset * (scale < 1 ? 1 : scale);
      auto moved = [&](const Vec3& p) { return Vec3{p.x * scale + shift, p.y * scale - shift, p.z * scale + 0.5 * shift}; };
      for (int trial = 0; trial < 3000; ++trial) {
        const GridCase g = grid_case(random);
        const Vec3 x = moved(g.x), a = moved(g.a), b = moved(g.b), c = moved(g.c);
        const double w = g.w * scale * scale;
        INFO("scale " << scale << ", offset " << shift << ", trial " << trial);
        REQUIRE(lrvd::ball_meets_triangle(x, w, a, b, c) == reference_meets(x, w, a, b, c));
      }
    }
}

TEST_CASE("ball_meets_triangle decides near-ties of random doubles exactly", "[predicates]") {
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  auto point = [&] { return Vec3{coordinate(random), coordinate(random), coordinate(random)}; };
  int inside = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const Vec3 x = point(), a = point(), b = point(), c = point();
    // w within a few ulps of the exact squared distance, on either side.
    const double d2 = CGAL::to_double(squared_distance_to_triangle(x, a, b, c));
    double w = d2;
    for (int k = random() % 7; k > 3; --k) w = std::nextafter(w, 1e300);
    for (int k = random() % 7; k > 3; --k) w = std::nextafter(w, 0.0);
    INFO("trial " << trial);
    const bool meets = lrvd::ball_meets_triangle(x, w, a, b, c);
    REQUIRE(meets == reference_meets(x, w, a, b, c));
    inside += meets;
  }
  CHECK(inside > 500);
  CHECK(inside < 4500);
}

TEST_CASE("ball_meets_triangle on degenerate triangles: a segment, a point", "[predicates]") {
  std::mt19937_64 random(17);
  std::uniform_int_distribution<int> coordinate(-3, 3), weight(0, 20);
  auto point = [&] { return Vec3{double(coordinate(random)), double(coordinate(random)), double(coordinate(random))}; };
  for (int trial = 0; trial < 4000; ++trial) {
    const Vec3 x = point(), a = point(), b = point();
    const Vec3 mid = trial % 2 ? a : Vec3{2 * a.x - b.x, 2 * a.y - b.y, 2 * a.z - b.z};  // coincident or collinear
    const double w = weight(random);
    INFO("trial " << trial);
    REQUIRE(lrvd::ball_meets_triangle(x, w, a, b, mid) == reference_meets(x, w, a, b, mid));
    REQUIRE(lrvd::ball_meets_triangle(x, w, a, a, a) == reference_meets(x, w, a, a, a));
  }
}
