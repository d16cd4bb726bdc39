// Vertex fitting alone (remesh/fit.h): the CVT of each (model, N) once without fitting, then the
// fitting, timed (CPU seconds, minimum over --runs), with the shape and two-sided distance before and after.
// Usage: bench_fit [--models elk,knot,...] [--counts 516,1000,...] [--runs R] [--seed S] [--focus-rounds K]
//                  [--focus-fraction F] [--ring-share S] [--samples-per-edge S]
//                  [--input-samples-per-edge S] [--no-balance]
#include <algorithm>
#include <ctime>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "bench_util.h"
#include "io/mesh_io.h"
#include "metrics/quality.h"
#include "remesh/fit.h"
#include "remesh/remesh_pipeline.h"
#include "verification/remesh_check.h"

using namespace lrvd;
using bench::cpu_seconds;
using bench::split;

int main(int argc, char** argv) {
  std::vector<std::string> models = {"elk", "armadillo"};
  std::vector<int> counts = {516, 1000, 4000};
  int runs = 1, seed = 1;
  FitOptions fit_options;
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--models") && a + 1 < argc) {
      models = split(argv[++a]);
    } else if (!std::strcmp(argv[a], "--counts") && a + 1 < argc) {
      counts.clear();
      for (const std::string& c : split(argv[++a])) counts.push_back(std::stoi(c));
    } else if (!std::strcmp(argv[a], "--runs") && a + 1 < argc) {
      runs = std::stoi(argv[++a]);
    } else if (!std::strcmp(argv[a], "--focus-rounds") && a + 1 < argc) {
      fit_options.offsets.focus_rounds = std::stoi(argv[++a]);
    } else if (!std::strcmp(argv[a], "--focus-fraction") && a + 1 < argc) {
      fit_options.offsets.focus_fraction = std::stod(argv[++a]);
    } else if (!std::strcmp(argv[a], "--ring-share") && a + 1 < argc) {
      fit_options.offsets.ring_share = std::stod(argv[++a]);
    } else if (!std::strcmp(argv[a], "--samples-per-edge") && a + 1 < argc) {
      fit_options.offsets.samples_per_edge = std::stod(argv[++a]);
    } else if (!std::strcmp(argv[a], "--input-samples-per-edge") && a + 1 < argc) {
      fit_options.offsets.input_samples_per_edge = std::stod(argv[++a]);
    } else if (!std::strcmp(argv[a], "--seed") && a + 1 < argc) {
      seed = std::stoi(argv[++a]);
    } else if (!std::strcmp(argv[a], "--no-balance")) {
      fit_options.balance = false;
    } else {
      std::fprintf(stderr, "usage: %s [--models a,b] [--counts n1,n2] [--runs R] [--seed S] [--focus-rounds K] [--focus-fraction F] [--ring-share S]\n"
                   "       [--samples-per-edge S] [--input-samples-per-edge S] [--no-balance]\n", argv[0]);
      return 2;
    }
  }
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  std::printf("| model | N | valid | Qmin CVT → fit | Qavg | θmin | Hausdorff %% | RMS %% | sampled max %% before → after | fit CPU s |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& model : models) {
    const SurfaceMesh input = read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/" + model + ".off").mesh;
    const double diagonal = input.bounding_box().diagonal();
    for (int n : counts) {
      RemeshOptions options;
      options.fit = false;
      options.untangle = false;
      // As `lrvd remesh` makes it, with the vertices left at the samples; `mesh` is the surface it ran on.
      RemeshStart from;
      from.n = n;
      from.seed = seed;
      const RemeshResult cvt = remesh_from(input, from, options);
      const SurfaceMesh& mesh = *from.mesh;
      DualMesh fitted;
      FitResult fit;
      double best = 1e30;
      for (int r = 0; r < runs; ++r) {
        fitted = cvt.dual;
        const double start = cpu_seconds();
        fit = fit_to_surface(cvt.cvt.diagram, mesh, fitted, fit_options);
        best = std::min(best, cpu_seconds() - start);
      }
      const QualityMetrics before = shape_metrics(cvt.dual.positions, cvt.dual.triangles);
      const QualityMetrics q = quality_metrics(input, fitted.positions, fitted.triangles);
      const RemeshVerification check = verify_remesh(input, fitted.positions, fitted.triangles, n);
      std::printf("| %s | %d | %s | %.3f → %.3f | %.3f | %.1f | %.3f | %.3f | %.3f → %.3f | %.3f |\n", model.c_str(), n,
                  check.passed ? "yes" : "**no**", before.q_min, q.q_min, q.q_avg, q.theta_min, q.hausdorff_pct,
                  q.rms_pct, 100 * fit.offsets.max_before / diagonal, 100 * fit.offsets.max_after / diagonal, best);
      std::fflush(stdout);
    }
  }
  return 0;
}
