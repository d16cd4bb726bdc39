// Discrete curvature of a triangle mesh, for the curvature-adaptive CVT density and MPS radius.
#pragma once

#include <vector>

#include "mesh/surface_mesh.h"

namespace lrvd {

//! Mean curvature magnitude at each vertex, |Δx| / 2 from the cotangent Laplacian over the
//! barycentric vertex area; 0 on the boundary, where it would measure the boundary's bend.
std::vector<double> mean_curvature(const SurfaceMesh& mesh);

//! Angle deficit at each vertex: 2π minus the angles of its triangles there (the Gaussian curvature
//! gathered at the vertex; a cone's apex has 2π minus its cone angle), π minus them on the boundary
//! (the boundary's turn there).
std::vector<double> angle_deficits(const SurfaceMesh& mesh);

}  // namespace lrvd
