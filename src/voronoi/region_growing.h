// The LRVD's cell-to-vertex assignment (paper §3.2): each mesh vertex goes to the cell whose region,
// grown over the edge graph from the samples' triangles in order of power distance, reaches it first.
#pragma once

#include <vector>

#include "mesh/surface_mesh.h"
#include "predicates/predicates.h"
#include "samples/samples.h"
#include "voronoi/growth_entry.h"

namespace lrvd::detail {

// A vertex during the growth: the sample of the least entry queued for it (whose distance is
// computed again from the vertex's position when needed) and the sample it went to (-1 while
// none). One record, not two arrays, and eight bytes: the growth visits the vertices in the order
// of the distances, all over the mesh, and misses the cache on each visit's records.
struct VertexClaim {
  int best_sample = -1;  // the sample of the least entry queued for the vertex, -1 while none
  int label = -1;
};

//! The growth's storage, kept between diagrams of one mesh (a CVT computes hundreds).
struct RegionGrowingWorkspace {
  std::vector<VertexClaim> claims;  // per vertex
  std::vector<VertexEntry> heap;
  std::vector<VertexEntry> seeds;  // the samples' corners, sorted
};

//! vertex_label[v] = the cell that vertex v goes to (one per vertex of the mesh). Every cell's
//! vertex set is connected over the mesh's edges. `sites` are the samples' points and weights.
void assign_vertices_to_cells(const SurfaceMesh& mesh, const Samples& samples, const std::vector<Site>& sites,
                              RegionGrowingWorkspace& work, std::vector<int>& vertex_label);

}  // namespace lrvd::detail
