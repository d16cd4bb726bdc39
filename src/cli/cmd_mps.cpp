// `lrvd mps`: maximal Poisson-disk sampling (paper §4.2), its independent verification on a
// fresh LRPD, and optionally the LRRT remesh of the samples, checked like any remesh.
#include "cli/cmd_mps.h"

#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "cli/common.h"
#include "common/error.h"
#include "diagram/dual.h"
#include "io/mesh_writers.h"
#include "metrics/quality.h"
#include "mps/mps.h"
#include "predicates/predicates.h"
#include "report/lrrt_repair.h"
#include "report/mps_report.h"
#include "verification/mps_check.h"
#include "verification/remesh_check.h"
#include "voronoi/lrvd.h"

namespace lrvd::cli {

namespace {

struct MpsCommandOptions {
  std::string mesh_path;
  ReadOptions read;  //!< --repair, --weld, --fill-holes
  MpsSettings settings;  //!< the `*_given` flags set by the parser's callbacks below
  std::string output, remesh, report;
  bool features_flag = false;  //!< --features, accepted: sampling the features first is the default
};

// One line on the feature lines the input has and whether they were sampled first, e.g.
// "features: 12 edges where the surface turns by more than 60 degrees, 8 corners: sampled first
// (98 samples; --no-features turns this off)"; "" for a mesh without any (sampled as with --no-features).
std::string features_line(const MpsRun& run) {
  const MpsResult& r = run.result;
  if (r.feature_edges == 0) return "";
  const int sharp = r.feature_edges - r.boundary_edges;
  std::string edges;
  if (sharp > 0)
    edges = fmt::format("{} where the surface turns by more than {:g} degrees", counted(sharp, "edge", "edges"),
                        run.options.feature_angle);
  if (r.boundary_edges > 0)
    edges += (edges.empty() ? "" : " and ") + counted(r.boundary_edges, "boundary edge", "boundary edges");
  const std::string found = fmt::format("features: {}, {}", edges, counted(r.feature_corners, "corner", "corners"));
  if (!run.options.sample_features) return found + ": not sampled first (--no-features)";
  return found + fmt::format(": sampled first ({}; --no-features turns this off)",
                             counted(r.feature_samples, "sample", "samples"));
}

int run_mps_command(const MpsCommandOptions& opt) {
  check_mps_settings(opt.settings);
  if (opt.settings.keep_radius && opt.remesh.empty()) throw InputError("--keep-radius applies to --remesh");
  // The samples are text, 'x y z r^2' per line: not a mesh file.
  check_outputs({{opt.output, "-o", {}, kMeshReadExtensions},
                 {opt.remesh, "--remesh", kMeshWriteExtensions},
                 {opt.report, "--report", {}, kMeshReadExtensions}},
                {{opt.mesh_path, "the input mesh"}});
  const LoadedMesh loaded = read_mesh(opt.mesh_path, opt.read);
  print_repair(loaded.repair, opt.read);

  MpsRun run = run_mps(loaded, opt.read.repair, opt.settings, opt.mesh_path, opt.output, !opt.remesh.empty(), opt.remesh,
                       progress, [&](const Samples& samples) { write_xyz(opt.output, samples.positions, samples.weights); },
                       [&](const DualMesh& dual) { write_mesh(opt.remesh, dual.positions, dual.triangles); });
  const MpsResult& result = run.result;
  const Samples& samples = result.samples;
  const MpsVerification& check = run.check;
  const bool maximal = run.maximal, min_distance_ok = run.min_distance_ok;
  nlohmann::json& report = run.report;
  bool remesh_ok = true;
  if (run.lrrt) {
    const DualMesh& dual = run.dual;
    remesh_ok = run.remesh_check.passed;
    if (run.smaller_disks.rounds > 0)
      std::printf("LRRT: smaller disks where it had defects, %s of the radius halved round them (down to %.4g on "
                  "%s), %.3f s\n",
                  counted(run.smaller_disks.rounds, "round", "rounds").c_str(), run.result.radius / run.result.scale,
                  counted(run.smaller_disks.vertices, "vertex", "vertices").c_str(), run.smaller_disks.time_s);
    std::printf("remesh (LRRT): %s, %s -> %s; verification: %s\n",
                counted(dual.positions.size(), "vertex", "vertices").c_str(),
                counted(dual.triangles.size(), "triangle", "triangles").c_str(), opt.remesh.c_str(),
                remesh_ok ? "passed" : "FAILED");
    if (!remesh_ok) std::fputs(run.remesh_check.summary().c_str(), stdout);
    if (!remesh_ok) std::printf("%s\n", run.lrrt_refusal.c_str());
    print_quality(run.measurable ? &run.quality : nullptr, true);
  }
  report["predicates"] = predicates_json();
  if (!opt.report.empty()) write_report(opt.report, report, {opt.output, opt.remesh});

  std::printf("mps (%s, r = %g): %s (%d by dart throwing, %d in gaps), %.3f s "
              "(init %.3f, darts %.3f, gaps %.3f) -> %s\n",
              opt.settings.adaptive ? "adaptive" : "uniform", opt.settings.radius, counted(samples.size(), "sample", "samples").c_str(),
              result.dart_samples, result.gap_samples,
              result.time_s.total, result.time_s.init, result.time_s.dart_throwing, result.time_s.gap_filling,
              opt.output.c_str());
  const std::string ratio = std::isnan(check.min_distance_ratio)
                                ? std::string(check.close_pairs_not_local > 0
                                                  ? "no two samples local to each other, the only kind it bounds"
                                                  : "no two samples near each other")
                                : fmt::format("smallest ratio {:.4f}", check.min_distance_ratio);
  const std::string features = features_line(run);
  if (!features.empty()) std::printf("%s\n", features.c_str());
  std::printf("maximal: %s, minimum distance: %s (%s)\n", maximal ? "yes" : "NO", min_distance_ok ? "yes" : "NO",
              ratio.c_str());
  // Closer pairs the disk condition does not cover (docs/algorithms/mps.md, "Conflict rule"): said, not hidden.
  if (check.facing_cut)
    std::printf("  conflict rule: --conflict close-across-turns: %s of samples closer than their radius that the "
                "paper's rule calls local %s let through\n",
                counted(check.close_pairs_local_past_facing_cut, "pair", "pairs").c_str(),
                check.close_pairs_local_past_facing_cut == 1 ? "is" : "are");
  if (check.close_pairs_not_local > 0)
    std::printf("  %s of samples closer than their radius %s not local to each other (another component, "
                "the other side of a sheet, or %s): allowed\n",
                counted(check.close_pairs_not_local, "pair", "pairs").c_str(),
                check.close_pairs_not_local == 1 ? "is" : "are",
                check.facing_cut ? "past a turn of the surface of 90 degrees or more"
                                 : "beyond what their balls reach along the surface");
  if (check.polygons_outside_own_ball > 0)
    std::printf("  %lld LRPD polygons reach outside their cell's ball; in %lld of their triangles disks of samples "
                "that are no LRPD candidate there cover them\n",
                static_cast<long long>(check.polygons_outside_own_ball),
                static_cast<long long>(check.triangles_covered_by_other_disks));
  if (!check.passed) std::fputs(check.summary().c_str(), stdout);
  return maximal && min_distance_ok && remesh_ok ? kOk : kCheckFailed;
}

}  // namespace

Action add_mps_command(CLI::App& app) {
  auto opt = std::make_shared<MpsCommandOptions>();
  CLI::App* cmd = app.add_subcommand("mps", "Maximal Poisson-disk sampling with LRPD gap detection, checked; optional LRRT remesh");
  cmd->add_option("mesh", opt->mesh_path, "Input mesh (.off, .obj, .ply, .stl)")->required()->check(path_validator());
  cmd->add_option("--radius", opt->settings.radius,
                  "Disk radius r (r_min with --adaptive), relative to the longest bounding-box side "
                  "(the model normalised into the unit cube)")
      ->required();
  cmd->add_flag("--adaptive", opt->settings.adaptive, "Radius from curvature, never below --radius");
  cmd->add_option("--max-radius-ratio", opt->settings.max_radius_ratio, "Adaptive: largest radius / --radius")
      ->check(CLI::Range(1.0, 100.0))
      ->each([opt](const std::string&) { opt->settings.max_radius_ratio_given = true; })
      ->capture_default_str();
  cmd->add_option("--seed", opt->settings.seed, "Seed of the darts")->check(seed_validator())->capture_default_str();
  cmd->add_option("--gap-update", opt->settings.gap_update,
                  "local: one LRPD, gaps clipped as disks are added (default); lrpd: a new LRPD after every round "
                  "of darts (the paper's loop)")
      ->check(CLI::IsMember({"local", "lrpd"}))
      ->capture_default_str();
  cmd->add_option("--conflict", opt->settings.conflict,
                  "reach (default, the paper's rule): samples whose balls' regions (grown over every "
                  "edge-adjacent triangle the ball meets) reach each other keep r apart; close-across-turns: "
                  "regions stop where the surface turns by 90 degrees or more, so samples may sit closer than r "
                  "across sharp edges and round thin rims (how many pairs is said; 'facing' is the old spelling)")
      ->check(CLI::IsMember({"reach", "close-across-turns", "facing"}))
      ->capture_default_str();
  cmd->add_option("--split-to", opt->settings.split_to,
                  "Split edges longer than --split-factor times the radius at their ends (field, default) or "
                  "longer than r_min everywhere (rmin: the paper's rule, 3-9 times the triangles)")
      ->check(CLI::IsMember({"field", "rmin"}))
      ->capture_default_str();
  cmd->add_option("--split-factor", opt->settings.split_factor,
                  "With --split-to field: edges are split until no longer than this times the radius")
      ->check(CLI::Range(1.0, 64.0))
      ->each([opt](const std::string&) { opt->settings.split_factor_given = true; })
      ->capture_default_str();
  CLI::Option* features = cmd->add_flag("--features", opt->features_flag,
                                        "Samples on the corners and feature lines first (the boundary, and edges "
                                        "sharper than --feature-angle) when the mesh has any: the default");
  cmd->add_flag_callback("--no-features", [opt]() { opt->settings.features = false; },
                         "Darts everywhere, none placed on the feature lines first (the paper's sampling; the "
                         "LRRT may then cut sharp edges and boundary corners)")
      ->excludes(features);
  cmd->add_option("--feature-angle", opt->settings.feature_angle,
                  "An edge is a feature when its triangles' normals are more than this many degrees apart")
      ->check(CLI::Range(1.0, 179.0))
      ->each([opt](const std::string&) { opt->settings.feature_angle_given = true; })
      ->capture_default_str();
  add_repair_options(cmd, opt->read);
  cmd->add_option("-o,--output", opt->output, "Samples as 'x y z r^2' lines (.xyz)")->required()->check(path_validator());
  cmd->add_option("--remesh", opt->remesh, "Also write the LRRT of the samples (.off, .obj, .ply) and check it")
      ->check(path_validator());
  cmd->add_flag("--keep-radius", opt->settings.keep_radius,
                fmt::format("With --remesh: keep the radius where the LRRT has defects (by default it is halved round "
                            "them and the surface sampled again, up to {} times, until the LRRT passes its checks)",
                            kMaxLrrtRounds));
  cmd->add_option("--report", opt->report, "Write a JSON report")->check(path_validator());
  cmd->add_flag("--exact", opt->settings.exact, "Decide every vertex of the maximality check with rational arithmetic");
  return [opt]() { return run_mps_command(*opt); };
}

}  // namespace lrvd::cli
