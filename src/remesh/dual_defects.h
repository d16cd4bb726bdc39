// The defects of a CVT's dual that the remesh repairs (paper Fig. 13): bad edges, repeated or
// merged triangles, unused samples, crossings, and the cells that locate a lost handle or hole.
#pragma once

#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "diagram/diagram.h"
#include "diagram/dual.h"
#include "mesh/surface_mesh.h"
#include "remesh/untangle.h"
#include "samples/samples.h"

namespace lrvd {

//! A ring of cells round a part of the surface (a tube, a handle) that the cells are too large to
//! go round: one cell whose boundary is more than one loop, or two cells sharing two arcs.
struct RingCell {
  int cell = -1;
  int other = -1;  //!< the second cell of a pair sharing two arcs; -1 for a cell alone
  //! The length of the ring's shortest boundary loop that meets other cells, from double positions:
  //! about how far round the part it wraps is (a figure for messages, deciding nothing).
  double around = 0;
};

//! Edges of a dual that are not shared by exactly two triangles (one, on a closed input), triangles
//! repeated on the same three vertices or given by two triple points (merged), samples in no
//! triangle, and triangles that intersect each other (but for the crossings the input has too:
//! `inherited`, between samples on two input components that cross each other): the
//! samples involved; also the cells that are not disks (a ring around a thin part, a handle
//! inside one cell), share more
//! than one boundary arc with a neighbour, or meet across a strip of an open mesh narrower than
//! them, which locate a lost handle, hole or link when the dual's Euler characteristic is wrong.
struct DualDefects {
  std::vector<int> topological;    //!< samples at bad edges, repeated or merged triangles, unused samples
  std::vector<int> crossing;       //!< samples of triangles that intersect others
  //! cells that are not disks (rings, or holding a handle smaller than them: V - E + F below 1),
  //! or share two arcs with a neighbour, or (two used cells) meet across a
  //! strip narrower than them: their one shared arc runs from the mesh boundary to the mesh
  //! boundary through no triple point, so the dual has no edge between them
  std::vector<int> cell_topology;
  //! Unused samples (also in `topological`) whose cells are disks that meet the boundary of an open
  //! mesh and one other cell: a small cell in a corner sharper than the cells, whose one neighbour
  //! spans the corner.
  //! More samples there repeat the pattern at a smaller scale; fewer make the cell grow until it
  //! meets two others.
  std::vector<int> cornered;
  //! Samples in `topological` whose cells, away from any boundary, hold more than π of the
  //! surface's angle deficit and meet one other cell (unused: a disk inside it) or two (which share
  //! two arcs round it): a cap on a tip sharper than a half-plane. Around such a cap fewer than
  //! three cells of its own size fit, at any scale, so more samples repeat the pattern; a larger cap
  //! meets more cells.
  std::vector<int> tip_caps;
  //! Neighbours of the tip caps that are in `cell_topology` (a ring round the narrowing part below a
  //! cap, or two cells sharing two arcs round it). When its caps have not grown past them for a few rounds, the third run lowers the
  //! density there too, so a cap can take the narrowing part.
  std::vector<int> tip_cap_rings;
  //! Boundary loops of the mesh (indices into SurfaceMesh::boundary_loops) that fewer than three
  //! cells meet: holes the dual closes over (their cells are in `cell_topology`).
  std::vector<int> closed_over_loops;
  //! The rings among the cells in `cell_topology`, with how far round they go.
  std::vector<RingCell> rings;
  bool euler_ok = true;            //!< the dual's V - E + F equals the mesh's Euler characteristic
  //! find_self_intersections of the dual's proper triangles, all of them (for the fitting)
  std::vector<std::pair<int, int>> crossing_pairs;
  //! Nothing to repair: no defect of the dual itself, no crossing, and the right Euler
  //! characteristic (cell-topology findings alone are harmless then).
  bool empty() const { return topological.empty() && crossing.empty() && euler_ok; }
  //! The samples to act on: the dual's own defects first, then crossings, then — when the
  //! Euler characteristic is wrong — the cells that are rings, share two arcs or meet across a strip.
  const std::vector<int>& where_to_act() const {
    if (!topological.empty()) return topological;
    if (!crossing.empty()) return crossing;
    return cell_topology;
  }
  //! "no defect", or the defects by kind with their counts, for progress lines and messages.
  std::string describe() const;
  bool fewer_than(const DualDefects& o) const {
    return std::make_tuple(topological.size(), !euler_ok, crossing.size(), cell_topology.size()) <
           std::make_tuple(o.topological.size(), !o.euler_ok, o.crossing.size(), o.cell_topology.size());
  }
};

//! The defects of `dual`, the dual of `diagram` (the cells of `samples` on `mesh`); `input_closed`:
//! whether the surface the output must keep is closed; `inherited`: the crossings the input has too.
DualDefects find_dual_defects(const DualMesh& dual, const Diagram& diagram, const SurfaceMesh& mesh,
                              const Samples& samples, bool input_closed, const InputCrossings& inherited = {});

}  // namespace lrvd
