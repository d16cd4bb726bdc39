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

namespace {

struct Arguments {
  std::vector<std::string> models = {"elk", "knot", "ellipsoid", "armadillo"};
  std::vector<int> counts = {300, 516, 1000, 2000, 4000};
  std::string out_path, json_path;
  int threads = 0;  // 0: every core
  CvtDensity density = CvtDensity::Uniform;
  int relax_rounds = 0;  // --shape: what `lrvd remesh --priority shape` runs
  std::vector<DiagramKind> kinds = {DiagramKind::Lrvd, DiagramKind::Rvd};
};

// False (after the usage line) on an argument it does not know.
bool parse_arguments(int argc, char** argv, Arguments& args) {
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--quick")) {
      args.models = {"elk", "knot"};
      args.counts = {516, 2000};
    } else if (!std::strcmp(argv[a], "--models") && a + 1 < argc) {
      args.models = split(argv[++a]);
    } else if (!std::strcmp(argv[a], "--counts") && a + 1 < argc) {
      args.counts.clear();
      for (const std::string& c : split(argv[++a])) args.counts.push_back(std::stoi(c));
    } else if (!std::strcmp(argv[a], "--threads") && a + 1 < argc) {
      args.threads = std::stoi(argv[++a]);
    } else if (!std::strcmp(argv[a], "--lrvd-only")) {
      args.kinds = {DiagramKind::Lrvd};
    } else if (!std::strcmp(argv[a], "--curvature")) {
      args.density = CvtDensity::Curvature;
    } else if (!std::strcmp(argv[a], "--shape")) {
      args.relax_rounds = kShapePriorityRounds;
    } else if (!std::strcmp(argv[a], "--out") && a + 1 < argc) {
      args.out_path = argv[++a];
    } else if (!std::strcmp(argv[a], "--json") && a + 1 < argc) {
      args.json_path = argv[++a];
    } else {
      std::fprintf(stderr, "usage: %s [--quick] [--lrvd-only] [--curvature] [--shape] [--threads N] [--models a,b] [--counts n1,n2] [--out F.md] [--json F]\n",
                   argv[0]);
      return false;
    }
  }
  return true;
}

// One remesh of `input` to n vertices on a diagram of `kind`, as a row of the table and of the JSON.
void remesh_row(const Arguments& args, const std::string& model, const SurfaceMesh& input, int n, DiagramKind kind,
                std::string& md, nlohmann::json& rows) {
  RemeshOptions options;
  options.cvt.diagram = kind;
  options.cvt.density = args.density;
  options.relax.rounds = args.relax_rounds;
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
                  {"density", args.density == CvtDensity::Curvature ? "curvature" : "uniform"},
                  {"priority", args.relax_rounds > 0 ? "shape" : "distance"}, {"triangles_in", triangles_in},
                  {"quality", q.to_json()}, {"verification", check.to_json()}, {"repair_rounds", r.repair_rounds},
                  {"iterations", r.total_iterations}, {"diagram_evaluations", r.diagram_evaluations},
                  {"time_s", r.time_s}, {"cpu_s", cpu_s}});
  std::fprintf(stderr, "%s %d %s: %s\n", model.c_str(), n, to_string(kind).c_str(),
               check.passed ? "valid" : check.summary().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  if (!parse_arguments(argc, argv, args)) return 2;
  const auto thread_limit = bench::limit_threads(args.threads);
  std::string md =
      "| model | N | diagram | V out | valid | manifold | genus kept | self-int. pairs | Qmin | Qavg | θmin/θmax | "
      "% tri <30° | Hausdorff % | RMS % | repair rounds | time s |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  nlohmann::json rows = nlohmann::json::array();
  for (const std::string& model : args.models) {
    const SurfaceMesh input = read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/" + model + ".off").mesh;
    for (int n : args.counts)
      for (DiagramKind kind : args.kinds) remesh_row(args, model, input, n, kind, md, rows);
  }
  std::printf("%s", md.c_str());
  if (!args.out_path.empty()) std::ofstream(args.out_path) << md;
  if (!args.json_path.empty()) std::ofstream(args.json_path) << rows.dump(2) << '\n';
  return 0;
}
