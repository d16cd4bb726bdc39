// Untangling the remesh where its triangles cut through each other: moves vertices of crossing
// triangles a little off the surface (one at a time, or a triangle or an edge of it together) and
// flips edges of crossing triangles, while the exact crossing count drops and the triangles keep
// their shape.
//
// Why: on a part thinner than the vertex spacing (a slab's rim, a bend of a folded sheet, the rim
// of a thin-walled cup) the dual is a manifold of the right genus, but its chords across one side
// cut through the chords across the other: the sag of a chord (L²/8R) or the zig-zag of the
// triangles around the rim exceeds the thickness. Raising the density there draws samples in only
// slowly (a cell shrinks as density^(-1/4)); moving the vertices of the offending triangles by a
// fraction of an edge — about the thickness — separates the sides. Where the connectivity itself
// is tangled (a triangle joining the outer side of a bend to the inner one), no small move does,
// and an edge flip reconnects it; flips keep the vertex count, the Euler characteristic and the
// orientation, and are taken only if the new edge is not in the mesh yet.
#pragma once

#include <vector>

#include "diagram/dual.h"
#include "mesh/surface_mesh.h"
#include "samples/samples.h"

namespace lrvd {

struct UntangleOptions {
  int passes = 12;                     //!< sweeps over the vertices of crossing triangles
  double max_move = 0.5;               //!< a vertex stays within this fraction of its mean edge length of where it was
  double max_angle_floor = 30.0;       //!< the angle floor is min(this, the smallest angle before)
  bool more_directions = true;         //!< single moves also along the crossed triangles' normals and the axes
  bool group_moves = true;             //!< also move a crossing triangle, or one of its edges, as a whole
  bool flip_edges = true;              //!< also flip edges of crossing triangles
};

//! The crossings a remesh inherits from its input: those between dual triangles whose samples lie
//! on two components of `mesh` that cross each other there. Built with no mesh, it excuses none.
class InputCrossings {
 public:
  InputCrossings() = default;
  explicit InputCrossings(const SurfaceMesh& mesh);
  bool any() const { return !pairs_.empty(); }
  //! Whether the crossing of dual triangles s and t (vertex i = sample i) is the input's own: the
  //! samples of each lie on one component, and the two components cross each other.
  bool inherited(const Samples& samples, const Triangle& s, const Triangle& t) const;

 private:
  int component(const Samples& samples, const Triangle& t) const;
  const SurfaceMesh* mesh_ = nullptr;
  std::vector<std::pair<int, int>> pairs_;  //!< intersecting_component_pairs(mesh)
};

struct UntangleResult {
  int crossings_before = 0;   //!< crossing pairs counted (see untangle_crossings) before
  int crossings_after = 0;    //!< and after
  int moved = 0;              //!< vertices that left their position
  int flipped = 0;            //!< edges flipped
  double max_displacement = 0;
  std::vector<std::pair<int, int>> remaining;  //!< the crossing pairs left (triangle indices)
};

//! Moves vertices of `dual` (whose vertex i is sample i on `mesh`) and flips its edges to remove
//! crossing triangle pairs. Sweeps, until no crossing is left or a sweep changes nothing: single
//! vertices of crossing triangles (along the input's normal, the vertex normal, the normals of the
//! triangles they cross, the axes, or towards their neighbours), then whole crossing triangles and
//! their edges (along the crossed triangle's normal, their own, the axes), then the edges of
//! crossing triangles flipped. A change is taken only if the exact count of crossing pairs of the
//! triangles it touches drops; a move also only if every triangle of the vertex keeps Q at or above
//! the mesh's worst Q before untangling (or its own, if lower), its smallest angle at or above
//! min(30°, the mesh's smallest angle) and its orientation, and each vertex stays within max_move
//! of its mean edge length of where it started; a flip only if both new triangles are proper, keep
//! those floors and face the side their two predecessors faced, and the new edge is not in the
//! mesh. Pairs the input has too (`inherited`) are not counted. With no crossing nothing changes; an edge without exactly two triangles
//! oriented consistently is never flipped.
//! `crossings`, if given, are find_self_intersections of `dual`'s proper triangles as it is passed
//! (the caller found them already).
UntangleResult untangle_crossings(const SurfaceMesh& mesh, const Samples& samples, DualMesh& dual,
                                  const InputCrossings& inherited, const UntangleOptions& options = {},
                                  const std::vector<std::pair<int, int>>* crossings = nullptr);

}  // namespace lrvd
