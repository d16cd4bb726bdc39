// Fitting the remesh to the input after the CVT: each vertex moves from its sample (on the
// surface, at the centroid of its cell) towards the point closest in the least-squares sense to
// the planes of the input under its cell, as far as its triangles keep their shape.
//
// Why: the dual's triangles are chords of the surface. Where the surface bends (the tips of
// antlers and hooves, a polyhedral input's corners) every chord cuts the bend on one side, and
// the two-sided distance is set there. A vertex on the planes of its cell's triangles sits at the
// apex of the bend instead, which roughly halves that distance. A second step (fit_offsets.h)
// then balances the sampled two-sided distance, moving vertices along their normals or sideways
// towards tips. The quality floor keeps the CVT's triangle shape: no triangle goes below the CVT's
// own worst Q or its own smallest angle (30° at most), and none turns over; the second step keeps
// the floor of the first step's result, so it never lowers the worst triangle either.
#pragma once

#include <utility>
#include <vector>

#include "diagram/diagram.h"
#include "diagram/dual.h"
#include "mesh/closest_point.h"
#include "mesh/surface_mesh.h"
#include "remesh/fit_offsets.h"

namespace lrvd {

struct FitOptions {
  //! Directions in which the cell's planes vary less than this fraction of the strongest one
  //! leave the vertex where it is (a flat cell keeps its vertex: only the normal direction is
  //! constrained there).
  double rank_threshold = 0.1;
  double max_angle_floor = 30.0;  //!< the angle floor is min(this, the smallest angle before)
  int passes = 3;                 //!< sweeps over the vertices (later ones finish partial moves)
  bool balance = true;            //!< then balance the two-sided distance (fit_offsets.h)
  //! While balancing, each triangle also keeps this fraction of its Q: the sideways steps would
  //! otherwise spend the triangles' shape on distance (with 0: Qavg 0.94 -> 0.86 on ellipsoid 4000).
  double keep_quality = 0.95;
  OffsetOptions offsets;
};

struct FitResult {
  int moved = 0;                //!< vertices that left their sample
  double max_displacement = 0;  //!< the longest move, in the mesh's units
  int reverted = 0;             //!< vertices put back because their triangles crossed others
  OffsetResult offsets;         //!< the sampled distance before and after balancing
  //! find_self_intersections of the fitted dual's proper triangles (for untangle_crossings)
  std::vector<std::pair<int, int>> crossings;
};

//! The passes `lrvd remesh --priority shape` runs (what they cost: docs/results.md, "`--priority shape`").
inline constexpr int kShapePriorityRounds = 5;

struct RelaxOptions {
  int rounds = 0;             //!< passes over the worst triangles (0: none)
  int worst_triangles = 40;   //!< the triangles of lowest Q whose vertices each pass tries to move
};

struct RelaxResult {
  int moved = 0;     //!< vertices that ended away from their sample
  int reverted = 0;  //!< vertices put back because their triangles crossed others
  //! find_self_intersections of the relaxed dual's proper triangles (for fit_to_surface)
  std::vector<std::pair<int, int>> crossings;
};

//! Before the fitting, for triangle shape: each pass moves every vertex of the `worst_triangles`
//! triangles of lowest Q (the worst first) towards the mean of its neighbours, then onto the surface
//! (the closest point of `mesh` on the vertex's own component), by the whole step or by a half, a
//! quarter or an eighth of it: the first of these that raises the lowest Q of the vertex's
//! triangles, turns none of them over and leaves the vertex on a part of the surface that faces the
//! way its previous place did (not across a thin wall). Vertices on the dual's boundary stay. Then
//! the vertices of triangles that cross others and did not before are put back until none does.
//! The fitting that follows keeps the raised worst triangle as its floor, so it has less room on
//! the bends: the distance to the input grows there (elk 1000: 0.79 -> 1.23 %; docs/results.md,
//! "`--priority shape`"). `samples`
//! are the dual's vertices' samples (their triangles of `mesh`); `crossings`, if given, are
//! find_self_intersections of `dual`'s proper triangles as it is passed.
RelaxResult relax_worst_triangles(const SurfaceMesh& mesh, const ClosestPointIndex& index, const Samples& samples,
                                  DualMesh& dual, const RelaxOptions& options,
                                  const std::vector<std::pair<int, int>>* crossings = nullptr);

//! Moves the vertices of `dual` (the dual of `diagram` on `mesh`) towards their cells' quadric
//! minimisers under the quality floor, then (options.balance) balances the two-sided distance under
//! the floor of that result. After each step the vertices of any triangle that crosses another one
//! and did not before are put back, with those of any triangle that falls below the floor then.
//! Triangles and their orientation are unchanged. `mesh_index`, if given, is a ClosestPointIndex of
//! `mesh` (the CVT's), used instead of building another; `crossings`, if given, are
//! find_self_intersections of `dual`'s proper triangles as it is passed (the caller found them).
FitResult fit_to_surface(const Diagram& diagram, const SurfaceMesh& mesh, DualMesh& dual,
                         const FitOptions& options = {}, const ClosestPointIndex* mesh_index = nullptr,
                         const std::vector<std::pair<int, int>>* crossings = nullptr);

}  // namespace lrvd
