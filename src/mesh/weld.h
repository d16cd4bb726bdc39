// Points that nearly coincide: welding a soup whose shared corners were written with rounding
// noise (`--weld`), and finding seams a weld would close (docs/guide/input.md, "Near-coincident corners").
// The tolerance is a distance chosen by the user or the reader, not a topological decision: the
// exact predicates decide everything about the welded mesh afterwards.
#pragma once

#include <functional>
#include <vector>

#include "mesh/surface_mesh.h"

namespace lrvd {

//! Each point's representative after welding every point to an earlier one closer than
//! `tolerance` (Euclidean). Greedy in index order and without chains: point i, if no earlier
//! representative took it, becomes a representative and takes every later free point within the
//! tolerance of it. A representative is its own; the cluster takes its position. `tolerance` <= 0
//! leaves every point its own.
std::vector<int> weld_representatives(const std::vector<Vec3>& points, double tolerance);

//! Candidates (indices into `points`) with another candidate closer than `tolerance` but not at the
//! same coordinates, skipping pairs that `joined(a, b)` says belong together (an edge's ends).
struct NearTwins {
  int count = 0;            //!< candidates with at least one near twin
  int a = -1, b = -1;       //!< the lowest such candidate and its nearest near twin
  double distance = 0;      //!< between a and b
  double max_distance = 0;  //!< the largest distance of any such pair (a weld above it takes them all)
};
NearTwins find_near_twins(const std::vector<Vec3>& points, const std::vector<int>& candidates, double tolerance,
                          const std::function<bool(int, int)>& joined);

//! A corner on the boundary (an edge used by one triangle) that lies on another triangle's boundary
//! edge, away from the edge's ends: a crack along a seam that one side splits at a vertex and the
//! other does not (a T-junction, common in CAD exports).
struct TJunction {
  int vertex;    //!< the corner
  int triangle;  //!< the triangle whose edge it lies on (the corner is not one of its corners)
  int edge;      //!< edge e joins corners e and e + 1
  double along;  //!< where its closest point on the edge is: 0 at corner e, 1 at corner e + 1
};

//! Every (corner, boundary edge) pair with the corner within `tolerance` of the edge's line at a
//! point of the edge farther than `tolerance` from both its ends (a corner near an end is a near
//! twin, or a corner beside it), sorted by triangle, edge and `along`. Triangles with a repeated
//! corner are left out.
std::vector<TJunction> find_t_junctions(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                                        double tolerance);

//! `triangles` with each triangle that has T-junctions on its edges split at them: at the corners
//! on its first such edge, into a fan from the opposite corner, in order along the edge, each part
//! oriented as the triangle. A triangle with junctions on several edges keeps those on the others
//! for another pass (its parts hold the other edges whole). Returns the edges split.
int split_at_t_junctions(std::vector<Triangle>& triangles, const std::vector<TJunction>& junctions);

}  // namespace lrvd
