// Maximal Poisson-disk sampling timings (paper Table 3): uniform r = 0.005 and adaptive
// r_min = 0.004 in the unit cube, init / dart throwing / gap filling / total seconds and sample
// counts per model, then the independent checks (minimum distance, maximality on a fresh LRPD).
//
// Usage: bench_mps [--quick] [--no-verify] [--remesh] [--threads N] [--json FILE] [--gap-update local|lrpd]
//                  [--split-to field|rmin] [--split-factor F] [MESH ...]
// --remesh also checks the LRRT of the samples (verify_remesh against the input); --split-to rmin
// splits the edges to r_min, as the paper does (default: to F = 2 times the radius field).
// Without meshes: CGAL's armadillo, ChineseDragon-10kv and bunny00 (LRVD_CGAL_DATA_DIR), then the
// Table 3 models of /work/shared/data/meshes when present (feline, vaselion, dragon_100k,
// gargoyle_100k). --quick runs uniform only with r = 0.01.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_util.h"
#include "diagram/dual.h"
#include "io/mesh_io.h"
#include "mps/mps.h"
#include "verification/mps_check.h"
#include "verification/remesh_check.h"
#include "voronoi/lrvd.h"

namespace {

std::string fmt_violations(const lrvd::RemeshVerification& v) {
  return "INVALID(unused " + std::to_string(v.vertex_count.violations) + ", non-manifold " +
         std::to_string(v.manifold.violations) + ", self-intersections " + std::to_string(v.self_intersecting_pairs) + ")";
}

struct Row {
  std::string model, mode;
  double r;
  lrvd::MpsResult result;
  bool verified = false, maximal = false, min_distance = false;
  std::string remesh = "-";
  double verify_s = 0;
};

struct Arguments {
  bool quick = false, verify = true, remesh = false;
  std::string json_path;
  lrvd::MpsGapUpdate update = lrvd::MpsGapUpdate::Local;
  lrvd::MpsRefinement refinement = lrvd::MpsRefinement::RadiusField;
  double split_factor = lrvd::MpsOptions{}.split_factor;
  std::vector<std::string> meshes;
  int threads = 0;  // 0: every core
};

// -1 when the run goes on; otherwise the exit status (after the usage line).
int parse_arguments(int argc, char** argv, Arguments& args) {
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--quick") args.quick = true;
    else if (arg == "--no-verify") args.verify = false;
    else if (arg == "--remesh") args.remesh = true;
    else if (arg == "--json" && a + 1 < argc) args.json_path = argv[++a];
    else if (arg == "--threads" && a + 1 < argc) args.threads = std::stoi(argv[++a]);
    else if (arg == "--gap-update" && a + 1 < argc) args.update = std::string(argv[++a]) == "lrpd" ? lrvd::MpsGapUpdate::Lrpd : lrvd::MpsGapUpdate::Local;
    else if (arg == "--split-to" && a + 1 < argc)
      args.refinement = std::string(argv[++a]) == "rmin" ? lrvd::MpsRefinement::MinRadius : lrvd::MpsRefinement::RadiusField;
    else if (arg == "--split-factor" && a + 1 < argc) args.split_factor = std::stod(argv[++a]);
    else if (arg.rfind("--", 0) == 0) {  // an option it does not know (or --help), not a mesh
      std::fprintf(stderr, "usage: %s [--quick] [--no-verify] [--remesh] [--threads N] [--json FILE] "
                           "[--gap-update local|lrpd] [--split-to field|rmin] [--split-factor F] [MESH ...]\n", argv[0]);
      return arg == "--help" ? 0 : 2;
    } else args.meshes.push_back(arg);
  }
  if (args.meshes.empty()) {
    for (const char* name : {"armadillo.off", "ChineseDragon-10kv.off", "bunny00.off"})
      args.meshes.push_back(std::string(LRVD_CGAL_DATA_DIR) + "/" + name);
    for (const char* name : {"feline.off", "vaselion.off", "dragon_100k.off", "gargoyle_100k.off"}) {
      const std::string path = std::string("/work/shared/data/meshes/") + name;
      if (std::filesystem::exists(path)) args.meshes.push_back(path);
    }
  }
  return -1;
}

// The independent checks of row.result (minimum distance, maximality on a fresh LRPD; with
// --remesh the LRRT too): what the row's checks column says.
std::string check_row(const Arguments& args, const lrvd::SurfaceMesh& mesh, Row& row) {
  const lrvd::MpsResult& r = row.result;
  lrvd::LrvdOptions lrpd_options;
  lrpd_options.weighted = true;
  const lrvd::Diagram lrpd = lrvd::compute_lrvd(r.mesh, r.samples, lrpd_options);
  const lrvd::MpsVerification v = lrvd::verify_mps(r.mesh, r.samples, lrpd);
  row.verified = true;
  row.maximal = v.maximal.passed && v.diagram_covers.passed;
  row.min_distance = v.min_distance.passed;
  row.verify_s = v.time_s + lrpd.stats.time_s;
  if (!v.passed) {
    std::fputs(v.summary().c_str(), stderr);
    std::fprintf(stderr, "gaps_closed %d, first LRPD gap pieces %d, dropped %d, clamped %d\n", r.gaps_closed,
                 r.gap_pieces, r.dropped_gap_pieces, r.clamped_radii);
  }
  std::string checks = std::string(row.maximal ? "maximal" : "NOT-MAXIMAL") + "," + (row.min_distance ? "min-dist" : "MIN-DIST-FAIL");
  if (args.remesh) {
    const lrvd::DualMesh dual = lrvd::compute_dual(lrpd, r.mesh, r.samples);
    const lrvd::RemeshVerification rv = lrvd::verify_remesh(mesh, dual.positions, dual.triangles, r.samples.size());
    row.remesh = rv.passed ? "valid" : fmt_violations(rv);
    checks += ",remesh " + row.remesh;
  }
  return checks;
}

nlohmann::json row_json(const Arguments& args, const lrvd::SurfaceMesh& mesh, const Row& row) {
  const lrvd::MpsResult& r = row.result;
  return {{"model", row.model},
          {"mode", row.mode},
          {"r", row.r},
          {"samples", r.samples.size()},
          {"dart_samples", r.dart_samples},
          {"gap_samples", r.gap_samples},
          {"dust_samples", r.dust_samples},
          {"split_factor", args.refinement == lrvd::MpsRefinement::MinRadius ? 1.0 : args.split_factor},
          {"darts", r.darts},
          {"lrpd_evaluations", r.lrpd_evaluations},
          {"refined_triangles", r.mesh.triangle_count()},
          {"input_triangles", mesh.triangle_count()},
          {"time_s", {{"init", r.time_s.init}, {"dart_throwing", r.time_s.dart_throwing},
                      {"gap_filling", r.time_s.gap_filling}, {"total", r.time_s.total}}},
          {"verify_s", row.verify_s},
          {"maximal", row.maximal},
          {"remesh", row.remesh},
          {"min_distance_ok", row.min_distance}};
}

// The sampling of `mesh` (uniform, or adaptive), checked unless --no-verify: a line on the console
// and a row of the JSON.
void sample_row(const Arguments& args, const lrvd::SurfaceMesh& mesh, const std::string& model, bool adaptive,
                nlohmann::json& out) {
  Row row;
  row.model = model;
  row.mode = adaptive ? "adaptive" : "uniform";
  row.r = args.quick ? 0.01 : (adaptive ? 0.004 : 0.005);
  lrvd::MpsOptions options;
  options.radius = row.r;
  options.adaptive = adaptive;
  options.gap_update = args.update;
  options.refinement = args.refinement;
  options.split_factor = args.split_factor;
  row.result = lrvd::maximal_poisson_disk_sampling(mesh, options);
  const lrvd::MpsResult& r = row.result;
  const std::string checks = args.verify ? check_row(args, mesh, row) : "-";
  std::printf("%-22s %-8s %6.3f %8d %7.2f %7.2f %7.2f %7.2f %9.2f %s (darts %lld, gap samples %d, LRPDs %d, triangles %d)\n",
              model.c_str(), row.mode.c_str(), row.r, r.samples.size(), r.time_s.init, r.time_s.dart_throwing,
              r.time_s.gap_filling, r.time_s.total, row.verify_s, checks.c_str(), static_cast<long long>(r.darts),
              r.gap_samples, r.lrpd_evaluations, r.mesh.triangle_count());
  std::fflush(stdout);
  out.push_back(row_json(args, mesh, row));
}

}  // namespace

int main(int argc, char** argv) {
  Arguments args;
  if (const int status = parse_arguments(argc, argv, args); status >= 0) return status;
  const auto thread_limit = lrvd::bench::limit_threads(args.threads);
  nlohmann::json out = nlohmann::json::array();
  std::printf("%-22s %-8s %6s %8s %7s %7s %7s %7s %9s %s\n", "model", "mode", "r", "#V", "t_init", "t_dt", "t_gap",
              "t_total", "verify_s", "checks");
  for (const std::string& path : args.meshes) {
    lrvd::SurfaceMesh mesh;
    try {
      mesh = lrvd::read_mesh(path, lrvd::ReadOptions{true}).mesh;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
      continue;
    }
    const std::string model = std::filesystem::path(path).stem().string();
    for (int adaptive = 0; adaptive < (args.quick ? 1 : 2); ++adaptive) sample_row(args, mesh, model, adaptive, out);
  }
  if (!args.json_path.empty()) {
    std::FILE* f = std::fopen(args.json_path.c_str(), "w");
    if (f) {
      std::fputs(out.dump(2).c_str(), f);
      std::fclose(f);
    }
  }
  return 0;
}
