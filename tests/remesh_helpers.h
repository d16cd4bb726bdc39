// Helpers of the remeshing tests (test_cvt, test_dual_defects, test_fit, test_remesh, test_untangle):
// CGAL's meshes, the surface refined for n samples, a whole remesh with its check, and a first CVT
// with the defects of its dual.
#pragma once

#include <string>

#include "io/mesh_io.h"
#include "mesh/refine.h"
#include "metrics/quality.h"
#include "remesh/remesh_pipeline.h"
#include "verification/remesh_check.h"

namespace lrvd::test {

inline SurfaceMesh cgal_mesh(const std::string& name) {
  return read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/" + name).mesh;
}

// The mesh n samples go on: refined when n would crowd its triangles (as remesh_to does it).
inline SurfaceMesh for_samples(const SurfaceMesh& mesh, int n) {
  const double length = suggested_refinement_length(mesh, n);
  return length > 0 && mesh.max_edge_length() > length ? refine_long_edges(mesh, length) : mesh;
}

struct Remeshed {
  RemeshResult result;
  RemeshVerification check;
  QualityMetrics quality;
};

// The remesh of `input` to n vertices as `lrvd remesh -n N --seed S` makes it (remesh_to), checked
// and measured.
inline Remeshed remesh(const SurfaceMesh& input, int n, int seed = 1) {
  Remeshed r;
  r.result = remesh_to(input, n, seed);
  r.check = verify_remesh(input, r.result.dual.positions, r.result.dual.triangles, n);
  r.quality = quality_metrics(input, r.result.dual.positions, r.result.dual.triangles);
  return r;
}

// The first CVT of n uniform samples (`seed`) on `mesh` (the input itself or refined for n: no
// crossing components) and the defects of its dual, before any repair round.
struct FirstCvt {
  CvtResult cvt;
  DualDefects defects;
};

inline FirstCvt first_cvt(const SurfaceMesh& mesh, int n, int seed) {
  FirstCvt r;
  r.cvt = optimize_cvt(mesh, sample_uniform(mesh, n, seed), CvtOptions{});
  r.defects = find_dual_defects(compute_dual(r.cvt.diagram, mesh, r.cvt.samples), r.cvt.diagram, mesh, r.cvt.samples,
                                mesh.is_closed());
  return r;
}

// The remesh of n uniform samples (`seed`) on `mesh` with the vertices left at their samples: the
// CVT's dual, as the fitting and the relaxation get it.
inline RemeshResult unfitted(const SurfaceMesh& reference, const SurfaceMesh& mesh, int n, int seed) {
  RemeshOptions options;
  options.fit = false;
  return remesh_cvt(reference, mesh, sample_uniform(mesh, n, seed), options);
}

}  // namespace lrvd::test
