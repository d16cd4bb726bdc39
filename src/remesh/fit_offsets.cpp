// Vertex offsets balancing the sampled two-sided distance: the steps and their rounds (see fit_offsets.h).
#include "remesh/fit_offsets.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "metrics/quality.h"
#include "remesh/fit_offsets_samples.h"

namespace lrvd {

namespace fit_detail {

namespace {

// x^p for an integer p ≥ 1, by squaring.
double power(double x, int p) {
  double result = 1;
  for (; p > 0; p >>= 1, x *= x)
    if (p & 1) result *= x;
  return result;
}

// The same for a p known when compiling (the default p = 16 of the hot loops): the same products
// in the same order, so the same value, unrolled (the compiler keeps the loop otherwise).
template <int P>
double power_by_squaring(double result, double x) {
  if constexpr (P == 0) {
    return result;
  } else {
    if constexpr ((P & 1) != 0) result *= x;
    return power_by_squaring<(P >> 1)>(result, x * x);
  }
}
template <int P>
double power(double x) {
  return power_by_squaring<P>(1.0, x);
}

// The steps of balance_offsets on the samples' linearised distances: coordinate descent over the
// vertices, one at a time (sweep) or, in the focus rounds, with their one-ring (group_sweep).
class OffsetBalancer : public OffsetSamples {
 public:
  OffsetBalancer(const SurfaceMesh& mesh, DualMesh& dual, const std::vector<std::vector<int>>& incident,
                 const std::function<bool(int)>& acceptable, const OffsetOptions& options,
                 const ClosestPointIndex* mesh_index, const std::vector<int>* input_vertex_cell)
      : OffsetSamples(mesh, dual, options, mesh_index, input_vertex_cell), incident_(incident), acceptable_(acceptable) {}

  // The unit normal of vertex v (its triangles' area-weighted normals) and the shortest edge of
  // its triangles; false when either is degenerate.
  bool vertex_frame(int v, Vec3& normal, double& shortest) const;

  // One sweep of coordinate descent on the linearised distances: each vertex tries a few directions
  // (its normal; the steepest descent of its samples' Σ|d|^p, which leaves the normal at a tip the
  // vertex must reach sideways; that descent's tangential part) and keeps the best accepted step.
  void sweep(double floor);

  // Coordinate descent on groups, for the focus rounds: each vertex whose samples reach `floor`,
  // largest |d| first, moves alone (ring_share = 0) or with its one-ring, the ring by `ring_share` of
  // the vertex's step (1: the triangles at the vertex keep their shape and the ring's outer
  // triangles deform instead; where the vertex alone is stopped by a triangle at the floor, the
  // group can still move). A step is taken under `relaxed` (the worst-Q floor) when that beats the
  // best step under `strict` (the rounds' floor) and the Q it takes from the group's triangles fits
  // in what is left of the budget; otherwise under `strict`.
  void group_sweep(double floor, const std::function<bool(int)>& strict, const std::function<bool(int)>& relaxed,
                   double ring_share);

  void set_quality_budget(double budget) { quality_budget_ = budget; }

 private:
  // The vertex's samples, gathered: d / scale, weight and direction.
  inline void gather(int v, double scale);
  inline void set_coefficients(const Vec3& direction, double scale);
  // Σ |d + c t|^p / scale^p over the gathered samples (c = 0 when t = 0).
  inline double objective(double t) const;
  template <int P>  // P = options_.power, or 0 when that is not one compiled for
  inline double objective_with(double t) const;
  // The offset t in [-limit, limit] that minimises Σ |d + c t|^p over the gathered samples: the
  // function is convex, so Newton's method on its derivative inside a shrinking bracket.
  inline double best_offset(double limit) const;
  template <int P>  // as in objective_with
  inline double best_offset_with(double limit) const;

  // The largest |d| of the samples of vertex v.
  inline double largest_distance(int v) const;

  // group_sweep's steps. The group (group_, its vertex first; group_from_, where they start) moves
  // together, the ring by ring_share of the vertex's step.
  struct GroupSteps {
    double start = 0;                  // the objective before any step
    double strict_value = 0, relaxed_value = 0;
    Vec3 strict_move{0, 0, 0}, relaxed_move{0, 0, 0};  // the best step under each floor (0: none better)
  };
  // The vertices whose samples' largest |d| reaches `floor`, largest first, as (-|d|, vertex).
  std::vector<std::pair<double, int>> vertices_by_distance(double floor) const;
  // The vertex v, and with a ring_share its one-ring, as the group.
  void collect_group(int v, double ring_share);
  // The group's samples gathered (combined_ and touched_: each with the weight of its moving
  // corners, the ring's scaled by its share), and the steepest descent of their Σ|d|^p; returns
  // their largest |d|, the scale of the gathered values.
  double gather_group(double ring_share, Vec3& descent);
  void place_group(const Vec3& move, double ring_share);
  bool group_holds(const std::function<bool(int)>& accept) const;
  // The best accepted steps along the normal, the descent and its tangential part.
  GroupSteps best_group_steps(const Vec3& normal, const Vec3& descent, double limit, double group_scale,
                              const std::function<bool(int)>& strict, const std::function<bool(int)>& relaxed,
                              double ring_share);
  // The Q the group's `move` takes from the triangles around the group, summed.
  double quality_spent(const Vec3& move, double ring_share);

  const std::vector<std::vector<int>>& incident_;
  const std::function<bool(int)>& acceptable_;
  std::vector<double> coefficient_, local_d_, local_w_;
  std::vector<Vec3> local_g_;
  double quality_budget_ = 0;  // the Q the focus rounds' relaxed steps may still take, summed over triangles
  std::vector<double> combined_;  // group_sweep: per sample, the weight of the group's moving corners
  std::vector<int> group_, touched_, around_;  // group_sweep: the group, its samples, its triangles
  std::vector<Vec3> group_from_;
};

}  // namespace

bool OffsetBalancer::vertex_frame(int v, Vec3& normal, double& shortest) const {
  normal = Vec3{0, 0, 0};
  shortest = INFINITY;
  for (int t : incident_[v]) {
    const Triangle& f = dual_.triangles[t];
    normal += cross(dual_.positions[f[1]] - dual_.positions[f[0]], dual_.positions[f[2]] - dual_.positions[f[0]]);
    for (int e = 0; e < 3; ++e) shortest = std::min(shortest, distance(dual_.positions[f[e]], dual_.positions[f[(e + 1) % 3]]));
  }
  if (!(norm(normal) > 0) || !(shortest > 0)) return false;
  normal = normal / norm(normal);
  return true;
}

void OffsetBalancer::sweep(double floor) {
  const int n = static_cast<int>(dual_.positions.size());
  for (int v = 0; v < n; ++v) {
    if (incident_[v].empty() || first_[v] == first_[v + 1]) continue;
    Vec3 normal;
    double shortest;
    if (!vertex_frame(v, normal, shortest)) continue;
    const double scale = largest_distance(v);
    if (!(scale > 0) || scale < floor) continue;
    Vec3 descent{0, 0, 0};
    for (int k = first_[v]; k < first_[v + 1]; ++k) {
      const Sample& s = sample(entries_[k].sample);
      descent -= (power(s.d / scale, options_.power - 1) * entries_[k].weight) * s.direction;
    }
    const double limit = options_.trust * shortest;
    gather(v, scale);
    const double start = objective(0);
    const Vec3 from = dual_.positions[v];
    Vec3 best_move{0, 0, 0};
    double best_value = start;
    // The normal, the steepest descent, and the descent's part along the surface (at a tip, the
    // descent leans into the surface and its own step is cut short by the floor first).
    const Vec3 unit = norm(descent) > 0 ? descent / norm(descent) : Vec3{0, 0, 0};
    const Vec3 along = unit - dot(unit, normal) * normal;
    const Vec3 candidates[3] = {normal, unit, norm(along) > 1e-3 ? along / norm(along) : Vec3{0, 0, 0}};
    for (int candidate = 0; candidate < (options_.sideways ? 3 : 1); ++candidate) {
      const Vec3& direction = candidates[candidate];
      if (!(norm(direction) > 0)) continue;
      set_coefficients(direction, scale);
      const double t = best_offset(limit);
      for (double step : {1.0, 0.875, 0.75, 0.625, 0.5, 0.375, 0.25, 0.125}) {
        dual_.positions[v] = from + (step * t) * direction;
        const bool ok = acceptable_(v);
        dual_.positions[v] = from;
        if (!ok) continue;
        const double value = objective(step * t);
        if (value < best_value) best_value = value, best_move = (step * t) * direction;
        break;
      }
    }
    if (!(best_value < start)) continue;
    dual_.positions[v] = from + best_move;
    moved_[v] = 1;
    for (int k = first_[v]; k < first_[v + 1]; ++k) {
      Sample& s = sample(entries_[k].sample);
      s.d += entries_[k].weight * dot(best_move, s.direction);
    }
  }
}

void OffsetBalancer::gather(int v, double scale) {
  local_d_.clear(), local_w_.clear(), local_g_.clear();
  for (int k = first_[v]; k < first_[v + 1]; ++k) {
    const Sample& s = sample(entries_[k].sample);
    local_d_.push_back(s.d / scale);
    local_w_.push_back(entries_[k].weight);
    local_g_.push_back(s.direction);
  }
}

void OffsetBalancer::set_coefficients(const Vec3& direction, double scale) {
  coefficient_.resize(local_d_.size());
  for (size_t k = 0; k < local_d_.size(); ++k) coefficient_[k] = local_w_[k] * dot(direction, local_g_[k]) / scale;
}

template <int P>
double OffsetBalancer::objective_with(double t) const {
  const int p = options_.power;
  double sum = 0;
  for (size_t k = 0; k < local_d_.size(); ++k) {
    const double e = local_d_[k] + (t == 0 ? 0 : coefficient_[k] * t);
    sum += P > 0 ? power<P>(e) : power(e, p);
  }
  return sum;
}

double OffsetBalancer::objective(double t) const { return options_.power == 16 ? objective_with<16>(t) : objective_with<0>(t); }

template <int P>
double OffsetBalancer::best_offset_with(double limit) const {
  const int p = options_.power;
  auto slopes = [&](double t, double& first, double& second) {
    first = second = 0;
    for (size_t k = 0; k < local_d_.size(); ++k) {
      const double c = coefficient_[k], e = local_d_[k] + c * t;
      const double e2 = P > 0 ? power<(P > 0 ? P - 2 : 0)>(e) : power(e, p - 2);
      first += e2 * e * c;
      second += (p - 1) * e2 * c * c;
    }
  };
  double f, g;
  slopes(-limit, f, g);
  if (f >= 0) return -limit;
  slopes(limit, f, g);
  if (f <= 0) return limit;
  double lo = -limit, hi = limit, t = 0;
  for (int it = 0; it < 30; ++it) {
    slopes(t, f, g);
    if (f == 0) break;
    (f > 0 ? hi : lo) = t;
    double next = g > 0 ? t - f / g : lo;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool converged = std::abs(next - t) < 1e-6 * limit;
    t = next;
    if (converged) break;
  }
  return t;
}

double OffsetBalancer::best_offset(double limit) const { return options_.power == 16 ? best_offset_with<16>(limit) : best_offset_with<0>(limit); }

double OffsetBalancer::largest_distance(int v) const {
  double scale = 0;
  for (int k = first_[v]; k < first_[v + 1]; ++k) scale = std::max(scale, std::abs(sample(entries_[k].sample).d));
  return scale;
}

std::vector<std::pair<double, int>> OffsetBalancer::vertices_by_distance(double floor) const {
  const int n = static_cast<int>(dual_.positions.size());
  std::vector<std::pair<double, int>> order;
  for (int v = 0; v < n; ++v) {
    if (incident_[v].empty() || first_[v] == first_[v + 1]) continue;
    const double scale = largest_distance(v);
    if (scale > 0 && scale >= floor) order.push_back({-scale, v});
  }
  std::sort(order.begin(), order.end());
  return order;
}

void OffsetBalancer::collect_group(int v, double ring_share) {
  group_.assign(1, v);
  if (ring_share > 0)
    for (int t : incident_[v])
      for (int u : dual_.triangles[t])
        if (std::find(group_.begin(), group_.end(), u) == group_.end()) group_.push_back(u);
  group_from_.resize(group_.size());
  for (size_t g = 0; g < group_.size(); ++g) group_from_[g] = dual_.positions[group_[g]];
}

double OffsetBalancer::gather_group(double ring_share, Vec3& descent) {
  touched_.clear();
  for (size_t g = 0; g < group_.size(); ++g)
    for (int k = first_[group_[g]]; k < first_[group_[g] + 1]; ++k) {
      const int i = entries_[k].sample;
      if (combined_[i] == 0) touched_.push_back(i);
      combined_[i] += (g == 0 ? 1.0 : ring_share) * entries_[k].weight;
    }
  double group_scale = 0;
  for (int i : touched_) group_scale = std::max(group_scale, std::abs(sample(i).d));
  local_d_.clear(), local_w_.clear(), local_g_.clear();
  descent = Vec3{0, 0, 0};
  for (int i : touched_) {
    const Sample& s = sample(i);
    local_d_.push_back(s.d / group_scale);
    local_w_.push_back(combined_[i]);
    local_g_.push_back(s.direction);
    descent -= (power(s.d / group_scale, options_.power - 1) * combined_[i]) * s.direction;
  }
  return group_scale;
}

void OffsetBalancer::place_group(const Vec3& move, double ring_share) {
  for (size_t g = 0; g < group_.size(); ++g)
    dual_.positions[group_[g]] = group_from_[g] + (g == 0 ? 1.0 : ring_share) * move;
}

bool OffsetBalancer::group_holds(const std::function<bool(int)>& accept) const {
  for (int u : group_)
    if (!accept(u)) return false;
  return true;
}

OffsetBalancer::GroupSteps OffsetBalancer::best_group_steps(const Vec3& normal, const Vec3& descent, double limit,
                                                            double group_scale, const std::function<bool(int)>& strict,
                                                            const std::function<bool(int)>& relaxed, double ring_share) {
  GroupSteps steps;
  steps.start = steps.strict_value = steps.relaxed_value = objective(0);
  const Vec3 unit = norm(descent) > 0 ? descent / norm(descent) : Vec3{0, 0, 0};
  const Vec3 along = unit - dot(unit, normal) * normal;
  const Vec3 candidates[3] = {normal, unit, norm(along) > 1e-3 ? along / norm(along) : Vec3{0, 0, 0}};
  for (const Vec3& direction : candidates) {
    if (!(norm(direction) > 0)) continue;
    set_coefficients(direction, group_scale);
    const double t = best_offset(limit);
    for (int which = 0; which < (relaxed ? 2 : 1); ++which)
      for (double step : {1.0, 0.875, 0.75, 0.625, 0.5, 0.375, 0.25, 0.125}) {
        place_group((step * t) * direction, ring_share);
        const bool ok = group_holds(which == 0 ? strict : relaxed);
        place_group({0, 0, 0}, ring_share);
        if (!ok) continue;
        const double value = objective(step * t);
        double& best = which == 0 ? steps.strict_value : steps.relaxed_value;
        if (value < best) best = value, (which == 0 ? steps.strict_move : steps.relaxed_move) = (step * t) * direction;
        break;
      }
  }
  return steps;
}

double OffsetBalancer::quality_spent(const Vec3& move, double ring_share) {
  around_.clear();
  for (int u : group_)
    for (int t : incident_[u])
      if (std::find(around_.begin(), around_.end(), t) == around_.end()) around_.push_back(t);
  auto q_sum = [&] {
    double sum = 0;
    for (int t : around_) {
      const Triangle& f = dual_.triangles[t];
      sum += triangle_quality(dual_.positions[f[0]], dual_.positions[f[1]], dual_.positions[f[2]]);
    }
    return sum;
  };
  const double before = q_sum();
  place_group(move, ring_share);
  const double spent = before - q_sum();
  place_group({0, 0, 0}, ring_share);
  return spent;
}

void OffsetBalancer::group_sweep(double floor, const std::function<bool(int)>& strict,
                                 const std::function<bool(int)>& relaxed, double ring_share) {
  combined_.assign(remesh_.size() + input_.size(), 0);
  // The vertices at the largest distances first: they spend the quality budget first.
  for (const auto& [negative_scale, v] : vertices_by_distance(floor)) {
    collect_group(v, ring_share);
    Vec3 normal;
    double shortest;
    if (!vertex_frame(v, normal, shortest)) continue;
    Vec3 descent;
    const double group_scale = gather_group(ring_share, descent);
    const GroupSteps steps =
        best_group_steps(normal, descent, options_.trust * shortest, group_scale, strict, relaxed, ring_share);
    // The Q the relaxed step takes from the triangles around the group, against the budget.
    const double spent = steps.relaxed_value < steps.strict_value ? quality_spent(steps.relaxed_move, ring_share) : 0;
    Vec3 move{0, 0, 0};
    if (steps.relaxed_value < steps.strict_value && spent <= quality_budget_) {
      move = steps.relaxed_move;
      quality_budget_ -= std::max(0.0, spent);
    } else if (steps.strict_value < steps.start) {
      move = steps.strict_move;
    }
    if (norm(move) > 0) {
      place_group(move, ring_share);
      for (int u : group_) moved_[u] = 1;
      for (int i : touched_) {
        Sample& s = sample(i);
        s.d += combined_[i] * dot(move, s.direction);
      }
    }
    for (int i : touched_) combined_[i] = 0;
  }
}

}  // namespace fit_detail

OffsetResult balance_offsets(const SurfaceMesh& mesh, DualMesh& dual, const std::vector<std::vector<int>>& incident,
                             const std::function<bool(int)>& acceptable, const OffsetOptions& options,
                             const std::function<std::function<bool(int)>()>& focus_floor,
                             const ClosestPointIndex* mesh_index, const std::vector<int>* input_vertex_cell) {
  OffsetResult result;
  fit_detail::OffsetBalancer balancer(mesh, dual, incident, acceptable, options, mesh_index, input_vertex_cell);
  std::vector<Vec3> best = dual.positions;
  double best_max = result.max_before = balancer.measure();
  for (int round = 0; round < options.rounds; ++round) {
    // After the first round, only the vertices near the largest distances.
    const double floor = round == 0 ? 0.0 : options.active_fraction * best_max;
    for (int s = 0; s < options.sweeps; ++s) balancer.sweep(floor);
    const double largest = balancer.measure(options.requery_fraction * best_max);
    if (largest < best_max) {
      best_max = largest;
      best = dual.positions;
    }
  }
  if (focus_floor && options.focus_rounds > 0) {
    balancer.reset(best);
    const std::function<bool(int)> focus_acceptable = focus_floor();
    balancer.set_quality_budget(options.focus_quality_budget * static_cast<double>(dual.triangles.size()));
    if (options.refine_level > 0) {
      balancer.refine_input(options.focus_fraction * best_max, options.refine_level);
      balancer.refine_remesh(options.focus_fraction * best_max, 2 * options.refine_level);
    }
    best_max = balancer.measure();
    for (int round = 0; round < options.focus_rounds; ++round) {
      const double active = options.focus_fraction * best_max;
      balancer.group_sweep(active, acceptable, focus_acceptable, 0);
      if (options.ring_share > 0) balancer.group_sweep(active, acceptable, focus_acceptable, options.ring_share);
      const double largest = balancer.measure(options.requery_fraction * best_max);
      if (largest < best_max) {
        best_max = largest;
        best = dual.positions;
      }
    }
  }
  dual.positions = best;
  result.max_after = best_max;
  return result;
}

}  // namespace lrvd
