// Points that nearly coincide: welding a soup whose shared corners were written with rounding
// noise (`--weld`), and finding seams a weld would close (docs/input.md, "Near-coincident corners").
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

}  // namespace lrvd
