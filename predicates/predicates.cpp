// Filtered exact side1/side2/side3 (paper §3.6): a forward-error filter in doubles, an interval
// filter, CGAL::Mpzf exact fallback and symbolic perturbation of the weights on exact zeros.
// Derivations are in docs/algorithms/predicates.md.
#include "predicates/predicates.h"

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <mutex>
#include <utility>
#include <vector>

namespace lrvd {
namespace {

// ---------------------------------------------------------------------------------------------
// Counters: each thread owns its counters (only it writes them, so a relaxed load + store is an
// increment without a locked instruction); a registry lets predicate_stats() sum every thread.

enum Kind { kSide1, kSide2, kSide3, kOther, kKinds };
enum Field { kCalls, kFilterFailures, kExact, kPerturbations, kFields };

struct ThreadCounters {
  std::atomic<std::uint64_t> value[kKinds][kFields];
  ThreadCounters() {
    for (auto& row : value)
      for (auto& v : row) v.store(0, std::memory_order_relaxed);
  }
};

struct Registry {
  std::mutex mutex;
  std::vector<ThreadCounters*> live;
  std::uint64_t retired[kKinds][kFields] = {};  // counts of threads that have exited
};

// Never destroyed: threads may exit (and retire their counters) after static destruction.
Registry& registry() {
  static Registry* r = new Registry();
  return *r;
}

struct ThreadSlot {
  ThreadCounters counters;
  ThreadSlot() {
    Registry& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.live.push_back(&counters);
  }
  ~ThreadSlot() {
    Registry& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    for (int k = 0; k < kKinds; ++k)
      for (int f = 0; f < kFields; ++f) r.retired[k][f] += counters.value[k][f].load(std::memory_order_relaxed);
    r.live.erase(std::find(r.live.begin(), r.live.end(), &counters));
  }
};

ThreadCounters& local_counters() {
  thread_local ThreadSlot slot;
  return slot.counters;
}

inline void bump(ThreadCounters& c, Kind k, Field f) {
  std::atomic<std::uint64_t>& v = c.value[k][f];
  v.store(v.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
}

PredicateCounters to_counters(const std::uint64_t (&v)[kFields]) {
  PredicateCounters c;
  c.calls = v[kCalls];
  c.filter_failures = v[kFilterFailures];
  c.exact = v[kExact];
  c.perturbations = v[kPerturbations];
  return c;
}

// ---------------------------------------------------------------------------------------------
// Number types. The filters (Fpf below, then IA) decide only a certainly nonzero sign: an
// interval that contains 0 (including a result that is exactly [0,0]) goes to the exact path,
// which also owns the perturbation. Inputs are checked against a range in which no intermediate
// value (or magnitude) of the predicate can overflow, so the filters never hold inf or NaN;
// underflow only widens an interval, and Fpf's bound covers it (T below).

using IA = CGAL::Interval_nt<false>;
using EX = CGAL::Mpzf;

inline Sign certain_sign(const IA& x) {
  if (x.inf() > 0) return Sign::Positive;
  if (x.sup() < 0) return Sign::Negative;
  return Sign::Zero;  // undecided
}
inline Sign exact_sign(const EX& x) { return static_cast<Sign>(static_cast<int>(x.sign())); }

// Coordinates up to 2^100 and weights up to 2^200 keep every intermediate below 2^700
// (the largest is side3's D, of degree 6: < 3 * 2^205 * 6 * 2^408).
constexpr double kMaxCoord = 0x1p100;
constexpr double kMaxWeight = 0x1p200;

inline bool in_range(const Vec3& v, double bound = kMaxCoord) {
  return std::fabs(v.x) <= bound && std::fabs(v.y) <= bound && std::fabs(v.z) <= bound;
}
inline bool in_range(const Site& s) { return in_range(s.p) && std::fabs(s.w) <= kMaxWeight; }

// ---------------------------------------------------------------------------------------------
// The double filter, run before the intervals: the same templates evaluated in plain doubles (no
// rounding-mode switch) with a forward error bound (docs/algorithms/predicates.md has the derivation). Fpf
// carries the rounded value v, a magnitude m (the expression on |inputs| with - turned into +,
// plus T per product) and the number d of roundings on the deepest path. Any rounding mode,
// u = 2^-52, gamma_k = k u / (1 - k u), T = 2^-1021, no overflow (in_range):
//   fl(a +- b) = (a +- b)(1 + e)       |e| <= u  (exact when the result is subnormal)
//   fl(a * b)  = a b (1 + e) + h       |h| <= 2^-1074 <= u T  (h != 0 only on underflow)
// By induction, with E the exact value and M the unrounded m, |v - E| <= gamma_d M, |E| <= M:
//   +- : gamma_da Ma + gamma_db Mb + u (1 + gamma_max)(Ma + Mb) <= gamma_(max+1) (Ma + Mb);
//        of two inputs (d = 0): |v - E| <= u |E|, so M = |E| <= |v| / (1 - u) will do;
//   *  : |va vb - Ea Eb| <= gamma_(da+db) Ma Mb, |va vb| <= (1 + gamma_(da+db)) Ma Mb, so
//        |v - E| <= gamma_(da+db+1) Ma Mb + u T <= gamma_d (Ma Mb + T).
// T absorbs underflow anywhere in the tree, however large the cofactors. The stored m is M
// rounded r <= 2d times (once per sum; * then + T per product, the *'s underflow again <= u T),
// each time at most a factor (1 - u) low: M <= m (1 - u)^-2d. With m >= 2^-900 the product c_d m
// is normal, and c_d = d u (1 + 2^-30) >= gamma_d (1 - u)^(-2d-1) for d <= 2^19, so
// B = fl(c_d m) >= gamma_d M >= |v - E|. |v| > B then proves sign(v) = sign(E); an exact zero
// (|v| <= B) always falls through. d is at most 22 here (side3's D).

struct Fpf {
  double v = 0;  // value, rounded at every operation
  double m = 0;  // upper bound of the magnitude (see above)
  int d = 0;     // roundings along the deepest path: max + 1 for +-, sum + 1 for *
  Fpf() = default;
  explicit Fpf(double x) : v(x), m(std::fabs(x)) {}
  Fpf(double value, double magnitude, int depth) : v(value), m(magnitude), d(depth) {}
};

constexpr double kFpfUnderflow = 0x1p-1021;  // T
constexpr double kFpfMinMagnitude = 0x1p-900;
constexpr double kFpfMaxMagnitude = 0x1p1000;  // rejects inf and NaN too
constexpr int kFpfMaxDepth = 64;

// A sum of two inputs (d = 0: the coordinate differences) is rounded once, relative to itself,
// so far from the origin m is |p - q|, not |p| + |q|. In the flattened filters the test folds.
inline Fpf add(const Fpf& a, const Fpf& b, double v) {
  if (a.d == 0 && b.d == 0) return {v, std::fabs(v), 1};
  return {v, a.m + b.m, std::max(a.d, b.d) + 1};
}
inline Fpf operator+(const Fpf& a, const Fpf& b) { return add(a, b, a.v + b.v); }
inline Fpf operator-(const Fpf& a, const Fpf& b) { return add(a, b, a.v - b.v); }
inline Fpf operator*(const Fpf& a, const Fpf& b) {
  return {a.v * b.v, a.m * b.m + kFpfUnderflow, a.d + b.d + 1};
}
inline Fpf operator-(const Fpf& a) { return {-a.v, a.m, a.d}; }

inline Sign certain_sign(const Fpf& x) {
  if (!(x.m >= kFpfMinMagnitude && x.m <= kFpfMaxMagnitude) || x.d > kFpfMaxDepth) return Sign::Zero;
  const double bound = double(x.d) * (0x1p-52 + 0x1p-82) * x.m;  // c_d m; c_d is exact
  if (x.v > bound) return Sign::Positive;
  if (x.v < -bound) return Sign::Negative;
  return Sign::Zero;  // undecided
}

template <class NT>
struct V3 {
  NT x, y, z;
};

// a - b evaluated in NT (exact for Mpzf, an enclosing interval for IA).
template <class NT>
inline V3<NT> sub(const Vec3& a, const Vec3& b) {
  return {NT(a.x) - NT(b.x), NT(a.y) - NT(b.y), NT(a.z) - NT(b.z)};
}
template <class NT>
inline NT dot(const V3<NT>& a, const V3<NT>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class NT>
inline V3<NT> cross(const V3<NT>& a, const V3<NT>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class NT>
inline NT det3(const V3<NT>& a, const V3<NT>& b, const V3<NT>& c) {
  return dot(a, cross(b, c));
}

// Sign of sum_m coef_m * delta_{id_m} with delta_0 >> delta_1 >> ...: the sign of the summed
// coefficient of the lowest id whose coefficient is nonzero (equal ids are merged first).
template <std::size_t N>
Sign perturbed_sign(std::array<std::pair<int, EX>, N> terms) {
  std::sort(terms.begin(), terms.end(),
            [](const std::pair<int, EX>& a, const std::pair<int, EX>& b) { return a.first < b.first; });
  for (std::size_t a = 0; a < N;) {
    EX sum = terms[a].second;
    std::size_t b = a + 1;
    for (; b < N && terms[b].first == terms[a].first; ++b) sum = sum + terms[b].second;
    if (Sign s = exact_sign(sum); s != Sign::Zero) return s;
    a = b;
  }
  return Sign::Zero;
}

// ---------------------------------------------------------------------------------------------
// side1: f_il(q) = |q - p_i|^2 - |q - p_l|^2 - w_i + w_l. Perturbed: f - delta_i + delta_l.

template <class NT>
NT side1_f(const Site& i, const Site& l, const Vec3& q) {
  const V3<NT> u = sub<NT>(q, i.p), v = sub<NT>(q, l.p);
  return (dot(u, u) - dot(v, v)) - (NT(i.w) - NT(l.w));
}

// side2: with a_m = p_m - p_i, u_r = q_r - p_i, e = q1 - q2:
//   F_r = f_ij(q_r) = 2 u_r.a_j - |a_j|^2 - w_i + w_j,  G_r = f_il(q_r) (same with l),
//   f_il(q) (F1 - F2) = N = F1 G2 - G1 F2,  F1 - F2 = 2 e.a_j.
template <class NT>
void side2_num_den(const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2,
                   NT& num, NT& den) {
  const V3<NT> aj = sub<NT>(j.p, i.p), al = sub<NT>(l.p, i.p);
  const V3<NT> u1 = sub<NT>(q1, i.p), u2 = sub<NT>(q2, i.p), e = sub<NT>(q1, q2);
  const NT two(2);
  const NT cj = NT(j.w) - NT(i.w) - dot(aj, aj);
  const NT cl = NT(l.w) - NT(i.w) - dot(al, al);
  const NT F1 = two * dot(u1, aj) + cj, F2 = two * dot(u2, aj) + cj;
  const NT G1 = two * dot(u1, al) + cl, G2 = two * dot(u2, al) + cl;
  num = F1 * G2 - G1 * F2;
  den = two * dot(e, aj);
}

// side3: with a_m = p_m - p_i, u = p1 - p_i, n = (p2 - p1) x (p3 - p1):
//   h_m = f_im(p1) = 2 u.a_m - |a_m|^2 - w_i + w_m,
//   C_j = det(n, a_k, a_l), C_k = -det(n, a_j, a_l), C_l = det(n, a_j, a_k) = det M,
//   f_il(q) det M = D = h_j C_j + h_k C_k + h_l C_l   (= det [[n, 0], [a_m, h_m]]_{m=j,k,l}).
template <class NT>
struct Side3Terms {
  NT D, Cj, Ck, Cl;
};

template <class NT>
Side3Terms<NT> side3_terms(const Site& i, const Site& j, const Site& k, const Site& l,
                           const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  const V3<NT> n = cross(sub<NT>(p2, p1), sub<NT>(p3, p1));
  const V3<NT> aj = sub<NT>(j.p, i.p), ak = sub<NT>(k.p, i.p), al = sub<NT>(l.p, i.p);
  const V3<NT> u = sub<NT>(p1, i.p);
  const NT two(2), wi(i.w);
  const NT hj = two * dot(u, aj) - dot(aj, aj) + (NT(j.w) - wi);
  const NT hk = two * dot(u, ak) - dot(ak, ak) + (NT(k.w) - wi);
  const NT hl = two * dot(u, al) - dot(al, al) + (NT(l.w) - wi);
  Side3Terms<NT> t;
  t.Cj = det3(n, ak, al);
  t.Ck = -det3(n, aj, al);
  t.Cl = det3(n, aj, ak);
  t.D = hj * t.Cj + hk * t.Ck + hl * t.Cl;
  return t;
}

// The double filter of each predicate: its answer when the filter proves the signs, else Zero.
// Flattened so that the depths d fold into constants and no Fpf goes through memory.
[[gnu::flatten]] Sign side1_fpf(const Site& i, const Site& l, const Vec3& q) {
  return -certain_sign(side1_f<Fpf>(i, l, q));
}
// side2's filter takes a cheaper form of the same signs: with G2 = G1 - 2 e.a_l and
// F2 = F1 - 2 e.a_j, N = 2 (G1 e.a_j - F1 e.a_l) and F1 - F2 = 2 e.a_j; and
// F1 = a_j.((q1 - p_i) + (q1 - p_j)) + w_j - w_i (2 u1.a_j - |a_j|^2 = a_j.(2 u1 - a_j)), G1 alike.
// 14 products instead of 28.
[[gnu::flatten]] Sign side2_fpf(const Site& i, const Site& j, const Site& l, const Vec3& q1,
                                const Vec3& q2) {
  const V3<Fpf> aj = sub<Fpf>(j.p, i.p), al = sub<Fpf>(l.p, i.p), e = sub<Fpf>(q1, q2);
  const V3<Fpf> u1 = sub<Fpf>(q1, i.p), vj = sub<Fpf>(q1, j.p), vl = sub<Fpf>(q1, l.p);
  const V3<Fpf> sj{u1.x + vj.x, u1.y + vj.y, u1.z + vj.z}, sl{u1.x + vl.x, u1.y + vl.y, u1.z + vl.z};
  const Fpf F1 = dot(aj, sj) + (Fpf(j.w) - Fpf(i.w)), G1 = dot(al, sl) + (Fpf(l.w) - Fpf(i.w));
  const Fpf ea = dot(e, aj), el = dot(e, al);
  const Fpf half_num = G1 * ea - F1 * el;
  return -(certain_sign(half_num) * certain_sign(ea));
}
[[gnu::flatten]] bool cross_certainly_nonzero_fpf(const Vec3& a, const Vec3& b, const Vec3& c) {
  const V3<Fpf> n = cross(sub<Fpf>(b, a), sub<Fpf>(c, a));
  return certain_sign(n.x) != Sign::Zero || certain_sign(n.y) != Sign::Zero || certain_sign(n.z) != Sign::Zero;
}
[[gnu::flatten]] Sign side3_fpf(const Site& i, const Site& j, const Site& k, const Site& l,
                                const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  const Side3Terms<Fpf> t = side3_terms<Fpf>(i, j, k, l, p1, p2, p3);
  return -(certain_sign(t.D) * certain_sign(t.Cl));
}

}  // namespace

// -------------------------------------------------------------------------------------------------

PredicateStats predicate_stats() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::uint64_t sum[kKinds][kFields];
  for (int k = 0; k < kKinds; ++k)
    for (int f = 0; f < kFields; ++f) {
      sum[k][f] = r.retired[k][f];
      for (ThreadCounters* c : r.live) sum[k][f] += c->value[k][f].load(std::memory_order_relaxed);
    }
  PredicateStats s;
  s.side1 = to_counters(sum[kSide1]);
  s.side2 = to_counters(sum[kSide2]);
  s.side3 = to_counters(sum[kSide3]);
  s.other = to_counters(sum[kOther]);
  s.total = s.side1;
  s.total += s.side2;
  s.total += s.side3;
  s.total += s.other;
  return s;
}

std::uint64_t thread_perturbations() {
  const ThreadCounters& c = local_counters();
  std::uint64_t sum = 0;
  for (int k = 0; k < kKinds; ++k) sum += c.value[k][kPerturbations].load(std::memory_order_relaxed);
  return sum;
}

void reset_predicate_stats() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (int k = 0; k < kKinds; ++k)
    for (int f = 0; f < kFields; ++f) {
      r.retired[k][f] = 0;
      for (ThreadCounters* c : r.live) c->value[k][f].store(0, std::memory_order_relaxed);
    }
}

namespace predicates {

bool ball_clear_of_bisector_weighted(const Site& i, const Site& l, double reach2) {
  if (!(reach2 >= 0) || !std::isfinite(reach2)) return false;
  CGAL::Protect_FPU_rounding<true> rounding;
  const IA dx = IA(l.p.x) - IA(i.p.x), dy = IA(l.p.y) - IA(i.p.y), dz = IA(l.p.z) - IA(i.p.z);
  const IA d2 = CGAL::square(dx) + CGAL::square(dy) + CGAL::square(dz);
  const IA margin = d2 + (IA(i.w) - IA(l.w));  // D^2 + w_i - w_l, which must exceed 2 D r >= 0
  if (!(margin.inf() > 0)) return false;
  return (CGAL::square(margin) - IA(4) * d2 * IA(reach2)).inf() > 0;
}

bool in_filter_range(const Vec3& v) { return in_range(v); }
bool in_filter_range(const Site& s) { return in_range(s); }

namespace {

// sign(-f_il(q)) of the unperturbed weights, Zero on an exact tie; counted as one side1 call.
[[gnu::always_inline]] inline Sign side1_unperturbed_counted(ThreadCounters& c, const Site& i, const Site& l, const Vec3& q, bool inputs_in_range) {
  bump(c, kSide1, kCalls);
  if (inputs_in_range || (in_range(i) && in_range(l) && in_range(q))) {
    if (Sign s = side1_fpf(i, l, q); s != Sign::Zero) return s;
    Sign s;
    {
      CGAL::Protect_FPU_rounding<true> rounding;
      s = certain_sign(side1_f<IA>(i, l, q));
    }
    if (s != Sign::Zero) return -s;
    bump(c, kSide1, kFilterFailures);
  }
  bump(c, kSide1, kExact);
  return -exact_sign(side1_f<EX>(i, l, q));
}

}  // namespace

Sign side1(const Site& i, const Site& l, const Vec3& q, bool inputs_in_range) {
  ThreadCounters& c = local_counters();
  if (Sign s = side1_unperturbed_counted(c, i, l, q, inputs_in_range); s != Sign::Zero) return s;
  // f' = f - delta_i + delta_l: the lower id is the closer site.
  bump(c, kSide1, kPerturbations);
  if (i.id == l.id) return Sign::Zero;
  return i.id < l.id ? Sign::Positive : Sign::Negative;
}

Sign side1_unperturbed(const Site& i, const Site& l, const Vec3& q, bool inputs_in_range) {
  return side1_unperturbed_counted(local_counters(), i, l, q, inputs_in_range);
}

void add_calls(CallTally& tally) {
  ThreadCounters& c = local_counters();
  std::atomic<std::uint64_t>& s1 = c.value[kSide1][kCalls];
  std::atomic<std::uint64_t>& s2 = c.value[kSide2][kCalls];
  s1.store(s1.load(std::memory_order_relaxed) + tally.side1, std::memory_order_relaxed);
  s2.store(s2.load(std::memory_order_relaxed) + tally.side2, std::memory_order_relaxed);
  tally = CallTally{};
}

Sign side1(const Site& i, const Site& l, const Vec3& q, const BoundedPowerDistance& di,
           const BoundedPowerDistance& dl, CallTally* tally) {
  // |r - (d_l - d_i)| <= e_i + e_l + u |d~_l - d~_i| <= e_i + e_l + u |r| / (1 - u): a margin of
  // 2^-40 on the rounded sum of the bounds covers the last term and the sum's own rounding.
  const double r = dl.value - di.value;
  if (std::fabs(r) > (di.error + dl.error) * (1 + 0x1p-40)) {
    if (tally) ++tally->side1;
    else bump(local_counters(), kSide1, kCalls);
    return r > 0 ? Sign::Positive : Sign::Negative;
  }
  return side1(i, l, q, true);
}

Sign side2(const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2,
           const BoundedPowerDistance& i1, const BoundedPowerDistance& j1, const BoundedPowerDistance& l1,
           const BoundedPowerDistance& i2, const BoundedPowerDistance& j2, const BoundedPowerDistance& l2,
           CallTally* tally) {
  // Each value with a bound on its distance to the exact one (docs/algorithms/predicates.md, "Shared power
  // distances"): a difference adds 2u of its rounded value, a product |a| e_b + (|b| + e_b) e_a
  // and 2u of itself; 2^-1000 covers every underflow. The bounds themselves are rounded: the
  // 2^-40 margin of the final tests covers that.
  constexpr double u2 = 0x1p-51;  // 2u, u = 2^-52
  const double F1 = i1.value - j1.value, F2 = i2.value - j2.value;
  const double G1 = i1.value - l1.value, G2 = i2.value - l2.value;
  const double eF1 = i1.error + j1.error + u2 * std::fabs(F1), eF2 = i2.error + j2.error + u2 * std::fabs(F2);
  const double eG1 = i1.error + l1.error + u2 * std::fabs(G1), eG2 = i2.error + l2.error + u2 * std::fabs(G2);
  const double den = F1 - F2;
  const double eden = eF1 + eF2 + u2 * std::fabs(den);
  const double P = F1 * G2, Q = G1 * F2, N = P - Q;
  const double eN = std::fabs(F1) * eG2 + (std::fabs(G2) + eG2) * eF1 + std::fabs(G1) * eF2 +
                    (std::fabs(F2) + eF2) * eG1 + u2 * (std::fabs(P) + std::fabs(Q) + std::fabs(N)) + 0x1p-1000;
  constexpr double margin = 1 + 0x1p-40;
  if (std::fabs(N) > eN * margin && std::fabs(den) > eden * margin) {
    if (tally) ++tally->side2;
    else bump(local_counters(), kSide2, kCalls);
    // side2 is sign(-f_il(q)), f_il(q) (F1 - F2) = N.
    return (N > 0) == (den > 0) ? Sign::Negative : Sign::Positive;
  }
  return side2(i, j, l, q1, q2, true);
}

namespace {

// side2's filters: the sign when they decide it, else Zero (then counted as going exact).
[[gnu::always_inline]] inline Sign side2_filtered(ThreadCounters& c, const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2,
                    bool inputs_in_range) {
  bump(c, kSide2, kCalls);
  if (inputs_in_range || (in_range(i) && in_range(j) && in_range(l) && in_range(q1) && in_range(q2))) {
    if (Sign s = side2_fpf(i, j, l, q1, q2); s != Sign::Zero) return s;
    Sign s;
    {
      CGAL::Protect_FPU_rounding<true> rounding;
      IA num, den;
      side2_num_den<IA>(i, j, l, q1, q2, num, den);
      s = certain_sign(num) * certain_sign(den);
    }
    if (s != Sign::Zero) return -s;
    bump(c, kSide2, kFilterFailures);
  }
  bump(c, kSide2, kExact);
  return Sign::Zero;
}

}  // namespace

Sign side2(const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2,
           bool inputs_in_range) {
  ThreadCounters& c = local_counters();
  if (Sign s = side2_filtered(c, i, j, l, q1, q2, inputs_in_range); s != Sign::Zero) return s;
  EX num, den;
  side2_num_den<EX>(i, j, l, q1, q2, num, den);
  const Sign sden = exact_sign(den);
  if (sden == Sign::Zero) return Sign::Zero;  // precondition violated: no vertex
  if (Sign s = exact_sign(num); s != Sign::Zero) return -(s * sden);
  // N' = N + (-delta_i + delta_j)(G2 - G1) + (-delta_i + delta_l)(F1 - F2), with
  // G2 - G1 = -2 e.a_l and G1 - G2 - F1 + F2 = 2 e.(p_l - p_j).
  bump(c, kSide2, kPerturbations);
  const V3<EX> e = sub<EX>(q1, q2);
  const EX two(2);
  const Sign s = perturbed_sign(std::array<std::pair<int, EX>, 3>{
      std::pair<int, EX>{i.id, two * dot(e, sub<EX>(l.p, j.p))},
      std::pair<int, EX>{j.id, -(two * dot(e, sub<EX>(l.p, i.p)))},
      std::pair<int, EX>{l.id, den}});
  return -(s * sden);
}

Sign side2_unperturbed(const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2,
                       bool inputs_in_range) {
  ThreadCounters& c = local_counters();
  if (Sign s = side2_filtered(c, i, j, l, q1, q2, inputs_in_range); s != Sign::Zero) return s;
  EX num, den;
  side2_num_den<EX>(i, j, l, q1, q2, num, den);
  return -(exact_sign(num) * exact_sign(den));
}

Sign side3(const Site& i, const Site& j, const Site& k, const Site& l,
           const Vec3& p1, const Vec3& p2, const Vec3& p3, bool inputs_in_range) {
  ThreadCounters& c = local_counters();
  bump(c, kSide3, kCalls);
  if (inputs_in_range || (in_range(i) && in_range(j) && in_range(k) && in_range(l) && in_range(p1) &&
                          in_range(p2) && in_range(p3))) {
    if (Sign s = side3_fpf(i, j, k, l, p1, p2, p3); s != Sign::Zero) return s;
    Sign s;
    {
      CGAL::Protect_FPU_rounding<true> rounding;
      const Side3Terms<IA> t = side3_terms<IA>(i, j, k, l, p1, p2, p3);
      s = certain_sign(t.D) * certain_sign(t.Cl);
    }
    if (s != Sign::Zero) return -s;
    bump(c, kSide3, kFilterFailures);
  }
  bump(c, kSide3, kExact);
  const Side3Terms<EX> t = side3_terms<EX>(i, j, k, l, p1, p2, p3);
  const Sign sdet = exact_sign(t.Cl);
  if (sdet == Sign::Zero) return Sign::Zero;  // precondition violated: no vertex
  if (Sign s = exact_sign(t.D); s != Sign::Zero) return -(s * sdet);
  // D' = D + sum_{m=j,k,l} (-delta_i + delta_m) C_m.
  bump(c, kSide3, kPerturbations);
  const Sign s = perturbed_sign(std::array<std::pair<int, EX>, 4>{
      std::pair<int, EX>{i.id, -(t.Cj + t.Ck + t.Cl)}, std::pair<int, EX>{j.id, t.Cj},
      std::pair<int, EX>{k.id, t.Ck}, std::pair<int, EX>{l.id, t.Cl}});
  return -(s * sdet);
}

// ---------------------------------------------------------------------------------------------
// Unperturbed helpers. Range bounds keep their (degree 2 or 3) intermediates finite.

bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  ThreadCounters& cnt = local_counters();
  bump(cnt, kOther, kCalls);
  // The double filter first: every triangle of a refined mesh is checked, almost none is flat.
  if (in_range(a) && in_range(b) && in_range(c) && cross_certainly_nonzero_fpf(a, b, c)) return false;
  if (in_range(a, 0x1p400) && in_range(b, 0x1p400) && in_range(c, 0x1p400)) {
    bool nonzero;
    {
      CGAL::Protect_FPU_rounding<true> rounding;
      const V3<IA> n = cross(sub<IA>(b, a), sub<IA>(c, a));
      nonzero = certain_sign(n.x) != Sign::Zero || certain_sign(n.y) != Sign::Zero ||
                certain_sign(n.z) != Sign::Zero;
    }
    if (nonzero) return false;
    bump(cnt, kOther, kFilterFailures);
  }
  bump(cnt, kOther, kExact);
  const V3<EX> n = cross(sub<EX>(b, a), sub<EX>(c, a));
  return n.x.is_zero() && n.y.is_zero() && n.z.is_zero();
}

Sign orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  ThreadCounters& cnt = local_counters();
  bump(cnt, kOther, kCalls);
  if (in_range(a, 0x1p250) && in_range(b, 0x1p250) && in_range(c, 0x1p250) && in_range(d, 0x1p250)) {
    Sign s;
    {
      CGAL::Protect_FPU_rounding<true> rounding;
      s = certain_sign(det3(sub<IA>(b, a), sub<IA>(c, a), sub<IA>(d, a)));
    }
    if (s != Sign::Zero) return s;
    bump(cnt, kOther, kFilterFailures);
  }
  bump(cnt, kOther, kExact);
  return exact_sign(det3(sub<EX>(b, a), sub<EX>(c, a), sub<EX>(d, a)));
}

namespace {
template <class NT>
NT orient2d_value(const Vec3& a, const Vec3& b, const Vec3& c, int drop) {
  const int x = (drop + 1) % 3, y = (drop + 2) % 3;
  return (NT(b[x]) - NT(a[x])) * (NT(c[y]) - NT(a[y])) - (NT(b[y]) - NT(a[y])) * (NT(c[x]) - NT(a[x]));
}
}  // namespace

Sign orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int drop) {
  ThreadCounters& cnt = local_counters();
  bump(cnt, kOther, kCalls);
  if (in_range(a, 0x1p400) && in_range(b, 0x1p400) && in_range(c, 0x1p400)) {
    Sign s;
    {
      CGAL::Protect_FPU_rounding<true> rounding;
      s = certain_sign(orient2d_value<IA>(a, b, c, drop));
    }
    if (s != Sign::Zero) return s;
    bump(cnt, kOther, kFilterFailures);
  }
  bump(cnt, kOther, kExact);
  return exact_sign(orient2d_value<EX>(a, b, c, drop));
}

int projection_axis(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = lrvd::cross(b - a, c - a);
  double key[3];
  for (int axis = 0; axis < 3; ++axis) {
    key[axis] = std::fabs(n[axis]);
    if (std::isnan(key[axis])) key[axis] = 0;  // overflowed: no preference
  }
  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int p, int q) { return key[p] > key[q]; });
  for (int axis : order)
    if (orient2d(a, b, c, axis) != Sign::Zero) return axis;
  return -1;
}

}  // namespace predicates
}  // namespace lrvd
