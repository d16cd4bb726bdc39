// Feature-first sampling for maximal Poisson-disk sampling (not in the paper): samples on the
// mesh's corners and feature lines before any dart on the surface (docs/algorithms/mps.md,
// "Features"). Internal to mps.cpp; not part of the public API.
#pragma once

#include "mesh/surface_mesh.h"
#include "mps/mps_sampler.h"

namespace lrvd::mps_detail {

//! Samples on the corners and along the feature lines of `mesh` (boundary edges, and edges whose
//! triangles' normals are more than `angle_deg` apart), each through the sampler's own test, so
//! that the minimum distance holds as for any other sample. Returns the samples placed.
int sample_features(const SurfaceMesh& mesh, Sampler& sampler, double angle_deg);

}  // namespace lrvd::mps_detail
