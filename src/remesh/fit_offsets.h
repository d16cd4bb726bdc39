// Second step of the vertex fitting (fit.h): moves the vertices so that the two-sided distance
// between the remesh and the input is balanced, not only least-squares small.
//
// Why: the quadric fit puts a vertex on the planes of its cell, but a chord across a bend then
// stays inside the surface by most of its sagitta s (2s/3 on a cylinder, where the balanced offset
// leaves s/2 on each side), and at the tip of a thin part the vertex would have to move sideways,
// towards the tip, which the quadric's weak directions leave alone.
//
// How: points are sampled on both surfaces (lattices at a fraction of the remesh's edge length,
// always with the edge midpoints, where a chord is farthest from a bend; and the input's
// vertices). Each carries its distance d to the other surface, signed "remesh outside input"
// positive, and the outward direction in which d grows. Each vertex then takes the step that
// minimises Σ|d|^p over the samples of its triangles (p large: close to the maximum), with d
// linearised in the step (the vertex's barycentric weight times the step along the direction),
// along its normal, the steepest descent of its samples or that descent's tangential part:
// coordinate descent over the vertices, re-measured a few times.
#pragma once

#include <functional>
#include <vector>

#include "diagram/dual.h"
#include "mesh/closest_point.h"
#include "mesh/surface_mesh.h"

namespace lrvd {

struct OffsetOptions {
  int rounds = 3;                   //!< re-measurements of the samples, each after `sweeps` sweeps
  int sweeps = 2;                   //!< coordinate-descent sweeps per round, on the linearised distances
  int power = 16;                   //!< p of Σ|d|^p (even): larger is closer to the maximum
  double trust = 0.5;               //!< longest step, as a fraction of the shortest edge at the vertex
  double samples_per_edge = 2;      //!< remesh sample spacing: its mean edge length over this
  double input_samples_per_edge = 2;  //!< the same on the input (its vertices are samples too)
  double active_fraction = 0.5;     //!< after round 1, only vertices with a sample at this × the largest |d|
  double requery_fraction = 0.25;   //!< after round 1, only samples at this × the largest |d| are re-measured
  //! Rounds after the others, on the vertices near the largest |d| only, whose triangles may then go
  //! down to the caller's looser floor (`focus_floor`), alone or with their ring (0: none)
  int focus_rounds = 4;
  double focus_fraction = 0.8;  //!< the focus rounds' vertices: a sample at this × the largest |d|
  //! before the focus rounds, input triangles near focus_fraction × the largest |d| get a lattice at
  //! this level, remesh triangles one at twice it
  int refine_level = 4;
  //! The focus rounds' group steps: the one-ring moves by this share of the vertex's step (1: the
  //! vertex's triangles keep their shape; 0: no group steps)
  double ring_share = 1.0;
  //! The focus rounds' steps below the rounds' floor may lower Qavg by this much in all, the
  //! vertices at the largest |d| first (a thin tip needs them; a smooth bend would spend it all)
  double focus_quality_budget = 0.005;
  bool sideways = true;             //!< also try the steepest descent and its tangential part, not only the normal
};

struct OffsetResult {
  double max_before = 0, max_after = 0;  //!< the largest sampled two-sided distance, before and after
};

//! Moves vertices of `dual` to balance the sampled two-sided distance to `mesh` (see above). A
//! step is taken whole or cut back in eighths, and only if `acceptable(v)` holds with the vertex
//! moved (the caller's quality floor); `incident[v]` are the triangles of vertex v. Of the states
//! after each round, the one with the smallest sampled maximum is kept (the given positions when
//! no round improves on them).
//!
//! Then, with `focus_floor` given, the focus rounds: the input and remesh triangles near the largest
//! distances get finer lattices (the distance between an input's vertices, on a tine's side, can
//! exceed theirs), and only the vertices near the largest |d| move, alone and then with their
//! one-ring, under the floor `focus_floor()` returns (called once, with `dual` at the state the
//! focus rounds start from) where that beats the rounds' floor, within a Qavg budget. `max_after`
//! is then measured on the finer samples. `mesh_index`, if given, is a ClosestPointIndex of `mesh`
//! (the CVT's), used instead of building another. `input_vertex_cell`, if given, is per input vertex
//! the remesh vertex whose cell holds it (or -1): the first search of the vertex's closest point on
//! the remesh starts at that vertex's triangles, which only prunes it (the same answer).
OffsetResult balance_offsets(const SurfaceMesh& mesh, DualMesh& dual, const std::vector<std::vector<int>>& incident,
                             const std::function<bool(int)>& acceptable, const OffsetOptions& options = {},
                             const std::function<std::function<bool(int)>()>& focus_floor = {},
                             const ClosestPointIndex* mesh_index = nullptr,
                             const std::vector<int>* input_vertex_cell = nullptr);

}  // namespace lrvd
