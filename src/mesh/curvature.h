// Discrete curvature of a triangle mesh, for the curvature-adaptive CVT density and MPS radius.
#pragma once

#include <vector>

#include "mesh/surface_mesh.h"

namespace lrvd {

//! Mean curvature magnitude at each vertex, |Δx| / 2 from the cotangent Laplacian over the
//! barycentric vertex area; 0 on the boundary, where it would measure the boundary's bend.
std::vector<double> mean_curvature(const SurfaceMesh& mesh);

}  // namespace lrvd
