// Filtered exact predicates that classify restricted power/Voronoi vertices against a bisector
// (paper §3.6), with one symbolic perturbation of the weights for every predicate.
// Formulas, degrees and the perturbation rule: docs/algorithms/predicates.md.
#pragma once

#include <cstdint>

#include "predicates/vec3.h"

namespace lrvd {

//! Sign of an exact quantity. Values are those of CGAL::Sign, so casts between them are safe.
enum class Sign : int { Negative = -1, Zero = 0, Positive = 1 };

inline Sign operator-(Sign s) { return static_cast<Sign>(-static_cast<int>(s)); }
inline Sign operator*(Sign a, Sign b) { return static_cast<Sign>(static_cast<int>(a) * static_cast<int>(b)); }

//! A sample of the diagram: position, power weight (0 for Voronoi) and sample index. The power
//! distance is d(q) = |q - p|^2 - w. `id` orders the symbolic perturbation: on an exact tie the
//! site with the lower id is the closer one.
struct Site {
  Vec3 p;
  double w = 0;
  int id = -1;
};

//! How often one kind of predicate ran and how it was decided.
struct PredicateCounters {
  std::uint64_t calls = 0;            //!< predicate evaluations
  std::uint64_t filter_failures = 0;  //!< interval filter could not decide (inputs out of its range count in `exact` only)
  std::uint64_t exact = 0;            //!< evaluations that reached exact (Mpzf) arithmetic
  std::uint64_t perturbations = 0;    //!< exact zeros resolved by the symbolic perturbation

  PredicateCounters& operator+=(const PredicateCounters& o) {
    calls += o.calls;
    filter_failures += o.filter_failures;
    exact += o.exact;
    perturbations += o.perturbations;
    return *this;
  }
};

//! Counters per predicate kind and their sum, over all threads since the last reset.
struct PredicateStats {
  PredicateCounters side1, side2, side3, other;  //!< other: collinear / orientation helpers
  PredicateCounters total;
};

//! Sum of the counters of every thread (live and finished) since the last reset.
PredicateStats predicate_stats();
//! Zeroes all counters. Exact when no other thread runs predicates meanwhile.
void reset_predicate_stats();
//! The exact ties the calling thread's predicates have resolved by the perturbation so far. A
//! computation after which it differs has met a degenerate configuration (a tie can leave a
//! perturbed side of zero length in the limit). reset_predicate_stats() between the two reads
//! spoils the comparison: reset between computations only.
std::uint64_t thread_perturbations();

namespace predicates {

// Conventions: f_ab(q) = d_a(q) - d_b(q) (negative when q is closer to a). Every side predicate
// returns sign(-f_il(q)) for the perturbed weights w' = w + delta_id, delta_0 >> delta_1 >> ... > 0:
// Positive when q is strictly closer to i, Negative when strictly closer to l. It returns Zero
// only if i.id == l.id, or if l repeats a site that defines q (then q lies on bisector(i,l)).
// Inputs: finite doubles of any magnitude. Each call checks that its inputs lie in the range of
// the filters (in_filter_range) and goes straight to the exact path when one does not; a caller
// that has checked every input once (a whole mesh and its sites) passes `inputs_in_range` = true
// and saves the check on every call. The answer is the same either way.

//! Whether a point or a site is in the range where the filters cannot overflow (coordinates up to
//! 2^100, weights up to 2^200 in magnitude): false for inf and NaN too.
bool in_filter_range(const Vec3& v);
bool in_filter_range(const Site& s);

//! Type (a): q is a mesh vertex. Degree 2.
Sign side1(const Site& i, const Site& l, const Vec3& q, bool inputs_in_range = false);

//! q's power distance to a site in doubles, with a bound on its rounding error: what side1 needs of
//! each side, computed once where one point is tested against several sites (a triangle's corners
//! against its candidate cells). Derivation: docs/algorithms/predicates.md, "Shared power distances".
struct BoundedPowerDistance {
  double value = 0;  //!< fl(|q - p|^2 - w), each coordinate difference, square and sum rounded
  double error = 0;  //!< >= |value - (|q - p|^2 - w)|
};

//! \pre `s` and `q` are in the filter range (in_filter_range).
inline BoundedPowerDistance bounded_power_distance(const Site& s, const Vec3& q) {
  const double dx = q.x - s.p.x, dy = q.y - s.p.y, dz = q.z - s.p.z;
  const double squared = dx * dx + dy * dy + dz * dz;
  // 8u·squared + 2u·|w| + 2^-1000 >= (γ5 / (1 - γ5) + u)·squared + u·|w| + 2^-1071 even after its
  // own two roundings, with u = 2^-52: any rounding mode, as the double filter's bound.
  return {squared - s.w, 0x1p-49 * squared + (0x1p-51 * (s.w < 0 ? -s.w : s.w) + 0x1p-1000)};
}

//! Whether every point y with |y - x_i|^2 <= reach2 is strictly closer (power distance) to site i
//! than to site l: a certified test, false whenever it cannot tell (never true for one site twice).
//! For such y, d_l(y) - d_i(y) = D^2 - 2 (y - x_i).(x_l - x_i) + w_i - w_l >= D^2 - 2 D r + w_i - w_l
//! with D = |x_l - x_i| and r = sqrt(reach2), which is positive when 2 D r < D^2 + w_i - w_l; with
//! equal weights, when 4 reach2 < D^2. The clipper skips, by it, bisectors far from a polygon.
//! \pre i and l are in the filter range (in_filter_range).
bool ball_clear_of_bisector_weighted(const Site& i, const Site& l, double reach2);
inline bool ball_clear_of_bisector(const Site& i, const Site& l, double reach2) {
  if (i.w != l.w) return ball_clear_of_bisector_weighted(i, l, reach2);
  // D^2 from below: bounded_power_distance's value less twice its error bound (once for the bound,
  // once more for this subtraction's and the product's roundings). 4 reach2 is exact or infinite.
  const BoundedPowerDistance d = bounded_power_distance(Site{l.p, 0, -1}, i.p);
  return d.value - 2 * d.error > 4 * reach2;
}

//! Calls of the two overloads below that doubles decided, counted by their caller: one that makes
//! many calls in a row (the clipper, per triangle) passes a tally and adds it to the thread's
//! counters once (add_calls), instead of each call looking up the thread's counters -- a
//! thread-local look-up, which in a module loaded at run time (the Python module) is a call to
//! __tls_get_addr (3 % of a remesh's instructions there).
struct CallTally {
  std::uint64_t side1 = 0, side2 = 0;
};
//! Adds the tally to the calling thread's counters and zeroes it.
void add_calls(CallTally& tally);

//! side1(i, l, q, true) from q's bounded power distances to i and to l: the same answer, decided in
//! doubles when the distances differ by more than their error bounds, else by side1 itself (and
//! counted as one side1 call either way: in `tally` when given and doubles decided).
//! \pre i, l and q are in the filter range; di and dl are bounded_power_distance(i, q) and (l, q).
Sign side1(const Site& i, const Site& l, const Vec3& q, const BoundedPowerDistance& di,
           const BoundedPowerDistance& dl, CallTally* tally = nullptr);

//! side2(i, j, l, q1, q2, true) from the bounded power distances of q1 and q2 to i, j and l (the
//! corners of a triangle's edge): the same answer, decided in doubles when the signs of
//! F1·G2 − G1·F2 and F1 − F2 (F_r = d_i(q_r) − d_j(q_r), G_r = d_i(q_r) − d_l(q_r)) exceed their
//! error bounds, else by side2 itself (and counted as one side2 call either way: in `tally` when
//! given and doubles decided).
//! \pre i, j, l, q1 and q2 are in the filter range; i1 = bounded_power_distance(i, q1), and so on.
Sign side2(const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2,
           const BoundedPowerDistance& i1, const BoundedPowerDistance& j1, const BoundedPowerDistance& l1,
           const BoundedPowerDistance& i2, const BoundedPowerDistance& j2, const BoundedPowerDistance& l2,
           CallTally* tally = nullptr);

//! Type (b): q is the point of line (q1,q2) on bisector(i,j).
//! \pre (q1 - q2).(p_j - p_i) != 0 (the vertex exists); otherwise returns Zero.
//! Degree 4 (numerator) times degree 2 (weight-free denominator).
Sign side2(const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2,
           bool inputs_in_range = false);

//! side1 and side2 of the unperturbed weights: Zero on an exact tie (q on bisector(i, l)), which
//! the perturbation would have resolved. Counted as side1 and side2 calls, never as perturbations.
Sign side1_unperturbed(const Site& i, const Site& l, const Vec3& q, bool inputs_in_range = false);
Sign side2_unperturbed(const Site& i, const Site& j, const Site& l, const Vec3& q1, const Vec3& q2,
                       bool inputs_in_range = false);

//! Type (c): q = plane(p1,p2,p3) ∩ bisector(i,j) ∩ bisector(i,k).
//! \pre n, p_j - p_i, p_k - p_i are linearly independent, n = (p2-p1)x(p3-p1) (the vertex
//!      exists); otherwise returns Zero. Degree 6 times degree 4 (weight-free det M).
Sign side3(const Site& i, const Site& j, const Site& k, const Site& l,
           const Vec3& p1, const Vec3& p2, const Vec3& p3, bool inputs_in_range = false);

//! Exact: (b - a) x (c - a) == 0 (includes coincident points). No perturbation.
bool collinear(const Vec3& a, const Vec3& b, const Vec3& c);

//! Exact sign of det(b - a, c - a, d - a): Positive when d is above the plane (a,b,c) oriented
//! counterclockwise. No perturbation.
Sign orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

//! Exact orientation of a, b, c projected on the coordinate plane that drops axis `drop` (0,1,2),
//! with axes (drop+1)%3, (drop+2)%3 as (x, y): Positive for a counterclockwise turn.
//! No perturbation.
Sign orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int drop);

//! The triangle's own 2D frame: an axis to drop such that orient2d(a, b, c, axis) != Zero
//! (the largest normal component when the double normal shows it, checked exactly), or -1 when
//! a, b, c are exactly collinear.
int projection_axis(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace predicates
}  // namespace lrvd
