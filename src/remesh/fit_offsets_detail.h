// Internals of balance_offsets (fit_offsets.h), shared by fit_offsets_samples.cpp (the samples of the
// two surfaces and their distances) and fit_offsets.cpp (the steps). Not part of the public API.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "diagram/dual.h"
#include "mesh/closest_point.h"
#include "mesh/surface_mesh.h"
#include "remesh/fit_offsets.h"

namespace lrvd::fit_detail {

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

class OffsetBalancer {
 public:
  // fit_offsets_samples.cpp: places the samples on both surfaces (not measured yet).
  OffsetBalancer(const SurfaceMesh& mesh, DualMesh& dual, const std::vector<std::vector<int>>& incident,
                 const std::function<bool(int)>& acceptable, const OffsetOptions& options,
                 const ClosestPointIndex* mesh_index, const std::vector<int>* input_vertex_cell);

  // Measures the samples on triangles that moved and whose linearised |d| reaches `floor` (the
  // others keep the linearised value: far below the largest, they only matter for the mean);
  // returns the largest |d|.
  double measure(double floor = 0);

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

  // Adds a finer lattice (level `level`, all points) on the input triangles around the input samples
  // whose |d| reaches `threshold`: there the distance between the input's vertices may exceed theirs
  // (a tine's side is farther from the chords than its tip). Returns the samples added.
  int refine_input(double threshold, int level);
  void set_quality_budget(double budget) { quality_budget_ = budget; }

  // The same on the remesh: its triangles with a sample whose |d| reaches `threshold` get a lattice
  // at `level` (their corners are samples already), measured at the next measure().
  int refine_remesh(double threshold, int level);
  // Sets the positions, marking the vertices that differ as moved.
  void reset(const std::vector<Vec3>& positions);

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

  // Defined in fit_offsets_samples.cpp, and those below in fit_offsets.cpp. The `inline` ones are
  // called only in their own file: inline, the compiler may still inline them into the hot loops
  // there, as when the class was private to one file.
  inline Vec3 triangle_normal(int t) const;
  void place_samples();
  // The input vertices' first hints: a proper remesh triangle at the vertex whose cell holds them.
  void hint_input_vertices(const std::vector<int>& cell_of);
  // Per vertex, the samples of its triangles with the vertex's weight there (CSR).
  inline void index_samples();

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
  std::vector<char> on_boundary_;  // vertices on the remesh's boundary (an edge of one triangle)
  std::vector<Entry> entries_;
  std::vector<double> coefficient_, local_d_, local_w_;
  std::vector<Vec3> local_g_;
  double quality_budget_ = 0;  // the Q the focus rounds' relaxed steps may still take, summed over triangles
  std::vector<double> combined_;  // group_sweep: per sample, the weight of the group's moving corners
  std::vector<int> group_, touched_, around_;  // group_sweep: the group, its samples, its triangles
  std::vector<Vec3> group_from_;
};

}  // namespace lrvd::fit_detail
