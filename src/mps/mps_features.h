// Feature-first sampling for maximal Poisson-disk sampling (not in the paper): the mesh's feature
// lines and corners, and samples on them before any dart on the surface (docs/algorithms/mps.md,
// "Features"). Internal to mps.cpp; not part of the public API.
#pragma once

#include <utility>
#include <vector>

#include "mesh/surface_mesh.h"
#include "mps/mps_sampler.h"

namespace lrvd::mps_detail {

//! The feature lines of a mesh at a feature angle: its boundary edges and the edges whose two
//! triangles' normals are more than the angle apart; its corners, the vertices with other than two
//! such edges or with two that turn by more than the angle.
struct FeatureLines {
  struct Edge {
    int t, e, a, b;  //!< triangle, its edge e from corner a to corner b
  };
  std::vector<Edge> edges;
  int boundary_edges = 0;                      //!< of edges: on the boundary
  std::vector<std::vector<int>> at_vertex;     //!< the edges at each vertex
  std::vector<char> corner;                    //!< per vertex: a corner
  std::vector<std::pair<double, int>> corners; //!< (minus the cosine of the turn of its two edges, vertex), sharpest first
};

//! The feature lines and corners of `mesh` at `angle_deg` degrees. `normals`, if given: the unit
//! normal of each triangle as DiskIndex computes it (else computed here, alike).
//! \pre 0 < angle_deg < 180.
FeatureLines find_feature_lines(const SurfaceMesh& mesh, double angle_deg, const Vec3* normals = nullptr);

//! Samples on the corners and along the feature lines of `mesh` (find_feature_lines), each through
//! the sampler's own test, so that the minimum distance holds as for any other sample; none off the
//! boundary inside the balls of `exclusions` (MpsOptions::feature_exclusions). Returns the samples placed.
int sample_features(const SurfaceMesh& mesh, Sampler& sampler, double angle_deg,
                    const std::vector<std::pair<Vec3, double>>& exclusions = {});

}  // namespace lrvd::mps_detail
