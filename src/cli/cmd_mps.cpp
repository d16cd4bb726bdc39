// `lrvd mps`: maximal Poisson-disk sampling (paper §4.2), its independent verification on a
// fresh LRPD, and optionally the LRRT remesh of the samples, checked like any remesh.
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/common.h"
#include "common/error.h"
#include "metrics/quality.h"
#include "predicates/predicates.h"
#include "remesh/mps.h"
#include "verification/mps_check.h"
#include "verification/remesh_check.h"
#include "voronoi/dual.h"
#include "voronoi/lrvd.h"

namespace lrvd::cli {

namespace {


struct MpsCommandOptions {
  std::string mesh_path;
  ReadOptions read;  //!< --repair, --weld, --fill-holes
  double radius = 0;
  bool adaptive = false;
  double max_radius_ratio = MpsOptions{}.max_radius_ratio;
  bool max_radius_ratio_given = false;  // set by the parser's callback below
  std::uint64_t seed = 1;
  std::string gap_update = "local";
  std::string split_to = "field";
  double split_factor = MpsOptions{}.split_factor;
  bool split_factor_given = false;  // set by the parser's callback below
  std::string output, remesh, report;
  bool exact = false;
  bool features = false;
  double feature_angle = MpsOptions{}.feature_angle;
  bool feature_angle_given = false;  // set by the parser's callback below
};

int run_mps(const MpsCommandOptions& opt) {
  // A radius of the model's size already leaves one sample per sheet; far beyond it, squared
  // distances overflow.
  if (!(opt.radius > 0) || !(opt.radius <= kMaxMpsRadius))
    throw InputError(fmt::format("--radius must be a positive number up to {:g} (relative to the longest bounding-box "
                                 "side), got {}",
                                 kMaxMpsRadius, opt.radius));
  if (opt.max_radius_ratio_given && !opt.adaptive) throw InputError("--max-radius-ratio applies to --adaptive");
  // The samples are text, 'x y z r^2' per line: not a mesh file.
  check_outputs({{opt.output, "-o", {}, kMeshReadExtensions},
                 {opt.remesh, "--remesh", kMeshWriteExtensions},
                 {opt.report, "--report", {}, kMeshReadExtensions}},
                {{opt.mesh_path, "the input mesh"}});
  const LoadedMesh loaded = read_mesh(opt.mesh_path, opt.read);
  const SurfaceMesh& input = loaded.mesh;
  print_repair(loaded.repair, opt.read);

  MpsOptions options;
  options.radius = opt.radius;
  options.adaptive = opt.adaptive;
  options.max_radius_ratio = opt.max_radius_ratio;
  options.seed = opt.seed;
  options.gap_update = opt.gap_update == "lrpd" ? MpsGapUpdate::Lrpd : MpsGapUpdate::Local;
  options.refinement = opt.split_to == "rmin" ? MpsRefinement::MinRadius : MpsRefinement::RadiusField;
  if (opt.split_factor_given && options.refinement == MpsRefinement::MinRadius)
    throw InputError("--split-factor applies to --split-to field; --split-to rmin splits to r_min");
  options.split_factor = opt.split_factor;
  if (opt.feature_angle_given && !opt.features) throw InputError("--feature-angle applies to --features");
  options.sample_features = opt.features;
  options.feature_angle = opt.feature_angle;
  options.on_progress = [](const std::string& message) { progress(message); };
  reset_predicate_stats();
  // What the sampler refuses is about this mesh (its refinement, its size for the radius): the
  // message names the file, as the loader's do.
  const MpsResult result = [&] {
    try {
      return maximal_poisson_disk_sampling(input, options);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", opt.mesh_path, e.what()));
    }
  }();
  const Samples& samples = result.samples;
  write_xyz(opt.output, samples.positions, samples.weights);

  // The checks start from the samples alone: a new LRPD, new local regions.
  progress(fmt::format("verifying {} samples on a fresh LRPD", samples.size()));
  MpsVerifyOptions verify_options;
  verify_options.exact_maximality = opt.exact;
  Diagram lrpd;
  const MpsVerification check = verify_mps(result.mesh, samples, verify_options, &lrpd);
  const bool maximal = check.maximal.passed && check.diagram_covers.passed;
  const bool min_distance_ok = check.min_distance.passed;

  nlohmann::json report;
  report["input"] = {{"path", opt.mesh_path},
                     {"vertices", input.vertex_count()},
                     {"triangles", input.triangle_count()},
                     {"area", input.area()},
                     {"components", input.component_count()},
                     {"closed", input.is_closed()},
                     {"euler_characteristic", input.euler_characteristic()},
                     {"longest_bbox_side", result.scale}};
  if (opt.read.repair) report["input"]["repair_changes"] = repair_changes(loaded.repair);
  if (!loaded.repair.notes.empty()) report["input"]["repair"] = loaded.repair.notes;
  report["refined"] = {{"triangles", result.mesh.triangle_count()},
                       {"max_edge_length", result.mesh.max_edge_length()},
                       {"rule", options.refinement == MpsRefinement::MinRadius ? "r_min" : "radius field"},
                       {"split_factor", options.refinement == MpsRefinement::MinRadius ? 1.0 : options.split_factor}};
  report["radius"] = {{"relative", opt.radius},
                      {"absolute", result.radius},
                      {"max_absolute", result.max_radius},
                      {"adaptive", opt.adaptive}};
  report["seed"] = opt.seed;
  report["gap_update"] = opt.gap_update;
  report["samples"] = samples.size();
  report["features"] = opt.features ? nlohmann::json{{"angle_deg", opt.feature_angle}, {"samples", result.feature_samples}}
                                     : nlohmann::json(nullptr);
  report["dart_samples"] = result.dart_samples;
  report["gap_samples"] = result.gap_samples;
  report["darts"] = result.darts;
  report["lrpd_evaluations"] = result.lrpd_evaluations;
  report["part_lrpd_triangles"] = result.part_lrpd_triangles;
  report["gap_pieces"] = result.gap_pieces;
  report["dropped_gap_pieces"] = result.dropped_gap_pieces;
  report["dust_samples"] = result.dust_samples;
  report["clamped_radii"] = result.clamped_radii;
  report["power_cell_exceptions"] = result.power_cell_exceptions;
  report["gaps_closed"] = result.gaps_closed;
  report["maximal"] = maximal;
  report["min_distance_ok"] = min_distance_ok;
  report["mps_verification"] = check.to_json();
  report["time_s"] = {{"init", result.time_s.init},
                      {"dart_throwing", result.time_s.dart_throwing},
                      {"gap_filling", result.time_s.gap_filling},
                      {"total", result.time_s.total},
                      {"verification_lrpd", lrpd.stats.time_s},
                      {"verification", check.time_s}};
  report["output"] = opt.output;

  bool remesh_ok = true;
  if (!opt.remesh.empty()) {
    progress("remeshing: the LRRT of the samples");
    const DualMesh dual = compute_dual(lrpd, result.mesh, samples);
    write_mesh(opt.remesh, dual.positions, dual.triangles);
    const RemeshVerification remesh_check = verify_remesh(input, dual.positions, dual.triangles, samples.size());
    // An LRRT without triangles (a sample or two on the whole surface) fails the checks and has
    // nothing to measure.
    const bool measurable = !dual.triangles.empty();
    const QualityMetrics quality =
        measurable ? quality_metrics(input, dual.positions, dual.triangles) : QualityMetrics{};
    report["quality"] = measurable ? remesh_quality_json(quality, remesh_check) : nlohmann::json(nullptr);
    report["verification"] = remesh_check.to_json();
    report["remesh"] = {{"path", opt.remesh}, {"vertices", dual.positions.size()}, {"triangles", dual.triangles.size()}};
    remesh_ok = remesh_check.passed;
    std::printf("remesh (LRRT): %s, %s -> %s; verification: %s\n",
                counted(dual.positions.size(), "vertex", "vertices").c_str(),
                counted(dual.triangles.size(), "triangle", "triangles").c_str(), opt.remesh.c_str(),
                remesh_ok ? "passed" : "FAILED");
    if (!remesh_ok) std::fputs(remesh_check.summary().c_str(), stdout);
    print_quality(measurable ? &quality : nullptr, true);
  }
  report["predicates"] = predicates_json();
  if (!opt.report.empty()) write_report(opt.report, report, {opt.output, opt.remesh});

  std::printf("mps (%s, r = %g): %s (%d by dart throwing, %d in gaps), %.3f s "
              "(init %.3f, darts %.3f, gaps %.3f) -> %s\n",
              opt.adaptive ? "adaptive" : "uniform", opt.radius, counted(samples.size(), "sample", "samples").c_str(),
              result.dart_samples, result.gap_samples,
              result.time_s.total, result.time_s.init, result.time_s.dart_throwing, result.time_s.gap_filling,
              opt.output.c_str());
  const std::string ratio = std::isnan(check.min_distance_ratio)
                                ? std::string(check.close_pairs_not_local > 0
                                                  ? "no two samples local to each other, the only kind it bounds"
                                                  : "no two samples near each other")
                                : fmt::format("smallest ratio {:.4f}", check.min_distance_ratio);
  std::printf("maximal: %s, minimum distance: %s (%s)\n", maximal ? "yes" : "NO", min_distance_ok ? "yes" : "NO",
              ratio.c_str());
  // Closer pairs the disk condition does not cover (docs/algorithms/mps.md, "Conflict rule"): said, not hidden.
  if (check.close_pairs_not_local > 0)
    std::printf("  %s of samples closer than their radius %s not local to each other (another component, "
                "the other side of a sheet, or past a turn of the surface of 90 degrees or more): allowed\n",
                counted(check.close_pairs_not_local, "pair", "pairs").c_str(),
                check.close_pairs_not_local == 1 ? "is" : "are");
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
  cmd->add_option("--radius", opt->radius,
                  "Disk radius r (r_min with --adaptive), relative to the longest bounding-box side "
                  "(the model normalised into the unit cube)")
      ->required();
  cmd->add_flag("--adaptive", opt->adaptive, "Radius from curvature, never below --radius");
  cmd->add_option("--max-radius-ratio", opt->max_radius_ratio, "Adaptive: largest radius / --radius")
      ->check(CLI::Range(1.0, 100.0))
      ->each([opt](const std::string&) { opt->max_radius_ratio_given = true; })
      ->capture_default_str();
  cmd->add_option("--seed", opt->seed, "Seed of the darts")->check(seed_validator())->capture_default_str();
  cmd->add_option("--gap-update", opt->gap_update,
                  "local: one LRPD, gaps clipped as disks are added (default); lrpd: a new LRPD after every round "
                  "of darts (the paper's loop)")
      ->check(CLI::IsMember({"local", "lrpd"}))
      ->capture_default_str();
  cmd->add_option("--split-to", opt->split_to,
                  "Split edges longer than --split-factor times the radius at their ends (field, default) or "
                  "longer than r_min everywhere (rmin: the paper's rule, 3-9 times the triangles)")
      ->check(CLI::IsMember({"field", "rmin"}))
      ->capture_default_str();
  cmd->add_option("--split-factor", opt->split_factor,
                  "With --split-to field: edges are split until no longer than this times the radius")
      ->check(CLI::Range(1.0, 64.0))
      ->each([opt](const std::string&) { opt->split_factor_given = true; })
      ->capture_default_str();
  cmd->add_flag("--features", opt->features,
                "Samples on the corners and feature lines first (the boundary, and edges sharper than --feature-angle): "
                "the LRRT then keeps them; the samples there are not uniform");
  cmd->add_option("--feature-angle", opt->feature_angle,
                  "With --features: an edge is a feature when its triangles' normals are more than this many "
                  "degrees apart")
      ->check(CLI::Range(1.0, 179.0))
      ->each([opt](const std::string&) { opt->feature_angle_given = true; })
      ->capture_default_str();
  add_repair_options(cmd, opt->read);
  cmd->add_option("-o,--output", opt->output, "Samples as 'x y z r^2' lines (.xyz)")->required()->check(path_validator());
  cmd->add_option("--remesh", opt->remesh, "Also write the LRRT of the samples (.off, .obj, .ply) and check it")
      ->check(path_validator());
  cmd->add_option("--report", opt->report, "Write a JSON report")->check(path_validator());
  cmd->add_flag("--exact", opt->exact, "Decide every vertex of the maximality check with rational arithmetic");
  return [opt]() { return run_mps(*opt); };
}

}  // namespace lrvd::cli
