// Remeshing table (paper Tables 1-2, issue targets): CVT on the LRVD and on the RVD for CGAL's
// models at low vertex counts; validity, quality, distance and time. Writes markdown and JSON.
// Usage: bench_remesh [--quick] [--lrvd-only] [--curvature] [--shape] [--threads N] [--models elk,knot,...]
//                     [--counts 300,516,...] [--out F.md] [--json F]
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <nlohmann/json.hpp>

#include "bench_util.h"
#include "io/mesh_io.h"
#include "metrics/quality.h"
#include "remesh/remesh_pipeline.h"
#include "verification/remesh_check.h"
#include "voronoi/lrvd.h"

using namespace lrvd;
using bench::cpu_seconds;
using bench::split;

int main(int argc, char** argv) {
  std::vector<std::string> models = {"elk", "knot", "ellipsoid", "armadillo"};
  std::vector<int> counts = {300, 516, 1000, 2000, 4000};
  std::string out_path, json_path;
  int threads = 0;  // 0: every core
  CvtDensity density = CvtDensity::Uniform;
  int relax_rounds = 0;  // --shape: what `lrvd remesh --priority shape` runs
  std::vector<DiagramKind> kinds = {DiagramKind::Lrvd, DiagramKind::Rvd};
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--quick")) {
      models = {"elk", "knot"};
      counts = {516, 2000};
    } else if (!std::strcmp(argv[a], "--models") && a + 1 < argc) {
      models = split(argv[++a]);
    } else if (!std::strcmp(argv[a], "--counts") && a + 1 < argc) {
      counts.clear();
      for (const std::string& c : split(argv[++a])) counts.push_back(std::stoi(c));
    } else if (!std::strcmp(argv[a], "--threads") && a + 1 < argc) {
      threads = std::stoi(argv[++a]);
    } else if (!std::strcmp(argv[a], "--lrvd-only")) {
      kinds = {DiagramKind::Lrvd};
    } else if (!std::strcmp(argv[a], "--curvature")) {
      density = CvtDensity::Curvature;
    } else if (!std::strcmp(argv[a], "--shape")) {
      relax_rounds = kShapePriorityRounds;
    } else if (!std::strcmp(argv[a], "--out") && a + 1 < argc) {
      out_path = argv[++a];
    } else if (!std::strcmp(argv[a], "--json") && a + 1 < argc) {
      json_path = argv[++a];
    } else {
      std::fprintf(stderr, "usage: %s [--quick] [--lrvd-only] [--curvature] [--shape] [--threads N] [--models a,b] [--counts n1,n2] [--out F.md] [--json F]\n",
                   argv[0]);
      return 2;
    }
  }
  std::unique_ptr<tbb::global_control> thread_limit;
  if (threads > 0)
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  std::string md =
      "| model | N | diagram | V out | valid | manifold | genus kept | self-int. pairs | Qmin | Qavg | θmin/θmax | "
      "% tri <30° | Hausdorff % | RMS % | repair rounds | time s |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  nlohmann::json rows = nlohmann::json::array();
  for (const std::string& model : models) {
    const SurfaceMesh input = read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/" + model + ".off").mesh;
    for (int n : counts) {
      for (DiagramKind kind : kinds) {
        RemeshOptions options;
        options.cvt.diagram = kind;
        options.cvt.density = density;
        options.relax.rounds = relax_rounds;
        const double cpu_start = cpu_seconds();
        // What `lrvd remesh -n N` does: the same refinement, samples and order.
        const RemeshResult r = remesh_to(input, n, 1, options);
        // The triangles of the mesh the CVT ran on (refined where N is comparable to the input's).
        const int triangles_in = static_cast<int>(r.cvt.diagram.triangle_offsets.size()) - 1;
        const double cpu_s = cpu_seconds() - cpu_start;
        const RemeshVerification check = verify_remesh(input, r.dual.positions, r.dual.triangles, n);
        const QualityMetrics q = quality_metrics(input, r.dual.positions, r.dual.triangles);
        const bool manifold = check.manifold.passed && check.closed.passed && check.oriented.passed;
        md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {:.3f} | {:.3f} | {:.1f}/{:.1f} | {:.2f} | {:.3f} | {:.3f} | {} | {:.2f} |\n",
                          model, n, to_string(kind), r.dual.positions.size(), check.passed ? "yes" : "**no**",
                          manifold ? "yes" : "**no**", check.topology.passed ? "yes" : "**no**",
                          check.self_intersecting_pairs, q.q_min, q.q_avg, q.theta_min, q.theta_max,
                          q.pct_triangles_below_30, q.hausdorff_pct, q.rms_pct, r.repair_rounds, r.time_s);
        rows.push_back({{"model", model}, {"n", n}, {"diagram", to_string(kind)},
                        {"density", density == CvtDensity::Curvature ? "curvature" : "uniform"},
                        {"priority", relax_rounds > 0 ? "shape" : "distance"}, {"triangles_in", triangles_in},
                        {"quality", q.to_json()}, {"verification", check.to_json()}, {"repair_rounds", r.repair_rounds},
                        {"iterations", r.total_iterations}, {"diagram_evaluations", r.diagram_evaluations},
                        {"time_s", r.time_s}, {"cpu_s", cpu_s}});
        std::fprintf(stderr, "%s %d %s: %s\n", model.c_str(), n, to_string(kind).c_str(),
                     check.passed ? "valid" : check.summary().c_str());
      }
    }
  }
  std::printf("%s", md.c_str());
  if (!out_path.empty()) std::ofstream(out_path) << md;
  if (!json_path.empty()) std::ofstream(json_path) << rows.dump(2) << '\n';
  return 0;
}
