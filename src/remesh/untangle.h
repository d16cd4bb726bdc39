// Untangling the remesh where its triangles cut through each other: moves single vertices of
// crossing triangles a little off the surface (along the normal, or towards their neighbours)
// while the exact crossing count drops and the triangles keep their shape.
//
// Why: on a part thinner than the vertex spacing (a slab's rim, a bend of a folded sheet, the rim
// of a thin-walled cup) the dual is a manifold of the right genus, but its chords across one side
// cut through the chords across the other: the sag of a chord (L²/8R) or the zig-zag of the
// triangles around the rim exceeds the thickness. Raising the density there draws samples in only
// slowly (a cell shrinks as density^(-1/4)); moving the vertices of the offending triangles by a
// fraction of an edge — about the thickness — separates the sides.
#pragma once

#include <vector>

#include "mesh/surface_mesh.h"
#include "voronoi/dual.h"
#include "voronoi/samples.h"

namespace lrvd {

struct UntangleOptions {
  int passes = 12;                     //!< sweeps over the vertices of crossing triangles
  double max_move = 0.25;              //!< a vertex stays within this fraction of its mean edge length of where it was
  double max_angle_floor = 30.0;       //!< the angle floor is min(this, the smallest angle before)
};

struct UntangleResult {
  int crossings_before = 0;   //!< crossing pairs counted (see untangle_crossings) before
  int crossings_after = 0;    //!< and after
  int moved = 0;              //!< vertices that left their position
  double max_displacement = 0;
  std::vector<std::pair<int, int>> remaining;  //!< the crossing pairs left (triangle indices)
};

//! Moves vertices of `dual` (whose vertex i is sample i on `mesh`) to remove crossing triangle pairs.
//! A move is taken only if the exact count of crossing pairs drops, every triangle of the vertex
//! keeps Q at or above the mesh's worst Q before untangling (or its own, if lower), its smallest
//! angle at or above min(30°, the mesh's smallest angle) and its orientation. Pairs between two
//! components are not counted when `ignore_between_components` (an input that crosses itself).
//! Triangles are unchanged; with no crossing nothing moves.
UntangleResult untangle_crossings(const SurfaceMesh& mesh, const Samples& samples, DualMesh& dual,
                                  bool ignore_between_components, const UntangleOptions& options = {});

}  // namespace lrvd
