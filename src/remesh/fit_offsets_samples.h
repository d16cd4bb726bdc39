// The samples of balance_offsets (fit_offsets.h) on both surfaces and their measured distances, per
// remesh vertex; the steps that move the vertices on them are in fit_offsets.cpp. Not part of the public API.
#pragma once

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

// The samples on the remesh (`dual`) and on the input (`mesh`), their distances to the other
// surface, and per remesh vertex the samples of its triangles with its weight there.
class OffsetSamples {
 public:
  // Places the samples on both surfaces (not measured yet).
  OffsetSamples(const SurfaceMesh& mesh, DualMesh& dual, const OffsetOptions& options,
                const ClosestPointIndex* mesh_index, const std::vector<int>* input_vertex_cell);

  // Measures the samples on triangles that moved and whose linearised |d| reaches `floor` (the
  // others keep the linearised value: far below the largest, they only matter for the mean);
  // returns the largest |d|.
  double measure(double floor = 0);

  // Adds a finer lattice (level `level`, all points) on the input triangles around the input samples
  // whose |d| reaches `threshold`: there the distance between the input's vertices may exceed theirs
  // (a tine's side is farther from the chords than its tip). Returns the samples added.
  int refine_input(double threshold, int level);

  // The same on the remesh: its triangles with a sample whose |d| reaches `threshold` get a lattice
  // at `level` (their corners are samples already), measured at the next measure().
  int refine_remesh(double threshold, int level);
  // Sets the positions, marking the vertices that differ as moved.
  void reset(const std::vector<Vec3>& positions);

 protected:
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

  const SurfaceMesh& mesh_;
  DualMesh& dual_;
  const OffsetOptions& options_;
  std::vector<Sample> remesh_, input_;
  std::vector<int> first_;  // per vertex: where its entries start (CSR), one more at the end
  std::vector<char> moved_;  // vertices moved since the last measure
  std::vector<Entry> entries_;

 private:
  // The `inline` ones are called only in this file's .cpp: inline, the compiler may still inline
  // them into the hot loops there.
  inline Vec3 triangle_normal(int t) const;
  void place_samples();
  // The input vertices' first hints: a proper remesh triangle at the vertex whose cell holds them.
  void hint_input_vertices(const std::vector<int>& cell_of);
  // Per vertex, the samples of its triangles with the vertex's weight there (CSR).
  inline void index_samples();

  std::optional<ClosestPointIndex> own_index_;  // when no index of the mesh is given
  const ClosestPointIndex* mesh_index_ = nullptr;
  const std::vector<char> proper_;
  std::vector<Triangle> proper_triangles_;  // the remesh triangles the input samples may land on
  std::vector<int> dual_triangle_;          // their indices in the dual
  std::vector<Vec3> input_points_;
  std::vector<int> input_source_;    // the input triangle of a lattice point, -1 for the input's vertices
  std::vector<char> input_refined_;  // input triangles sampled at the finer level already
  std::vector<char> on_boundary_;  // vertices on the remesh's boundary (an edge of one triangle)
};

}  // namespace lrvd::fit_detail
