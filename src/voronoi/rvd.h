// The exact restricted Voronoi (power) diagram, the baseline the LRVD is compared with: the cells
// meeting each triangle found on CGAL's Delaunay (regular) triangulation of the samples, clipped exactly.
#pragma once

#include "diagram/diagram.h"

namespace lrvd {

class SurfaceMesh;

//! The exact RVD (or restricted power diagram): the 3D Voronoi (power) diagram of the samples,
//! with neighbours from CGAL's Delaunay (regular) triangulation, intersected with every triangle.
//! \throw InputError as check_diagram_input (voronoi/lrvd.h).
Diagram compute_rvd(const SurfaceMesh& mesh, const Samples& samples, bool weighted = false);

}  // namespace lrvd
