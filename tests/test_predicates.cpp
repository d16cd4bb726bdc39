// side1/side2/side3 (paper §3.6) against independent rational references: the plain Gmpq
// determinant of each predicate, and on exact ties the geometric definition evaluated with the
// weights perturbed by powers of a symbolic epsilon. Plus invariants over small integer grids.
#include <catch2/catch.hpp>

#include <CGAL/Gmpq.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <thread>
#include <vector>

#include "predicates/predicates.h"

using lrvd::Sign;
using lrvd::Site;
using lrvd::Vec3;
namespace pr = lrvd::predicates;

namespace {

using Q = CGAL::Gmpq;

Sign sign_of(const Q& x) { return static_cast<Sign>(static_cast<int>(CGAL::sign(x))); }

// ---- Reference 1: the plain determinant in absolute coordinates over Q.

// Laplace expansion along the first row (no divisions: dyadic Gmpq products stay cheap).
Q det(const std::vector<std::vector<Q>>& m) {
  const std::size_t n = m.size();
  if (n == 1) return m[0][0];
  Q d = 0;
  for (std::size_t c = 0; c < n; ++c) {
    if (m[0][c] == 0) continue;
    std::vector<std::vector<Q>> minor;
    for (std::size_t r = 1; r < n; ++r) {
      minor.emplace_back();
      for (std::size_t k = 0; k < n; ++k)
        if (k != c) minor.back().push_back(m[r][k]);
    }
    const Q term = m[0][c] * det(minor);
    d = c % 2 ? d - term : d + term;
  }
  return d;
}

Q qd(double x) { return Q(x); }
Q qdot(const Vec3& a, const Vec3& b) { return qd(a.x) * qd(b.x) + qd(a.y) * qd(b.y) + qd(a.z) * qd(b.z); }
// Row of bisector(a, b) as a.q = b: [2(p_b - p_a), |p_b|^2 - |p_a|^2 + w_a - w_b].
std::vector<Q> bisector_row(const Site& a, const Site& b) {
  return {2 * (qd(b.p.x) - qd(a.p.x)), 2 * (qd(b.p.y) - qd(a.p.y)), 2 * (qd(b.p.z) - qd(a.p.z)),
          qdot(b.p, b.p) - qdot(a.p, a.p) + qd(a.w) - qd(b.w)};
}
// f_ab(q) = 2 q.(p_b - p_a) + |p_a|^2 - |p_b|^2 - w_a + w_b, from its row.
Q f_row(const std::vector<Q>& r, const Vec3& q) { return r[0] * qd(q.x) + r[1] * qd(q.y) + r[2] * qd(q.z) - r[3]; }
Q f_abs(const Site& a, const Site& b, const Vec3& q) { return f_row(bisector_row(a, b), q); }

Sign det_side1(const Site& i, const Site& l, const Vec3& q) { return -sign_of(f_abs(i, l, q)); }
Sign det_side2(const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2) {
  const std::vector<Q> rj = bisector_row(i, j), rl = bisector_row(i, l);
  const Q F1 = f_row(rj, q1), F2 = f_row(rj, q2), G1 = f_row(rl, q1), G2 = f_row(rl, q2);
  return -(sign_of(F1 * G2 - G1 * F2) * sign_of(F1 - F2));
}
// [n, n.p1] with n = (p2 - p1) x (p3 - p1): the plane row.
std::vector<Q> plane_row(const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  const Q e1[3] = {qd(p2.x) - qd(p1.x), qd(p2.y) - qd(p1.y), qd(p2.z) - qd(p1.z)};
  const Q e2[3] = {qd(p3.x) - qd(p1.x), qd(p3.y) - qd(p1.y), qd(p3.z) - qd(p1.z)};
  std::vector<Q> n(4);
  for (int c = 0; c < 3; ++c) n[c] = e1[(c + 1) % 3] * e2[(c + 2) % 3] - e1[(c + 2) % 3] * e2[(c + 1) % 3];
  n[3] = n[0] * qd(p1.x) + n[1] * qd(p1.y) + n[2] * qd(p1.z);
  return n;
}
// det4 = det [[M, r], [a_il, b_il]] and det M (the first three rows and columns).
struct Det3 {
  Q d4, dM;
};
Det3 det3_ref(const Site& i, const Site& j, const Site& k, const Site& l, const Vec3& p1,
              const Vec3& p2, const Vec3& p3) {
  std::vector<std::vector<Q>> m = {plane_row(p1, p2, p3), bisector_row(i, j), bisector_row(i, k), bisector_row(i, l)};
  Det3 d;
  d.d4 = det(m);
  m.pop_back();
  for (auto& row : m) row.pop_back();
  d.dM = det(m);
  return d;
}
Q det_M(const Site& i, const Site& j, const Site& k, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  return det3_ref(i, j, k, k, p1, p2, p3).dM;
}
// g det M = -det4 and side = -sign(g).
Sign det_side3(const Det3& d) { return sign_of(d.d4) * sign_of(d.dM); }
Sign det_side3(const Site& i, const Site& j, const Site& k, const Site& l, const Vec3& p1,
               const Vec3& p2, const Vec3& p3) {
  return det_side3(det3_ref(i, j, k, l, p1, p2, p3));
}

// ---- Reference 2: the geometric definition with perturbed weights w + eps^(rank(id)+1),
// evaluated exactly as polynomials in eps; the sign as eps -> 0+ is the lowest nonzero term's.

struct EpsPoly {
  std::vector<Q> c;  // c[k]: coefficient of eps^k
  EpsPoly(const Q& q = Q(0)) : c{q} {}
  static EpsPoly power(int k) {
    EpsPoly p;
    p.c.assign(k + 1, Q(0));
    p.c[k] = 1;
    return p;
  }
};
EpsPoly operator+(EpsPoly a, const EpsPoly& b) {
  if (a.c.size() < b.c.size()) a.c.resize(b.c.size(), Q(0));
  for (std::size_t k = 0; k < b.c.size(); ++k) a.c[k] += b.c[k];
  return a;
}
EpsPoly operator-(const EpsPoly& a) {
  EpsPoly r = a;
  for (Q& x : r.c) x = -x;
  return r;
}
EpsPoly operator-(const EpsPoly& a, const EpsPoly& b) { return a + (-b); }
EpsPoly operator*(const EpsPoly& a, const EpsPoly& b) {
  EpsPoly r;
  r.c.assign(a.c.size() + b.c.size() - 1, Q(0));
  for (std::size_t x = 0; x < a.c.size(); ++x)
    for (std::size_t y = 0; y < b.c.size(); ++y) r.c[x + y] += a.c[x] * b.c[y];
  return r;
}
EpsPoly operator/(EpsPoly a, const Q& s) {
  for (Q& x : a.c) x /= s;
  return a;
}
Sign sign_of(const EpsPoly& p) {
  for (const Q& x : p.c)
    if (x != 0) return sign_of(x);
  return Sign::Zero;
}
bool is_constant(const EpsPoly& p) {
  return std::all_of(p.c.begin() + 1, p.c.end(), [](const Q& x) { return x == 0; });
}

using P = std::array<EpsPoly, 3>;
P point(const Vec3& v) { return {EpsPoly(qd(v.x)), EpsPoly(qd(v.y)), EpsPoly(qd(v.z))}; }
// Perturbed power distance; `rank` is the site's position in the id order of the configuration.
EpsPoly power_distance(const P& q, const Site& s, int rank) {
  EpsPoly d;
  for (int c = 0; c < 3; ++c) {
    const EpsPoly t = q[c] - EpsPoly(qd(s.p[c]));
    d = d + t * t;
  }
  return d - (EpsPoly(qd(s.w)) + EpsPoly::power(rank + 1));
}

// Ranks of the sites' ids (ties keep equal ranks).
template <std::size_t N>
std::array<int, N> ranks(const std::array<const Site*, N>& s) {
  std::array<int, N> r{};
  for (std::size_t a = 0; a < N; ++a)
    for (std::size_t b = 0; b < N; ++b) r[a] += s[b]->id < s[a]->id;
  return r;
}

Sign geo_side1(const Site& i, const Site& l, const Vec3& q) {
  const auto r = ranks<2>({&i, &l});
  const P x = point(q);
  return -sign_of(power_distance(x, i, r[0]) - power_distance(x, l, r[1]));
}

Sign geo_side2(const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2) {
  const auto r = ranks<3>({&i, &j, &l});
  const P a = point(q1), b = point(q2);
  const EpsPoly F1 = power_distance(a, i, r[0]) - power_distance(a, j, r[1]);
  const EpsPoly F2 = power_distance(b, i, r[0]) - power_distance(b, j, r[1]);
  const EpsPoly den = F1 - F2;
  REQUIRE(is_constant(den));
  REQUIRE(den.c[0] != 0);
  const EpsPoly t = F1 / den.c[0];
  P q;
  for (int c = 0; c < 3; ++c) q[c] = a[c] + t * (b[c] - a[c]);
  return -sign_of(power_distance(q, i, r[0]) - power_distance(q, l, r[2]));
}

Sign geo_side3(const Site& i, const Site& j, const Site& k, const Site& l, const Vec3& p1,
               const Vec3& p2, const Vec3& p3) {
  const auto r = ranks<4>({&i, &j, &k, &l});
  // Rows: n.q = n.p1 and d_i(q) = d_m(q) <=> 2 (p_m - p_i).q = |p_m|^2 - |p_i|^2 + w_i' - w_m'.
  Q m[3][3];
  const std::vector<Q> n = plane_row(p1, p2, p3);
  for (int c = 0; c < 3; ++c) m[0][c] = n[c];
  const Site* s[3] = {&i, &j, &k};
  EpsPoly rhs[3];
  rhs[0] = EpsPoly(n[3]);
  const EpsPoly wi = EpsPoly(qd(i.w)) + EpsPoly::power(r[0] + 1);
  for (int row = 1; row < 3; ++row) {
    for (int c = 0; c < 3; ++c) m[row][c] = 2 * (qd(s[row]->p[c]) - qd(i.p[c]));
    const EpsPoly wm = EpsPoly(qd(s[row]->w)) + EpsPoly::power(r[row] + 1);
    rhs[row] = EpsPoly(qdot(s[row]->p, s[row]->p) - qdot(i.p, i.p)) + wi - wm;
  }
  // Cramer: q = adj(M) rhs / det M, adj[c][row] = cofactor(row, c).
  auto cof = [&](int row, int c) {
    const int r0 = (row + 1) % 3, r1 = (row + 2) % 3, c0 = (c + 1) % 3, c1 = (c + 2) % 3;
    return m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
  };
  const Q d = m[0][0] * cof(0, 0) + m[0][1] * cof(0, 1) + m[0][2] * cof(0, 2);
  REQUIRE(d != 0);
  P q;
  for (int c = 0; c < 3; ++c) q[c] = (rhs[0] * EpsPoly(cof(0, c)) + rhs[1] * EpsPoly(cof(1, c)) + rhs[2] * EpsPoly(cof(2, c))) / d;
  return -sign_of(power_distance(q, i, r[0]) - power_distance(q, l, r[3]));
}

// Expected answer: the plain determinant when it is nonzero, else the perturbed definition.
Sign expect1(const Site& i, const Site& l, const Vec3& q) {
  const Sign s = det_side1(i, l, q);
  return s != Sign::Zero ? s : geo_side1(i, l, q);
}
Sign expect2(const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2) {
  const Sign s = det_side2(i, j, l, q1, q2);
  return s != Sign::Zero ? s : geo_side2(i, j, l, q1, q2);
}
Sign expect3(const Site& i, const Site& j, const Site& k, const Site& l, const Vec3& p1,
             const Vec3& p2, const Vec3& p3) {
  const Sign s = det_side3(i, j, k, l, p1, p2, p3);
  return s != Sign::Zero ? s : geo_side3(i, j, k, l, p1, p2, p3);
}

// ---- Random inputs.

enum class Scale { Uniform, Grid, Tiny, Denormal, Huge, HugeUniform, Mixed };
// Mostly unit and grid inputs (the grid makes the ties); 1 in 16 of each extreme scale.
constexpr Scale kScales[16] = {Scale::Uniform, Scale::Grid,    Scale::Grid,     Scale::Tiny,
                               Scale::Uniform, Scale::Grid,    Scale::Grid,     Scale::Denormal,
                               Scale::Uniform, Scale::Grid,    Scale::Grid,     Scale::Huge,
                               Scale::Uniform, Scale::Grid,    Scale::HugeUniform, Scale::Mixed};

struct Gen {
  std::mt19937_64 rng{20140101};
  Scale scale = Scale::Uniform;
  bool power = false;
  double uni() { return std::uniform_real_distribution<double>(-1, 1)(rng); }
  double grid() { return double(std::uniform_int_distribution<int>(-2, 2)(rng)); }
  // Coordinates scaled by 2^e and weights by 2^2e keep the grid's exact ties (weights get at
  // least 2^-1074 at the subnormal scale).
  double value(bool is_weight) {
    const int k = is_weight ? 2 : 1;
    switch (scale) {
      case Scale::Uniform: return is_weight ? 0.5 * uni() : uni();
      case Scale::Grid: return grid();
      case Scale::Tiny: return std::ldexp(grid(), -500 * k);
      case Scale::Denormal: return std::ldexp(grid(), is_weight ? -1074 : -1060);
      case Scale::Huge: return std::ldexp(grid(), 500 * k);
      case Scale::HugeUniform: return uni() * 1e300;
      case Scale::Mixed: return std::ldexp(grid(), 1000 * std::uniform_int_distribution<int>(-1, 1)(rng));
    }
    return 0;
  }
  double coord() { return value(false); }
  double weight() { return power ? value(true) : 0.0; }
  Vec3 point() { return {coord(), coord(), coord()}; }
  // N sites with distinct ids in a random order.
  template <std::size_t N>
  std::array<Site, N> sites() {
    std::array<int, N> ids;
    for (std::size_t a = 0; a < N; ++a) ids[a] = int(a) * 3 + 1;
    std::shuffle(ids.begin(), ids.end(), rng);
    std::array<Site, N> s;
    for (std::size_t a = 0; a < N; ++a) s[a] = Site{point(), weight(), ids[a]};
    return s;
  }
  void next_mode(int n) {
    scale = kScales[n % 16];
    power = (n / 16) % 2 == 1;
  }
};

// side2 from the shared power distances of q1 and q2, as the clipper calls it.
Sign shared_side2(const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2) {
  using pr::bounded_power_distance;
  return pr::side2(i, j, l, q1, q2, bounded_power_distance(i, q1), bounded_power_distance(j, q1),
                   bounded_power_distance(l, q1), bounded_power_distance(i, q2), bounded_power_distance(j, q2),
                   bounded_power_distance(l, q2));
}

bool all_in_range(std::initializer_list<Site> sites, std::initializer_list<Vec3> points) {
  for (const Site& s : sites)
    if (!pr::in_filter_range(s)) return false;
  for (const Vec3& p : points)
    if (!pr::in_filter_range(p)) return false;
  return true;
}

}  // namespace

TEST_CASE("side1 agrees with the Gmpq determinant and the perturbed definition on random inputs", "[predicates]") {
  Gen g;
  int ties = 0, in_range = 0;
  for (int n = 0; n < 100000; ++n) {
    g.next_mode(n);
    const auto s = g.sites<2>();
    const Vec3 q = g.point();
    Sign expected = det_side1(s[0], s[1], q);
    if (expected == Sign::Zero) {
      ++ties;
      expected = geo_side1(s[0], s[1], q);
    }
    REQUIRE(expected != Sign::Zero);
    REQUIRE(pr::side1(s[0], s[1], q) == expected);
    // A caller that checked the range once gets the same answer without the per-call check.
    if (pr::in_filter_range(s[0]) && pr::in_filter_range(s[1]) && pr::in_filter_range(q)) {
      ++in_range;
      REQUIRE(pr::side1(s[0], s[1], q, true) == expected);
      // From the shared power distances (as the clipper tests a triangle's corners).
      REQUIRE(pr::side1(s[0], s[1], q, pr::bounded_power_distance(s[0], q), pr::bounded_power_distance(s[1], q)) ==
              expected);
    }
  }
  CHECK(ties > 1000);  // the grids must exercise the perturbation
  CHECK(in_range > 50000);
  CHECK(in_range < 100000);  // the huge modes are out of the filters' range
}

TEST_CASE("side2 agrees with the Gmpq determinant and the perturbed definition on random inputs", "[predicates]") {
  Gen g;
  int ties = 0, in_range = 0;
  for (int n = 0; n < 100000;) {
    g.next_mode(n);
    const auto s = g.sites<3>();
    const Vec3 q1 = g.point(), q2 = g.point();
    if (f_abs(s[0], s[1], q1) == f_abs(s[0], s[1], q2)) continue;  // no vertex
    ++n;
    Sign expected = det_side2(s[0], s[1], s[2], q1, q2);
    if (expected == Sign::Zero) {
      ++ties;
      expected = geo_side2(s[0], s[1], s[2], q1, q2);
    }
    REQUIRE(expected != Sign::Zero);
    REQUIRE(pr::side2(s[0], s[1], s[2], q1, q2) == expected);
    if (pr::in_filter_range(s[0]) && pr::in_filter_range(s[1]) && pr::in_filter_range(s[2]) &&
        pr::in_filter_range(q1) && pr::in_filter_range(q2)) {
      ++in_range;
      REQUIRE(pr::side2(s[0], s[1], s[2], q1, q2, true) == expected);
      REQUIRE(shared_side2(s[0], s[1], s[2], q1, q2) == expected);
    }
  }
  CHECK(ties > 1000);
  CHECK(in_range > 50000);
}

TEST_CASE("side3 agrees with the Gmpq determinant and the perturbed definition on random inputs", "[predicates]") {
  Gen g;
  int ties = 0, in_range = 0;
  for (int n = 0; n < 100000;) {
    g.next_mode(n);
    const auto s = g.sites<4>();
    const Vec3 p1 = g.point(), p2 = g.point(), p3 = g.point();
    const Det3 d = det3_ref(s[0], s[1], s[2], s[3], p1, p2, p3);
    if (d.dM == 0) continue;  // no vertex
    ++n;
    Sign expected = det_side3(d);
    if (expected == Sign::Zero) {
      ++ties;
      expected = geo_side3(s[0], s[1], s[2], s[3], p1, p2, p3);
    }
    REQUIRE(expected != Sign::Zero);
    REQUIRE(pr::side3(s[0], s[1], s[2], s[3], p1, p2, p3) == expected);
    if (std::all_of(s.begin(), s.end(), [](const Site& x) { return pr::in_filter_range(x); }) &&
        pr::in_filter_range(p1) && pr::in_filter_range(p2) && pr::in_filter_range(p3)) {
      ++in_range;
      REQUIRE(pr::side3(s[0], s[1], s[2], s[3], p1, p2, p3, true) == expected);
    }
  }
  CHECK(ties > 500);
  CHECK(in_range > 50000);
}

TEST_CASE("The two references agree wherever the determinant is nonzero", "[predicates]") {
  Gen g;
  for (int n = 0; n < 3000; ++n) {
    g.next_mode(n);
    const auto s = g.sites<4>();
    const Vec3 p1 = g.point(), p2 = g.point(), p3 = g.point();
    if (Sign d = det_side1(s[0], s[1], p1); d != Sign::Zero) REQUIRE(geo_side1(s[0], s[1], p1) == d);
    if (f_abs(s[0], s[1], p1) != f_abs(s[0], s[1], p2))
      if (Sign d = det_side2(s[0], s[1], s[2], p1, p2); d != Sign::Zero)
        REQUIRE(geo_side2(s[0], s[1], s[2], p1, p2) == d);
    if (det_M(s[0], s[1], s[2], p1, p2, p3) != 0)
      if (Sign d = det_side3(s[0], s[1], s[2], s[3], p1, p2, p3); d != Sign::Zero)
        REQUIRE(geo_side3(s[0], s[1], s[2], s[3], p1, p2, p3) == d);
  }
}


// ---- Constructed degenerate inputs: every answer is exact, ties are broken by the ids.

namespace {
Vec3 scaled(const Vec3& v, int e) { return {std::ldexp(v.x, e), std::ldexp(v.y, e), std::ldexp(v.z, e)}; }
Site scaled(const Site& s, int e) { return {scaled(s.p, e), std::ldexp(s.w, 2 * e), s.id}; }
constexpr int kExponents[] = {0, -500, 500, -1000, 1000};  // 2^+-1000 ~ 1e+-301 (weights 0 there)
}  // namespace

TEST_CASE("Sites equidistant from a mesh vertex: the lower id wins", "[predicates]") {
  const Vec3 q{1, 2, 3};
  for (int e : kExponents) {
    const bool w = std::abs(e) < 1000;
    const Site voronoi_i{q + Vec3{1, 0, 0}, 0, 5}, voronoi_l{q - Vec3{0, 0, 1}, 0, 9};
    const Site power_i{q + Vec3{1, 0, 0}, w ? 3.0 : 0.0, 5}, power_l{q + Vec3{0, w ? 2.0 : 1.0, 0}, w ? 6.0 : 0.0, 9};
    for (auto [i, l] : {std::pair{voronoi_i, voronoi_l}, std::pair{power_i, power_l}}) {
      const Site si = scaled(i, e), sl = scaled(l, e);
      const Vec3 sq = scaled(q, e);
      REQUIRE(det_side1(si, sl, sq) == Sign::Zero);
      CHECK(pr::side1(si, sl, sq) == Sign::Positive);
      CHECK(pr::side1(sl, si, sq) == Sign::Negative);
      CHECK(pr::side1(si, sl, sq) == geo_side1(si, sl, sq));
    }
  }
}

TEST_CASE("Duplicate samples (same point, different ids): the lower id owns the point", "[predicates]") {
  Gen g;
  g.scale = Scale::Grid;
  for (int n = 0; n < 2000; ++n) {
    g.power = n % 2;
    auto s = g.sites<4>();
    const Vec3 p1 = g.point(), p2 = g.point(), p3 = g.point();
    // Site 3 duplicates site n % 3 with a different id.
    s[3].p = s[n % 3].p, s[3].w = s[n % 3].w;
    CHECK(pr::side1(s[n % 3], s[3], p1) == (s[n % 3].id < s[3].id ? Sign::Positive : Sign::Negative));
    CHECK(pr::side1(s[0], s[3], p1) == expect1(s[0], s[3], p1));
    if (f_abs(s[0], s[1], p1) != f_abs(s[0], s[1], p2))
      CHECK(pr::side2(s[0], s[1], s[3], p1, p2) == expect2(s[0], s[1], s[3], p1, p2));
    if (det_M(s[0], s[1], s[2], p1, p2, p3) != 0)
      CHECK(pr::side3(s[0], s[1], s[2], s[3], p1, p2, p3) == expect3(s[0], s[1], s[2], s[3], p1, p2, p3));
  }
}

TEST_CASE("A bisector through a mesh vertex, and one along a mesh edge", "[predicates]") {
  const Vec3 q1{0, 0, 0}, q2{4, 0, 0}, q3{0, 4, 0};
  for (int e : kExponents) {
    const Vec3 a = scaled(q1, e), b = scaled(q2, e), c = scaled(q3, e);
    // bisector(i, j) is the plane x = 0 through q1; l is as far from q1 as i and j.
    const Site i = scaled(Site{{-1, 1, 0}, 0, 4}, e), j = scaled(Site{{1, 1, 0}, 0, 2}, e);
    for (const Site& l0 : {Site{{-1, -1, 0}, 0, 0}, Site{{0, 0, 2}, 2, 7}, Site{{1, 1, 0}, 0, 9}}) {
      const Site l = scaled(std::abs(e) < 1000 ? l0 : Site{l0.p, 0, l0.id}, e);
      REQUIRE(pr::side2(i, j, l, a, b) == expect2(i, j, l, a, b));
      REQUIRE(pr::side2(j, i, l, a, b) == pr::side2(i, j, l, a, b));
      REQUIRE(pr::side2(i, j, l, b, a) == pr::side2(i, j, l, a, b));
      REQUIRE(pr::side3(i, j, l, l, a, b, c) == Sign::Zero);  // l repeats a defining site
      // The tie itself, before the perturbation resolves it: the edge point is on bisector(i, l)
      // (the weighted l ties only with its weight, which the largest scales drop).
      if (std::abs(e) < 1000) REQUIRE(pr::side2_unperturbed(i, j, l, a, b) == Sign::Zero);
    }
    REQUIRE(pr::side1_unperturbed(i, j, a) == Sign::Zero);
    REQUIRE(pr::side1(i, j, a) != Sign::Zero);
    REQUIRE(pr::side1_unperturbed(i, j, b) == pr::side1(i, j, b));  // no tie at the other end
    // bisector(i, k) is the plane y = 0 holding edge (q1, q2): both ends tie the same way, and
    // the type (b) vertex does not exist.
    const Site k = scaled(Site{{1, -1, 0}, 0, 6}, e);
    CHECK(pr::side1(j, k, a) == Sign::Positive);
    CHECK(pr::side1(j, k, b) == Sign::Positive);
    CHECK(pr::side2(j, k, i, a, b) == Sign::Zero);
  }
}

TEST_CASE("Four cospherical samples put the type (c) vertex on the fourth bisector", "[predicates]") {
  // Sites at power distance 25 from the origin, which lies in the plane of the triangle.
  const std::vector<Site> sphere = {{{3, 4, 0}, 0, 3},  {{-3, 0, 4}, 0, 1}, {{0, -5, 0}, 0, 5},
                                    {{4, 0, -3}, 0, 0}, {{0, 0, 5}, 0, 4},  {{1, 0, 0}, -24, 2},
                                    {{0, 2, 1}, -20, 6}};
  const Vec3 t[3] = {{-5, -5, 0}, {5, -5, 0}, {0, 5, 0}};
  int checked = 0;
  for (int e : {0, -500, 500}) {
    for (std::size_t a = 0; a < sphere.size(); ++a)
      for (std::size_t b = 0; b < sphere.size(); ++b)
        for (std::size_t c = 0; c < sphere.size(); ++c)
          for (std::size_t d = 0; d < sphere.size(); ++d) {
            if (a == b || a == c || a == d || b == c || b == d || c == d) continue;
            const Site i = scaled(sphere[a], e), j = scaled(sphere[b], e), k = scaled(sphere[c], e),
                       l = scaled(sphere[d], e);
            const Vec3 p1 = scaled(t[0], e), p2 = scaled(t[1], e), p3 = scaled(t[2], e);
            if (det_M(i, j, k, p1, p2, p3) == 0) continue;
            REQUIRE(det_side3(i, j, k, l, p1, p2, p3) == Sign::Zero);
            const Sign s = pr::side3(i, j, k, l, p1, p2, p3);
            REQUIRE(s == geo_side3(i, j, k, l, p1, p2, p3));
            REQUIRE(s == pr::side3(j, k, i, l, p1, p2, p3));
            REQUIRE(s == pr::side3(k, j, i, l, p3, p2, p1));
            ++checked;
          }
  }
  CHECK(checked > 1000);
}

TEST_CASE("Samples placed on mesh vertices and edge points", "[predicates]") {
  const Vec3 t[3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  const std::vector<Vec3> spots = {t[0], t[1], t[2], {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 1, 1}, {0, 0, -1}};
  std::mt19937_64 rng(7);
  for (int n = 0; n < 20000; ++n) {
    std::array<Site, 4> s;
    for (int a = 0; a < 4; ++a)
      s[a] = Site{spots[rng() % spots.size()], n % 2 ? double(int(rng() % 3) - 1) : 0.0, int(rng() % 4) * 4 + a};
    const int c0 = rng() % 3, c1 = (c0 + 1 + rng() % 2) % 3;
    const Vec3 &q1 = t[c0], &q2 = t[c1];
    CHECK(pr::side1(s[0], s[3], q1) == expect1(s[0], s[3], q1));
    if (f_abs(s[0], s[1], q1) != f_abs(s[0], s[1], q2))
      CHECK(pr::side2(s[0], s[1], s[3], q1, q2) == expect2(s[0], s[1], s[3], q1, q2));
    if (det_M(s[0], s[1], s[2], t[0], t[1], t[2]) != 0)
      CHECK(pr::side3(s[0], s[1], s[2], s[3], t[0], t[1], t[2]) == expect3(s[0], s[1], s[2], s[3], t[0], t[1], t[2]));
  }
}

// ---- Near-degenerate inputs for the double filter (the stage before the intervals): exact ties
// in large coordinates with small differences, moved off the tie by 0 to 2^32 ulps of one input so
// that the value crosses the filter's error bound; and mixed scales whose products underflow.

namespace {
// Signed steps in ulps: dense near 0, where |value| crosses the filter's bound, then sparse.
constexpr double kUlpSteps[] = {1,  2,  3,  4,  5,   6,   7,      8,      10,     12,    14,   16,
                                 20, 24, 32, 48, 64, 128, 512, 0x1p12, 0x1p16, 0x1p24, 0x1p32};
constexpr int kTieExponents[] = {-400, -60, 0, 20, 50};  // coordinates up to 2^(50 + e)

// x moved by k ulps of x (rounded: the references see the moved double, whatever it is).
double moved(double x, double k) {
  const double ulp = std::nextafter(std::fabs(x), INFINITY) - std::fabs(x);
  return x + k * ulp;
}

// Exact ties around a center q: integers below 2^51 times 2^e, so every sum below is exact.
struct TieGen {
  std::mt19937_64 rng{31337};
  int e = 0;       // exponent of the unit
  int spread = 0;  // log2 of the differences between the points, in units (<= 48)
  double unit(int bits) {
    const std::int64_t r = std::int64_t(1) << bits;
    return std::ldexp(double(std::uniform_int_distribution<std::int64_t>(-r, r)(rng)), e);
  }
  Vec3 center() { return {unit(49), unit(49), unit(49)}; }
  Vec3 offset() { return {unit(spread), unit(spread), unit(spread)}; }
  // Equal weights of the order of the squared differences keep every tie.
  double weight(bool power) { return power ? std::ldexp(unit(std::min(2 * spread, 50)), e) : 0.0; }
  // d mapped by a random signed permutation of its axes: |rotated(d)| = |d|.
  Vec3 rotated(const Vec3& d) {
    std::array<int, 3> axes{0, 1, 2};
    std::shuffle(axes.begin(), axes.end(), rng);
    Vec3 r;
    for (int c = 0; c < 3; ++c) r[c] = rng() % 2 ? d[axes[c]] : -d[axes[c]];
    return r;
  }
  void next(int n) {
    e = kTieExponents[n % 5];
    spread = std::array<int, 4>{0, 10, 30, 48}[(n / 5) % 4];
  }
  // Moves one of the doubles by k ulps (a zero weight becomes a subnormal one).
  void move_one(const std::vector<double*>& slots, double k) {
    double& x = *slots[rng() % slots.size()];
    x = moved(x, k);
  }
};

// Every exact tie of `make` (a configuration and the doubles it may move), and every move of one
// double by +-kUlpSteps, must agree with the references.
template <class Make, class Check>
void sweep_ulps(TieGen& g, int configurations, Make make, Check check) {
  for (int n = 0; n < configurations; ++n) {
    g.next(n);
    const auto base = make(n % 2 == 1);
    if (!base) continue;
    check(*base);
    for (double k : kUlpSteps)
      for (double sign : {-1.0, 1.0}) {
        auto x = *base;
        g.move_one(x.slots(), sign * k);
        check(x);
      }
  }
}
}  // namespace

TEST_CASE("side1 is exact a few ulps off a bisector, with large coordinates and small differences", "[predicates]") {
  struct Config {
    Site i, l;
    Vec3 q;
    std::vector<double*> slots() { return {&q.x, &q.y, &q.z, &i.p.x, &l.p.y, &i.w, &l.w}; }
  };
  TieGen g;
  int checked = 0;
  sweep_ulps(g, 1000, [&](bool power) {
    Config c;
    c.q = g.center();
    const Vec3 d = g.offset();
    const double w = g.weight(power);
    c.i = Site{c.q + d, w, 3};
    c.l = Site{c.q + g.rotated(d), w, 1};
    REQUIRE(det_side1(c.i, c.l, c.q) == Sign::Zero);
    return std::optional<Config>(c);
  }, [&](const Config& c) {
    const Sign expected = expect1(c.i, c.l, c.q);
    REQUIRE(pr::side1(c.i, c.l, c.q) == expected);
    if (pr::in_filter_range(c.i) && pr::in_filter_range(c.l) && pr::in_filter_range(c.q))
      REQUIRE(pr::side1(c.i, c.l, c.q, pr::bounded_power_distance(c.i, c.q), pr::bounded_power_distance(c.l, c.q)) ==
              expected);
    ++checked;
  });
  CHECK(checked > 40000);
}

TEST_CASE("side2 is exact a few ulps off a tie, with large coordinates and small differences", "[predicates]") {
  struct Config {
    Site i, j, l;
    Vec3 q1, q2;
    std::vector<double*> slots() {
      return {&q1.x, &q1.y, &q2.z, &i.p.x, &j.p.y, &l.p.z, &i.w, &j.w, &l.w};
    }
  };
  TieGen g;
  int checked = 0;
  sweep_ulps(g, 1000, [&](bool power) -> std::optional<Config> {
    // q is equidistant from i, j, l and lies on the line (q1, q2): the type (b) vertex is q.
    const Vec3 q = g.center(), d = g.offset(), a = g.offset();
    const double w = g.weight(power);
    Config c{Site{q + d, w, 2}, Site{q + g.rotated(d), w, 5}, Site{q + g.rotated(d), w, 0}, q + a,
             q - 2.0 * a};
    if (f_abs(c.i, c.j, c.q1) == f_abs(c.i, c.j, c.q2)) return std::nullopt;  // no vertex
    REQUIRE(det_side2(c.i, c.j, c.l, c.q1, c.q2) == Sign::Zero);
    return c;
  }, [&](const Config& c) {
    if (f_abs(c.i, c.j, c.q1) == f_abs(c.i, c.j, c.q2)) return;
    const Sign expected = expect2(c.i, c.j, c.l, c.q1, c.q2);
    REQUIRE(pr::side2(c.i, c.j, c.l, c.q1, c.q2) == expected);
    if (all_in_range({c.i, c.j, c.l}, {c.q1, c.q2})) REQUIRE(shared_side2(c.i, c.j, c.l, c.q1, c.q2) == expected);
    ++checked;
  });
  CHECK(checked > 30000);
}

TEST_CASE("side3 is exact a few ulps off a tie, with large coordinates and small differences", "[predicates]") {
  struct Config {
    Site i, j, k, l;
    Vec3 p1, p2, p3;
    std::vector<double*> slots() {
      return {&p1.x, &p2.y, &p3.z, &i.p.x, &j.p.y, &k.p.z, &l.p.x, &i.w, &l.w};
    }
  };
  TieGen g;
  int checked = 0;
  sweep_ulps(g, 1000, [&](bool power) -> std::optional<Config> {
    // q is equidistant from the four sites and is the centroid of the triangle.
    const Vec3 q = g.center(), d = g.offset(), a = g.offset(), b = g.offset();
    const double w = g.weight(power);
    Config c{Site{q + d, w, 6}, Site{q + g.rotated(d), w, 2}, Site{q + g.rotated(d), w, 9},
             Site{q + g.rotated(d), w, 4}, q + a, q + b, q - a - b};
    if (det_M(c.i, c.j, c.k, c.p1, c.p2, c.p3) == 0) return std::nullopt;  // no vertex
    REQUIRE(det_side3(c.i, c.j, c.k, c.l, c.p1, c.p2, c.p3) == Sign::Zero);
    return c;
  }, [&](const Config& c) {
    if (det_M(c.i, c.j, c.k, c.p1, c.p2, c.p3) == 0) return;
    REQUIRE(pr::side3(c.i, c.j, c.k, c.l, c.p1, c.p2, c.p3) ==
            expect3(c.i, c.j, c.k, c.l, c.p1, c.p2, c.p3));
    ++checked;
  });
  CHECK(checked > 30000);
}

TEST_CASE("Products that underflow next to large cofactors do not fool the double filter", "[predicates]") {
  // Per coordinate: 0, or a small integer times 2^-540, 2^-537 (a product of two underflows), 1
  // or 2^90. Sites and end points near the origin with tiny differences, next to large ones, make
  // subnormal products that side2 and side3 multiply by large cofactors.
  std::mt19937_64 rng(1848);
  constexpr int kExp[] = {-540, -537, 0, 90};
  auto value = [&](bool weight) {
    const double k = double(int(rng() % 7) - 3);
    if (rng() % 3 == 0) return 0.0;
    const int e = kExp[rng() % 4];
    return std::ldexp(k, weight ? 2 * e : e);
  };
  auto point = [&] { return Vec3{value(false), value(false), value(false)}; };
  auto site = [&](int id, bool power) { return Site{point(), power ? value(true) : 0.0, id}; };
  for (int n = 0; n < 20000; ++n) {
    const bool power = n % 4 == 3;
    const Site i = site(4, power), j = site(1, power), k = site(7, power), l = site(2, power);
    const Vec3 p1 = point(), p2 = point(), p3 = point();
    REQUIRE(pr::side1(i, l, p1) == expect1(i, l, p1));
    if (f_abs(i, j, p1) != f_abs(i, j, p2))
      REQUIRE(pr::side2(i, j, l, p1, p2) == expect2(i, j, l, p1, p2));
    if (det_M(i, j, k, p1, p2, p3) != 0)
      REQUIRE(pr::side3(i, j, k, l, p1, p2, p3) == expect3(i, j, k, l, p1, p2, p3));
  }
}

TEST_CASE("Interval overflow and underflow fall through to the exact path", "[predicates]") {
  // Squares of 1e300 overflow doubles; products of 1e-300 underflow to zero.
  const Site i{{1e300, 0, 0}, 0, 1}, l{{-1e300, 1e-300, 0}, 0, 0};
  const Vec3 q{0, 0, 0};
  CHECK(pr::side1(i, l, q) == expect1(i, l, q));
  const Site a{{1e-300, 0, 0}, 0, 1}, b{{0, 1e-300, 0}, 0, 0};
  CHECK(pr::side1(a, b, q) == Sign::Negative);  // exact tie: the lower id (b) wins
  CHECK(pr::side1(a, b, Vec3{4.9e-324, 0, 0}) == Sign::Positive);
  const Site c{{3e-300, 1e-300, 0}, 1e-310, 2};
  CHECK(pr::side2(a, b, c, Vec3{-1e-300, 0, 0}, Vec3{0, 1e300, 0}) ==
        expect2(a, b, c, Vec3{-1e-300, 0, 0}, Vec3{0, 1e300, 0}));
}

TEST_CASE("Predicate counters count calls, exact evaluations and perturbations on every thread", "[predicates]") {
  const Site i{{1, 0, 0}, 0, 0}, l{{-1, 0, 0}, 0, 1};
  auto work = [&] {
    for (int n = 0; n < 100; ++n) {
      pr::side1(i, l, Vec3{0, 0, 0});  // tie: exact + perturbation
      pr::side1(i, l, Vec3{0.5, 0, 0});  // decided by the filter
    }
  };
  lrvd::reset_predicate_stats();
  std::thread other(work);
  work();
  other.join();
  const lrvd::PredicateStats s = lrvd::predicate_stats();
  CHECK(s.side1.calls == 400);
  CHECK(s.side1.exact == 200);
  CHECK(s.side1.filter_failures == 200);
  CHECK(s.side1.perturbations == 200);
  CHECK(s.total.calls == 400);
  lrvd::reset_predicate_stats();
  CHECK(lrvd::predicate_stats().total.calls == 0);
}

TEST_CASE("collinear, orient3d, orient2d and projection_axis are exact", "[predicates]") {
  for (int e : {0, -1000, 1000}) {
    const Vec3 a = scaled(Vec3{1, 1, 1}, e), b = scaled(Vec3{3, 5, 7}, e), c = scaled(Vec3{4, 7, 10}, e);
    CHECK(pr::collinear(a, b, c));
    CHECK(!pr::collinear(a, b, c + scaled(Vec3{0, 0, 0x1p-40}, e)));
    CHECK(pr::collinear(a, a, b));
    const Vec3 o{0, 0, 0}, x = scaled(Vec3{1, 0, 0}, e), y = scaled(Vec3{0, 1, 0}, e), z = scaled(Vec3{0, 0, 1}, e);
    CHECK(pr::orient3d(o, x, y, z) == Sign::Positive);
    CHECK(pr::orient3d(o, y, x, z) == Sign::Negative);
    CHECK(pr::orient3d(o, x, y, x + y) == Sign::Zero);
    CHECK(pr::orient2d(o, x, y, 2) == Sign::Positive);
    CHECK(pr::orient2d(o, x, z, 1) == Sign::Negative);  // axes (z, x)
    CHECK(pr::projection_axis(o, x, y) == 2);
    CHECK(pr::projection_axis(o, y, z) == 0);
    CHECK(pr::projection_axis(a, b, c) == -1);
  }
  // Nearly collinear: decided exactly, not by a tolerance.
  CHECK(!pr::collinear({0, 0, 0}, {1, 1, 1}, {1, 1, 1 + 0x1p-52}));
  CHECK(pr::orient2d({0, 0, 0}, {1, 1, 0}, {1 + 0x1p-52, 1 + 0x1p-52, 0}, 2) == Sign::Zero);
}
