// The remesh pipeline (remesh/remesh_pipeline.h): refinement, samples per component, spatial order,
// remesh_cvt.
#include "remesh/remesh_pipeline.h"

#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "mesh/refine.h"

namespace lrvd {

namespace {

// `input` refined where n samples would crowd its triangles (suggested_refinement_length), or as it is.
SurfaceMesh refined_for_remeshing(const SurfaceMesh& input, int n) {
  const double length = suggested_refinement_length(input, n);
  const bool refine = length > 0 && input.max_edge_length() > length;
  const double at_most = refine ? kRefinedTriangleMargin * expected_refined_triangle_count(input, length) : 0;
  if (at_most > kMaxRefinedTriangles)
    throw InputError(fmt::format("{} vertices would need the mesh refined to about {:.3g} triangles (limit {:.3g}): "
                                 "use fewer vertices",
                                 n, at_most, kMaxRefinedTriangles));
  return refine ? refine_long_edges(input, length) : input;
}

}  // namespace

void require_remesh_vertex_count(const SurfaceMesh& input, int n) {
  const int fewest = input.minimum_vertex_count();
  if (n < fewest)
    throw InputError(fmt::format("{} {} too few for this surface: no triangle mesh with its topology ({} "
                                 "component{}, Euler characteristic {}{}) has fewer than {}",
                                 n, n == 1 ? "vertex is" : "vertices are", input.component_count(),
                                 input.component_count() == 1 ? "" : "s", input.euler_characteristic(),
                                 input.boundary_loops().empty()
                                     ? std::string()
                                     : fmt::format(", {} boundary loop{}", input.boundary_loops().size(),
                                                   input.boundary_loops().size() == 1 ? "" : "s"),
                                 fewest));
}

void order_for_remeshing(SurfaceMesh& mesh, Samples& samples) {
  check_samples(mesh, samples);
  if (mesh.triangle_count() < kSpatialOrderMinTriangles) return;
  std::vector<int> new_triangle;
  mesh = spatially_ordered(mesh, &new_triangle);
  for (int& t : samples.triangles) t = new_triangle[t];
}

RemeshResult remesh_from(const SurfaceMesh& input, RemeshStart& start, const RemeshOptions& options) {
  require_workable_model(input, "remeshing");
  if (start.samples && !start.mesh) throw InputError("remesh_from: samples are given without the mesh they lie on");
  if (start.samples && start.samples->weighted())
    throw InputError("remesh computes a CVT of unweighted samples: the samples given carry weights");
  const int n = start.samples ? start.samples->size() : start.n;
  require_remesh_vertex_count(input, n);
  if (!start.mesh) start.mesh = refined_for_remeshing(input, n);
  SurfaceMesh& mesh = *start.mesh;
  // The CVT keeps each sample on its component: each gets its share of the samples up front, and
  // at least the fewest vertices its own topology needs.
  if (!start.samples)
    start.samples = mesh.component_count() > 1 ? sample_by_component(mesh, n, start.seed, mesh.minimum_vertex_counts())
                                               : sample_uniform(mesh, n, start.seed);
  // The CVT's diagrams pass over the mesh in memory order; the samples stay where they are.
  order_for_remeshing(mesh, *start.samples);
  if (start.before_cvt) start.before_cvt(mesh, *start.samples);
  return remesh_cvt(input, mesh, *start.samples, options);
}

RemeshResult remesh_to(const SurfaceMesh& input, int n, uint64_t seed, const RemeshOptions& options) {
  RemeshStart start;
  start.n = n;
  start.seed = seed;
  return remesh_from(input, start, options);
}

}  // namespace lrvd
