// Vertex offsets balancing the sampled two-sided distance (see fit_offsets.h).
#include "remesh/fit_offsets.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <tbb/parallel_for.h>

#include "mesh/closest_point.h"
#include "metrics/quality.h"
#include "metrics/self_intersections.h"

namespace lrvd {

namespace {

// A sample and its distance, written as "remesh minus input" along the outward direction: d > 0
// where the remesh is outside the input. Moving the remesh at the sample by δ changes d by
// δ·direction (to first order).
struct Sample {
  int triangle = -1;  // the remesh triangle that holds the sample (input samples: the closest one)
  Vec3 barycentric;   // in that triangle
  double d = 0;
  Vec3 direction;     // unit, outward
  int hint = -1;      // the triangle of the last closest point (remesh samples: the input's)
};

// Barycentric lattice points of a triangle at level k, without its corners, each edge's points
// only from the triangle that has the edge's lower vertex first (so they come once on an oriented
// manifold), and the centroid when the lattice has edge points but no interior point (a triangle
// shorter than the spacing has its corners only).
void lattice(const Triangle& f, int k, std::vector<Vec3>& out) {
  for (int i = 0; i <= k; ++i)
    for (int j = 0; i + j <= k; ++j) {
      const int l = k - i - j;
      const int zeros = (i == 0) + (j == 0) + (l == 0);
      if (zeros >= 2) continue;
      if (zeros == 1) {
        // Corners of the edge: the two with a nonzero weight, in the triangle's order.
        const int missing = i == 0 ? 0 : j == 0 ? 1 : 2;
        if (f[(missing + 1) % 3] > f[(missing + 2) % 3]) continue;
      }
      out.push_back({i / double(k), j / double(k), l / double(k)});
    }
  if (k == 2) out.push_back({1 / 3.0, 1 / 3.0, 1 / 3.0});
}

// The lattice level for a spacing, even from 2 on (so that the edge midpoints are samples: a chord's
// distance to a bend is largest there), at least `lowest`.
int lattice_level(const Vec3& a, const Vec3& b, const Vec3& c, double spacing, int lowest) {
  const double longest = std::max({distance(a, b), distance(b, c), distance(c, a)});
  const int k = std::clamp(static_cast<int>(std::ceil(longest / spacing)), lowest, 16);
  return k == 1 ? 1 : k + k % 2;
}

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

Vec3 at(const std::vector<Vec3>& positions, const Triangle& f, const Vec3& b) {
  return b.x * positions[f[0]] + b.y * positions[f[1]] + b.z * positions[f[2]];
}

// Outward unit direction from `from` to `to` given the normal at `from`, and the signed length.
void signed_offset(const Vec3& to, const Vec3& from, const Vec3& normal, double& d, Vec3& direction) {
  const Vec3 u = to - from;
  const double length = norm(u);
  const double sign = dot(u, normal) >= 0 ? 1.0 : -1.0;
  d = sign * length;
  direction = length > 1e-12 * (norm(to) + norm(from) + 1) ? (sign / length) * u : normal;
}

class OffsetBalancer {
 public:
  OffsetBalancer(const SurfaceMesh& mesh, DualMesh& dual, const std::vector<std::vector<int>>& incident,
                 const std::function<bool(int)>& acceptable, const OffsetOptions& options,
                 const ClosestPointIndex* mesh_index, const std::vector<int>* input_vertex_cell)
      : mesh_(mesh), dual_(dual), incident_(incident), acceptable_(acceptable), options_(options),
        proper_(proper_triangles(dual.positions, dual.triangles)) {
    if (!mesh_index) own_index_.emplace(mesh);
    mesh_index_ = mesh_index ? mesh_index : &*own_index_;
    for (int t = 0; t < static_cast<int>(dual_.triangles.size()); ++t)
      if (proper_[t]) proper_triangles_.push_back(dual_.triangles[t]), dual_triangle_.push_back(t);
    place_samples();
    if (input_vertex_cell) hint_input_vertices(*input_vertex_cell);
    moved_.assign(dual.positions.size(), 1);
  }

  // Measures the samples on triangles that moved and whose linearised |d| reaches `floor` (the
  // others keep the linearised value: far below the largest, they only matter for the mean);
  // returns the largest |d|.
  double measure(double floor = 0) {
    const int nr = static_cast<int>(remesh_.size()), ni = static_cast<int>(input_points_.size());
    // Only the samples on triangles with a moved corner can have changed (an input sample's
    // distance to its old triangle is unchanged then, so its stale value is an upper bound).
    auto moved = [&](const Sample& s) {
      if (s.triangle < 0) return true;
      const Triangle& f = dual_.triangles[s.triangle];
      return (moved_[f[0]] || moved_[f[1]] || moved_[f[2]]) && std::abs(s.d) >= floor;
    };
    // The remesh's index only when an input sample is measured.
    std::optional<ClosestPointIndex> remesh_index;
    if (std::any_of(input_.begin(), input_.end(), moved)) remesh_index.emplace(dual_.positions, proper_triangles_);
    tbb::parallel_for(tbb::blocked_range<int>(0, nr + ni, 1024), [&](const tbb::blocked_range<int>& range) {
      // A sample's last answer, or else the answer of the sample before it (samples come in the
      // order of their triangles), starts the search: hints only prune it, the answer is the same.
      int last_on_mesh = -1, last_on_remesh = -1;
      for (int i = range.begin(); i < range.end(); ++i) {
        if (!moved(sample(i))) continue;
        if (i < nr) {
          Sample& s = remesh_[i];
          const Vec3 x = at(dual_.positions, dual_.triangles[s.triangle], s.barycentric);
          const ClosestPoint c = mesh_index_->query(x, s.hint >= 0 ? s.hint : last_on_mesh);
          s.hint = last_on_mesh = c.triangle;
          signed_offset(x, c.point, mesh_.triangle_normal(c.triangle), s.d, s.direction);
        } else {
          Sample& s = input_[i - nr];
          const ClosestPoint c = remesh_index->query(input_points_[i - nr], s.hint >= 0 ? s.hint : last_on_remesh);
          s.hint = last_on_remesh = c.triangle;
          s.triangle = dual_triangle_[c.triangle];
          s.barycentric = c.barycentric;
          // The input point is outside the remesh when d < 0: the remesh must move out.
          signed_offset(input_points_[i - nr], c.point, triangle_normal(s.triangle), s.d, s.direction);
          s.d = -s.d;
        }
      }
    });
    double largest = 0;
    for (const std::vector<Sample>* list : {&remesh_, &input_})
      for (const Sample& s : *list) largest = std::max(largest, std::abs(s.d));
    std::fill(moved_.begin(), moved_.end(), 0);
    index_samples();
    return largest;
  }

  // The unit normal of vertex v (its triangles' area-weighted normals) and the shortest edge of
  // its triangles; false when either is degenerate.
  bool vertex_frame(int v, Vec3& normal, double& shortest) const {
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

  // One sweep of coordinate descent on the linearised distances: each vertex tries a few directions
  // (its normal; the steepest descent of its samples' Σ|d|^p, which leaves the normal at a tip the
  // vertex must reach sideways; that descent's tangential part) and keeps the best accepted step.
  void sweep(double floor) {
    const int n = static_cast<int>(dual_.positions.size());
    for (int v = 0; v < n; ++v) {
      if (incident_[v].empty() || first_[v] == first_[v + 1]) continue;
      Vec3 normal;
      double shortest;
      if (!vertex_frame(v, normal, shortest)) continue;
      double scale = 0;
      for (int k = first_[v]; k < first_[v + 1]; ++k) scale = std::max(scale, std::abs(sample(entries_[k].sample).d));
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

 private:
  struct Entry {
    int sample;     // index into remesh_ then input_
    double weight;  // the vertex's barycentric weight at the sample
  };

  Sample& sample(int i) {
    const int nr = static_cast<int>(remesh_.size());
    return i < nr ? remesh_[i] : input_[i - nr];
  }
  const Sample& sample(int i) const {
    const int nr = static_cast<int>(remesh_.size());
    return i < nr ? remesh_[i] : input_[i - nr];
  }

  Vec3 triangle_normal(int t) const {
    const Triangle& f = dual_.triangles[t];
    const Vec3 n = cross(dual_.positions[f[1]] - dual_.positions[f[0]], dual_.positions[f[2]] - dual_.positions[f[0]]);
    const double length = norm(n);
    return length > 0 ? n / length : n;
  }

  void place_samples() {
    const std::vector<Vec3>& x = dual_.positions;
    double length_sum = 0;
    int edges = 0;
    for (int t = 0; t < static_cast<int>(dual_.triangles.size()); ++t)
      if (proper_[t])
        for (int e = 0; e < 3; ++e, ++edges) length_sum += distance(x[dual_.triangles[t][e]], x[dual_.triangles[t][(e + 1) % 3]]);
    if (edges == 0) return;
    const double mean_edge = length_sum / edges, spacing = mean_edge / options_.samples_per_edge;
    // Remesh samples: each used vertex once (from one of its triangles), then the lattices.
    std::vector<char> placed(x.size(), 0);
    std::vector<Vec3> bary;
    for (int t = 0; t < static_cast<int>(dual_.triangles.size()); ++t) {
      if (!proper_[t]) continue;
      const Triangle& f = dual_.triangles[t];
      for (int k = 0; k < 3; ++k)
        if (!placed[f[k]]) {
          placed[f[k]] = 1;
          remesh_.push_back({t, {k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0}, 0, {}});
        }
      bary.clear();
      lattice(f, lattice_level(x[f[0]], x[f[1]], x[f[2]], spacing, 2), bary);
      for (const Vec3& b : bary) remesh_.push_back({t, b, 0, {}});
    }
    // Input samples: the vertices, then the lattices.
    input_points_ = mesh_.positions();
    input_source_.assign(input_points_.size(), -1);
    for (int t = 0; t < mesh_.triangle_count(); ++t) {
      const Triangle& f = mesh_.triangle(t);
      const std::vector<Vec3>& p = mesh_.positions();
      bary.clear();
      lattice(f, lattice_level(p[f[0]], p[f[1]], p[f[2]], mean_edge / options_.input_samples_per_edge, 1), bary);
      for (const Vec3& b : bary) input_points_.push_back(at(p, f, b)), input_source_.push_back(t);
    }
    input_.resize(input_points_.size());
  }

  // The input vertices' first hints: a proper remesh triangle at the vertex whose cell holds them.
  void hint_input_vertices(const std::vector<int>& cell_of) {
    if (static_cast<int>(cell_of.size()) != mesh_.vertex_count()) return;
    // A proper triangle at each remesh vertex, as its index in proper_triangles_.
    std::vector<int> proper_at(dual_.positions.size(), -1);
    for (int k = 0; k < static_cast<int>(proper_triangles_.size()); ++k)
      for (int v : proper_triangles_[k])
        if (proper_at[v] < 0) proper_at[v] = k;
    for (int u = 0; u < mesh_.vertex_count(); ++u)
      if (cell_of[u] >= 0 && cell_of[u] < static_cast<int>(proper_at.size())) input_[u].hint = proper_at[cell_of[u]];
  }

  // Per vertex, the samples of its triangles with the vertex's weight there (CSR).
  void index_samples() {
    const int n = static_cast<int>(dual_.positions.size());
    first_.assign(n + 1, 0);
    auto each = [&](auto&& visit) {
      int i = 0;  // the sample's index: remesh_ then input_
      for (const std::vector<Sample>* list : {&remesh_, &input_})
        for (const Sample& s : *list) {
          const Triangle& f = dual_.triangles[s.triangle];
          const double w[3] = {s.barycentric.x, s.barycentric.y, s.barycentric.z};
          for (int k = 0; k < 3; ++k)
            if (w[k] > 0) visit(f[k], i, w[k]);
          ++i;
        }
    };
    each([&](int v, int, double) { ++first_[v + 1]; });
    for (int v = 0; v < n; ++v) first_[v + 1] += first_[v];
    entries_.resize(first_[n]);
    std::vector<int> next(first_.begin(), first_.end() - 1);
    each([&](int v, int i, double w) { entries_[next[v]++] = {i, w}; });
  }

  // The vertex's samples, gathered: d / scale, weight and direction.
  void gather(int v, double scale) {
    local_d_.clear(), local_w_.clear(), local_g_.clear();
    for (int k = first_[v]; k < first_[v + 1]; ++k) {
      const Sample& s = sample(entries_[k].sample);
      local_d_.push_back(s.d / scale);
      local_w_.push_back(entries_[k].weight);
      local_g_.push_back(s.direction);
    }
  }

  void set_coefficients(const Vec3& direction, double scale) {
    coefficient_.resize(local_d_.size());
    for (size_t k = 0; k < local_d_.size(); ++k) coefficient_[k] = local_w_[k] * dot(direction, local_g_[k]) / scale;
  }

  // Σ |d + c t|^p / scale^p over the gathered samples (c = 0 when t = 0).
  double objective(double t) const { return options_.power == 16 ? objective_with<16>(t) : objective_with<0>(t); }
  template <int P>  // P = options_.power, or 0 when that is not one compiled for
  double objective_with(double t) const {
    const int p = options_.power;
    double sum = 0;
    for (size_t k = 0; k < local_d_.size(); ++k) {
      const double e = local_d_[k] + (t == 0 ? 0 : coefficient_[k] * t);
      sum += P > 0 ? power<P>(e) : power(e, p);
    }
    return sum;
  }

  // The offset t in [-limit, limit] that minimises Σ |d + c t|^p over the gathered samples: the
  // function is convex, so Newton's method on its derivative inside a shrinking bracket.
  double best_offset(double limit) const { return options_.power == 16 ? best_offset_with<16>(limit) : best_offset_with<0>(limit); }
  template <int P>  // as in objective_with
  double best_offset_with(double limit) const {
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

  const SurfaceMesh& mesh_;
  DualMesh& dual_;
  const std::vector<std::vector<int>>& incident_;
  const std::function<bool(int)>& acceptable_;
  const OffsetOptions& options_;
  std::optional<ClosestPointIndex> own_index_;  // when no index of the mesh is given
  const ClosestPointIndex* mesh_index_ = nullptr;
  const std::vector<char> proper_;
  std::vector<Triangle> proper_triangles_;  // the remesh triangles the input samples may land on
  std::vector<int> dual_triangle_;          // their indices in the dual
  std::vector<Sample> remesh_, input_;
  std::vector<Vec3> input_points_;
  std::vector<int> input_source_;    // the input triangle of a lattice point, -1 for the input's vertices
  std::vector<char> input_refined_;  // input triangles sampled at the finer level already
  std::vector<int> first_;
  std::vector<char> moved_;  // vertices moved since the last measure
  std::vector<Entry> entries_;
  std::vector<double> coefficient_, local_d_, local_w_;
  std::vector<Vec3> local_g_;
  double quality_budget_ = 0;  // the Q the focus rounds' relaxed steps may still take, summed over triangles
  std::vector<double> combined_;  // group_sweep: per sample, the weight of the group's moving corners
 public:
  // Coordinate descent on groups, for the focus rounds: each vertex whose samples reach `floor`,
  // largest |d| first, moves alone (ring_share = 0) or with its one-ring, the ring by `ring_share` of
  // the vertex's step (1: the triangles at the vertex keep their shape and the ring's outer
  // triangles deform instead; where the vertex alone is stopped by a triangle at the floor, the
  // group can still move). A step is taken under `relaxed` (the worst-Q floor) when that beats the
  // best step under `strict` (the rounds' floor) and the Q it takes from the group's triangles fits
  // in what is left of the budget; otherwise under `strict`.
  void group_sweep(double floor, const std::function<bool(int)>& strict, const std::function<bool(int)>& relaxed,
                   double ring_share) {
    const int n = static_cast<int>(dual_.positions.size());
    combined_.assign(remesh_.size() + input_.size(), 0);
    std::vector<int> touched, group;
    std::vector<Vec3> from;
    // The vertices at the largest distances first: they spend the quality budget first.
    std::vector<std::pair<double, int>> order;
    for (int v = 0; v < n; ++v) {
      if (incident_[v].empty() || first_[v] == first_[v + 1]) continue;
      double scale = 0;
      for (int k = first_[v]; k < first_[v + 1]; ++k) scale = std::max(scale, std::abs(sample(entries_[k].sample).d));
      if (scale > 0 && scale >= floor) order.push_back({-scale, v});
    }
    std::sort(order.begin(), order.end());
    std::vector<int> around;
    for (const auto& [negative_scale, v] : order) {
      group.assign(1, v);
      if (ring_share > 0)
        for (int t : incident_[v])
          for (int u : dual_.triangles[t])
            if (std::find(group.begin(), group.end(), u) == group.end()) group.push_back(u);
      Vec3 normal;
      double shortest;
      if (!vertex_frame(v, normal, shortest)) continue;
      // The group's samples, each with the weight of its moving corners (the ring's scaled by its share).
      touched.clear();
      for (size_t g = 0; g < group.size(); ++g)
        for (int k = first_[group[g]]; k < first_[group[g] + 1]; ++k) {
          const int i = entries_[k].sample;
          if (combined_[i] == 0) touched.push_back(i);
          combined_[i] += (g == 0 ? 1.0 : ring_share) * entries_[k].weight;
        }
      double group_scale = 0;
      for (int i : touched) group_scale = std::max(group_scale, std::abs(sample(i).d));
      local_d_.clear(), local_w_.clear(), local_g_.clear();
      Vec3 descent{0, 0, 0};
      for (int i : touched) {
        const Sample& s = sample(i);
        local_d_.push_back(s.d / group_scale);
        local_w_.push_back(combined_[i]);
        local_g_.push_back(s.direction);
        descent -= (power(s.d / group_scale, options_.power - 1) * combined_[i]) * s.direction;
      }
      from.resize(group.size());
      for (size_t g = 0; g < group.size(); ++g) from[g] = dual_.positions[group[g]];
      auto place = [&](const Vec3& move) {
        for (size_t g = 0; g < group.size(); ++g) dual_.positions[group[g]] = from[g] + (g == 0 ? 1.0 : ring_share) * move;
      };
      auto holds = [&](const std::function<bool(int)>& accept) {
        for (int u : group)
          if (!accept(u)) return false;
        return true;
      };
      const double limit = options_.trust * shortest;
      const double start = objective(0);
      Vec3 strict_move{0, 0, 0}, relaxed_move{0, 0, 0};
      double strict_value = start, relaxed_value = start;
      const Vec3 unit = norm(descent) > 0 ? descent / norm(descent) : Vec3{0, 0, 0};
      const Vec3 along = unit - dot(unit, normal) * normal;
      const Vec3 candidates[3] = {normal, unit, norm(along) > 1e-3 ? along / norm(along) : Vec3{0, 0, 0}};
      for (const Vec3& direction : candidates) {
        if (!(norm(direction) > 0)) continue;
        set_coefficients(direction, group_scale);
        const double t = best_offset(limit);
        for (int which = 0; which < (relaxed ? 2 : 1); ++which)
          for (double step : {1.0, 0.875, 0.75, 0.625, 0.5, 0.375, 0.25, 0.125}) {
            place((step * t) * direction);
            const bool ok = holds(which == 0 ? strict : relaxed);
            place({0, 0, 0});
            if (!ok) continue;
            const double value = objective(step * t);
            double& best = which == 0 ? strict_value : relaxed_value;
            if (value < best) best = value, (which == 0 ? strict_move : relaxed_move) = (step * t) * direction;
            break;
          }
      }
      // The Q the relaxed step takes from the triangles around the group, against the budget.
      double spent = 0;
      if (relaxed_value < strict_value) {
        around.clear();
        for (int u : group)
          for (int t : incident_[u])
            if (std::find(around.begin(), around.end(), t) == around.end()) around.push_back(t);
        auto q_sum = [&] {
          double sum = 0;
          for (int t : around) {
            const Triangle& f = dual_.triangles[t];
            sum += triangle_quality(dual_.positions[f[0]], dual_.positions[f[1]], dual_.positions[f[2]]);
          }
          return sum;
        };
        const double before = q_sum();
        place(relaxed_move);
        spent = before - q_sum();
        place({0, 0, 0});
      }
      Vec3 move{0, 0, 0};
      if (relaxed_value < strict_value && spent <= quality_budget_) {
        move = relaxed_move;
        quality_budget_ -= std::max(0.0, spent);
      } else if (strict_value < start) {
        move = strict_move;
      }
      if (norm(move) > 0) {
        place(move);
        for (int u : group) moved_[u] = 1;
        for (int i : touched) {
          Sample& s = sample(i);
          s.d += combined_[i] * dot(move, s.direction);
        }
      }
      for (int i : touched) combined_[i] = 0;
    }
  }

  // Adds a finer lattice (level `level`, all points) on the input triangles around the input samples
  // whose |d| reaches `threshold`: there the distance between the input's vertices may exceed theirs
  // (a tine's side is farther from the chords than its tip). Returns the samples added.
  int refine_input(double threshold, int level) {
    const int nv = static_cast<int>(mesh_.positions().size());
    input_refined_.resize(mesh_.triangle_count(), 0);
    std::vector<int> triangles;
    for (size_t i = 0; i < input_.size(); ++i) {
      if (!(std::abs(input_[i].d) >= threshold)) continue;
      if (static_cast<int>(i) < nv) {
        for (const int* t = mesh_.vertex_triangles_begin(static_cast<int>(i)); t != mesh_.vertex_triangles_end(static_cast<int>(i)); ++t)
          triangles.push_back(*t);
      } else {
        triangles.push_back(input_source_[i]);
      }
    }
    const size_t before = input_points_.size();
    const std::vector<Vec3>& p = mesh_.positions();
    for (int t : triangles) {
      if (input_refined_[t]) continue;
      input_refined_[t] = 1;
      const Triangle& f = mesh_.triangle(t);
      for (int i = 0; i <= level; ++i)
        for (int j = 0; i + j <= level; ++j) {
          const int l = level - i - j;
          if ((i == 0) + (j == 0) + (l == 0) >= 2) continue;
          input_points_.push_back(at(p, f, {i / double(level), j / double(level), l / double(level)}));
          input_source_.push_back(t);
        }
    }
    input_.resize(input_points_.size());
    return static_cast<int>(input_points_.size() - before);
  }
  void set_quality_budget(double budget) { quality_budget_ = budget; }

  // The same on the remesh: its triangles with a sample whose |d| reaches `threshold` get a lattice
  // at `level` (their corners are samples already), measured at the next measure().
  int refine_remesh(double threshold, int level) {
    std::vector<char> refine(dual_.triangles.size(), 0);
    for (const Sample& s : remesh_)
      if (std::abs(s.d) >= threshold) refine[s.triangle] = 1;
    const size_t before = remesh_.size();
    for (int t = 0; t < static_cast<int>(refine.size()); ++t) {
      if (!refine[t]) continue;
      for (int i = 0; i <= level; ++i)
        for (int j = 0; i + j <= level; ++j) {
          const int l = level - i - j;
          if ((i == 0) + (j == 0) + (l == 0) >= 2) continue;
          remesh_.push_back({t, {i / double(level), j / double(level), l / double(level)}, 0, {}});
        }
      for (int v : dual_.triangles[t]) moved_[v] = 1;
    }
    return static_cast<int>(remesh_.size() - before);
  }
  // Sets the positions, marking the vertices that differ as moved.
  void reset(const std::vector<Vec3>& positions) {
    for (size_t v = 0; v < positions.size(); ++v)
      if (positions[v] != dual_.positions[v]) moved_[v] = 1;
    dual_.positions = positions;
  }
};

}  // namespace

OffsetResult balance_offsets(const SurfaceMesh& mesh, DualMesh& dual, const std::vector<std::vector<int>>& incident,
                             const std::function<bool(int)>& acceptable, const OffsetOptions& options,
                             const std::function<std::function<bool(int)>()>& focus_floor,
                             const ClosestPointIndex* mesh_index, const std::vector<int>* input_vertex_cell) {
  OffsetResult result;
  OffsetBalancer balancer(mesh, dual, incident, acceptable, options, mesh_index, input_vertex_cell);
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
