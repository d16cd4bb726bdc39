// The dual of a diagram (paper §2.2-2.3): the LRDT of an LRVD (or RDT of an RVD, LRRT of an LRPD):
// one triangle per type (c) vertex, joining the three samples whose cells meet there.
#pragma once

#include <vector>

#include "diagram/diagram.h"
#include "mesh/surface_mesh.h"

namespace lrvd {

struct DualMesh {
  std::vector<Vec3> positions;      //!< the samples (every sample is a vertex, used or not)
  std::vector<Triangle> triangles;  //!< oriented like the surface below them
  int merged_duplicates = 0;        //!< type (c) vertices whose triangle another one already gave
  std::vector<int> merged_into;     //!< the triangles those duplicates were merged into (a thin part
                                    //!< wrapped by three cells meets them twice: paper Fig. 13)
};

//! One triangle per type (c) vertex {a, b, c}, ordered as the cells turn counterclockwise around
//! the vertex seen from the normal of its mesh triangle — a combinatorial decision read off the
//! polygons, so the dual is oriented like the input. Identical triangles are merged.
DualMesh compute_dual(const Diagram& diagram, const SurfaceMesh& mesh, const Samples& samples);

}  // namespace lrvd
