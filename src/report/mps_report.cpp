// The sampling the `lrvd mps` command and the Python module share (mps_report.h).
#include "report/mps_report.h"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "common/error.h"
#include "common/timing.h"
#include "predicates/predicates.h"
#include "report/lrrt_repair.h"
#include "voronoi/lrvd.h"

namespace lrvd {

MpsVerification verify_mps(const SurfaceMesh& mesh, const Samples& samples, const MpsVerifyOptions& options,
                           Diagram* lrpd) {
  const auto compute_lrpd = [&] {
    LrvdOptions lrpd_options;
    lrpd_options.weighted = true;
    return compute_lrvd(mesh, samples, lrpd_options);
  };
  return verify_mps(mesh, samples, compute_lrpd, options, lrpd);
}

void check_mps_settings(const MpsSettings& settings) {
  // A radius of the model's size already leaves one sample per sheet; far beyond it, squared
  // distances overflow.
  if (!(settings.radius > 0) || !(settings.radius <= kMaxMpsRadius))
    throw InputError(fmt::format("--radius must be a positive number up to {:g} (relative to the longest bounding-box "
                                 "side), got {}",
                                 kMaxMpsRadius, settings.radius));
  if (settings.max_radius_ratio_given && !settings.adaptive) throw InputError("--max-radius-ratio applies to --adaptive");
  // The command's parser checks these ranges and names first, in its own words.
  auto range = [](double value, const char* option, double low, double high) {
    if (!(value >= low && value <= high)) throw InputError(fmt::format("{} is {:g} to {:g}, not {}", option, low, high, value));
  };
  range(settings.max_radius_ratio, "--max-radius-ratio", 1, 100);
  range(settings.split_factor, "--split-factor", 1, 64);
  range(settings.feature_angle, "--feature-angle", 1, 179);
  if (settings.gap_update != "local" && settings.gap_update != "lrpd")
    throw InputError(fmt::format("--gap-update is local or lrpd, not '{}'", settings.gap_update));
  if (settings.conflict != "reach" && settings.conflict != "close-across-turns" && settings.conflict != "facing")
    throw InputError(fmt::format("--conflict is reach or close-across-turns, not '{}'", settings.conflict));
  if (settings.split_to != "field" && settings.split_to != "rmin")
    throw InputError(fmt::format("--split-to is field or rmin, not '{}'", settings.split_to));
}

namespace {

// "" for an LRRT that passed its checks; else one line: these samples give no valid LRRT at this
// radius, with the properties it fails. MPS cannot move its samples to mend the dual as the CVT
// remesh does (docs/algorithms/mps.md, "Known limits"); another seed, another radius or (after
// --no-features) the features sampled first is a new sampling.
std::string lrrt_refusal(const MpsRun& run, const MpsSettings& settings) {
  const RemeshVerification& check = run.remesh_check;
  if (check.passed) return "";
  std::string failed;
  const std::pair<const char*, const PropertyResult*> properties[] = {
      {"vertex_count", &check.vertex_count}, {"manifold", &check.manifold},
      {"closed", &check.closed},             {"oriented", &check.oriented},
      {"topology", &check.topology},         {"non_degenerate", &check.non_degenerate},
      {"no_self_intersection", &check.no_self_intersection}};
  for (const auto& [name, property] : properties)
    if (property->promised && !property->passed) failed += (failed.empty() ? "" : ", ") + std::string(name);
  const std::string smaller =
      run.smaller_disks.rounds > 0
          ? fmt::format(", {} of smaller disks round its defects included (radius down to {:.3g})",
                        run.smaller_disks.rounds == 1 ? std::string("1 round") : fmt::format("{} rounds", run.smaller_disks.rounds),
                        run.result.radius / run.result.scale)
          : settings.keep_radius ? " with --keep-radius" : "";
  std::string where;
  if (run.first_defect) {
    const Vec3& p = *run.first_defect;
    where = fmt::format(", the first at ({:.6g}, {:.6g}, {:.6g})", p.x, p.y, p.z);
  }
  const std::string crossing =
      run.input_crossings > 0
          ? fmt::format("; the input itself crosses itself ({} pairs of triangles of one part)", run.input_crossings)
          : "";
  return fmt::format("no valid LRRT from these samples at --radius {:g}{} (seed {}{}): its dual fails {}{}{}; written "
                     "for inspection, exit status 3 (another seed or radius{} samples anew)",
                     settings.radius, settings.adaptive ? " --adaptive" : "", settings.seed, smaller, failed, where,
                     crossing, settings.features ? "" : ", or the features sampled first (without --no-features),");
}

// The sampler's options, as the settings name them. \throw InputError on options that do not go together.
MpsOptions mps_options(const MpsSettings& settings, const ProgressFn& on_progress) {
  MpsOptions options;
  options.radius = settings.radius;
  options.adaptive = settings.adaptive;
  options.max_radius_ratio = settings.max_radius_ratio;
  options.seed = settings.seed;
  options.gap_update = settings.gap_update == "lrpd" ? MpsGapUpdate::Lrpd : MpsGapUpdate::Local;
  options.conflict = settings.conflict == "reach" ? MpsConflict::Reach : MpsConflict::CloseAcrossTurns;
  options.refinement = settings.split_to == "rmin" ? MpsRefinement::MinRadius : MpsRefinement::RadiusField;
  if (settings.split_factor_given && options.refinement == MpsRefinement::MinRadius)
    throw InputError("--split-factor applies to --split-to field; --split-to rmin splits to r_min");
  options.split_factor = settings.split_factor;
  if (settings.feature_angle_given && !settings.features)
    throw InputError("--feature-angle applies to the feature lines, which --no-features leaves unsampled");
  options.sample_features = settings.features;
  options.feature_angle = settings.feature_angle;
  options.on_progress = on_progress;
  return options;
}

// run.report, the JSON report of a finished sampling and its checks (the LRRT's parts are added by run_mps).
void write_mps_report(MpsRun& run, const LoadedMesh& loaded, bool repair_requested, const MpsSettings& settings,
                      const std::string& mesh_path, const std::string& output_path, const Diagram& lrpd) {
  const SurfaceMesh& input = loaded.mesh;
  const MpsOptions& options = run.options;
  const MpsResult& result = run.result;
  const Samples& samples = result.samples;
  const MpsVerification& check = run.check;
  const bool maximal = run.maximal, min_distance_ok = run.min_distance_ok;
  nlohmann::json& report = run.report;
  report["input"] = {{"path", mesh_path},
                     {"vertices", input.vertex_count()},
                     {"triangles", input.triangle_count()},
                     {"area", input.area()},
                     {"components", input.component_count()},
                     {"closed", input.is_closed()},
                     {"euler_characteristic", input.euler_characteristic()},
                     {"longest_bbox_side", result.scale}};
  if (repair_requested) report["input"]["repair_changes"] = repair_changes(loaded.repair);
  if (!loaded.repair.notes.empty()) report["input"]["repair"] = loaded.repair.notes;
  report["refined"] = {{"triangles", result.mesh.triangle_count()},
                       {"max_edge_length", result.mesh.max_edge_length()},
                       {"rule", options.refinement == MpsRefinement::MinRadius ? "r_min" : "radius field"},
                       {"split_factor", options.refinement == MpsRefinement::MinRadius ? 1.0 : options.split_factor}};
  report["radius"] = {{"relative", settings.radius},
                      {"absolute", result.radius},
                      {"max_absolute", result.max_radius},
                      {"adaptive", settings.adaptive}};
  report["seed"] = settings.seed;
  report["gap_update"] = settings.gap_update;
  // The facing cut gives up the paper's rule: how many close pairs that let through is said.
  const bool across_turns = options.conflict == MpsConflict::CloseAcrossTurns;
  report["conflict"] = {{"rule", across_turns ? "close-across-turns" : "reach"},
                        {"close_pairs_let_through", across_turns
                                                        ? nlohmann::json(check.close_pairs_local_past_facing_cut)
                                                        : nlohmann::json(nullptr)}};
  report["samples"] = samples.size();
  // The feature lines are counted whether or not they are sampled first (--no-features).
  report["features"] = {{"on", options.sample_features},
                        {"sampled", options.sample_features && result.feature_edges > 0},
                        {"angle_deg", options.feature_angle},
                        {"edges", result.feature_edges},
                        {"boundary_edges", result.boundary_edges},
                        {"corners", result.feature_corners},
                        {"samples", result.feature_samples}};
  report["dart_samples"] = result.dart_samples;
  report["gap_samples"] = result.gap_samples;
  report["darts"] = result.darts;
  report["lrpd_evaluations"] = result.lrpd_evaluations;
  report["part_lrpd_triangles"] = result.part_lrpd_triangles;
  report["gap_pieces"] = result.gap_pieces;
  report["dropped_gap_pieces"] = result.dropped_gap_pieces;
  report["dust_samples"] = result.dust_samples;
  report["carved_gap_pieces"] = result.carved_gap_pieces;
  report["certified_gap_pieces"] = result.certified_gap_pieces;
  report["clamped_radii"] = result.clamped_radii;
  report["radii_below_reach"] = result.radii_below_reach;
  report["power_cell_exceptions"] = result.power_cell_exceptions;
  report["gaps_closed"] = result.gaps_closed;
  report["maximal"] = maximal;
  report["min_distance_ok"] = min_distance_ok;
  report["mps_verification"] = check.to_json();
  report["time_s"] = {{"init", result.time_s.init},
                      {"dart_throwing", result.time_s.dart_throwing},
                      {"gap_filling", result.time_s.gap_filling},
                      {"total", result.time_s.total},
                      {"cpu_total", result.time_s.cpu_total},
                      {"verification_lrpd", lrpd.stats.time_s},
                      {"verification", check.time_s}};
  report["output"] = output_path;

}

}  // namespace

namespace {

// One sampling with `options` and its check on a fresh LRPD (kept in run.lrpd); no report yet.
MpsRun sample_and_check(const SurfaceMesh& input, const MpsSettings& settings, const MpsOptions& options,
                        const std::string& mesh_path, const ProgressFn& on_progress) {
  MpsRun run;
  run.options = options;
  // What the sampler refuses is about this mesh (its refinement, its size for the radius): the
  // message names the file, as the loader's do.
  try {
    run.result = maximal_poisson_disk_sampling(input, run.options);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", mesh_path, e.what()));
  }
  // The checks start from the samples alone: a new LRPD, new local regions.
  if (on_progress) on_progress(fmt::format("verifying {} samples on a fresh LRPD", run.result.samples.size()));
  MpsVerifyOptions verify_options;
  verify_options.exact_maximality = settings.exact;
  verify_options.facing_cut = options.conflict == MpsConflict::CloseAcrossTurns;
  run.check = verify_mps(run.result.mesh, run.result.samples, verify_options, &run.lrpd);
  run.maximal = run.check.maximal.passed && run.check.diagram_covers.passed;
  run.min_distance_ok = run.check.min_distance.passed;
  return run;
}

// The LRRT of run's samples (the dual of its LRPD) and its check against the input.
void remesh_and_check(const SurfaceMesh& input, MpsRun& run) {
  run.lrrt = true;
  run.dual = compute_dual(run.lrpd, run.result.mesh, run.result.samples);
  run.remesh_check = verify_remesh(input, run.dual.positions, run.dual.triangles, run.result.samples.size());
}

// While the LRRT fails its checks: the radius halved round the samples at its defects, and the
// sampling and its LRRT again (up to kMaxLrrtRounds); the last sampling is the result.
void smaller_disks_at_defects(const SurfaceMesh& input, const MpsSettings& settings, const std::string& mesh_path,
                              const ProgressFn& on_progress, const std::vector<std::pair<int, int>>& crossings,
                              MpsRun& run) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  // The rounds sample the first sampling's refined mesh, the same surface with triangles of about
  // the radius: a radius lowered at its vertices stays local, where on the input's own large
  // triangles it would spread over them (a thin box of 12 triangles, the whole box).
  const SurfaceMesh surface = run.result.mesh;
  std::vector<double> field = sampled_radius_field(surface, run.options, run.result);
  const std::vector<double> initial = field;
  const double first_estimate = expected_sample_count(surface, field);
  for (int round = 1; round <= kMaxLrrtRounds && !run.remesh_check.passed; ++round) {
    const std::vector<int> defects =
        away_from_crossings(input, run.result, lrrt_defect_samples(input, run.result, run.lrpd, run.dual), crossings);
    if (defects.empty()) break;  // none located, or all where the input crosses itself
    MpsOptions options = run.options;
    // A feature sample at a defect stays one at any radius (its line is where it is): darts there.
    const int excluded = exclude_feature_samples(run.result, defects, options.feature_exclusions);
    const std::vector<double> before = field;
    if (halve_radius_round(surface, run.result, defects, options.gradation, field) == 0 && excluded == 0) break;
    if (expected_sample_count(surface, field) > kMaxLrrtGrowth * first_estimate + kLrrtGrowthAllowance) {
      field = before;
      break;
    }
    if (on_progress)
      on_progress(fmt::format("the LRRT has defects at {} samples: round {}, the radius halved round them, sampling again",
                              defects.size(), round));
    options.radius_field = field;
    options.first_samples = samples_away_from(run.result, defects, options.gradation);
    MpsRun again = sample_and_check(surface, settings, options, mesh_path, on_progress);
    remesh_and_check(input, again);
    again.smaller_disks.rounds = round;
    // The feature lines the report names are the user's mesh's, not those of the refinement the
    // rounds sample (its split edges count again).
    again.result.feature_edges = run.result.feature_edges;
    again.result.boundary_edges = run.result.boundary_edges;
    again.result.feature_corners = run.result.feature_corners;
    run = std::move(again);
  }
  run.smaller_disks.vertices = 0;
  for (std::size_t v = 0; v < field.size(); ++v) run.smaller_disks.vertices += field[v] < initial[v];
  run.smaller_disks.time_s = seconds_since(start);
  run.smaller_disks.cpu_s = process_cpu_seconds() - cpu_start;
}

}  // namespace

MpsRun run_mps(const LoadedMesh& loaded, bool repair_requested, const MpsSettings& settings,
               const std::string& mesh_path, const std::string& output_path, bool lrrt,
               const std::string& remesh_path, const ProgressFn& on_progress,
               const std::function<void(const Samples&)>& on_samples,
               const std::function<void(const DualMesh&)>& on_dual) {
  const SurfaceMesh& input = loaded.mesh;
  reset_predicate_stats();
  MpsRun run = sample_and_check(input, settings, mps_options(settings, on_progress), mesh_path, on_progress);
  if (lrrt) {
    if (on_progress) on_progress("remeshing: the LRRT of the samples");
    remesh_and_check(input, run);
    if (!run.remesh_check.passed) {
      const std::vector<std::pair<int, int>> crossings = crossings_within_parts(input);
      if (!settings.keep_radius) smaller_disks_at_defects(input, settings, mesh_path, on_progress, crossings, run);
      run.input_crossings = static_cast<int>(crossings.size());
    }
  }
  if (on_samples) on_samples(run.result.samples);
  write_mps_report(run, loaded, repair_requested, settings, mesh_path, output_path, run.lrpd);
  if (!lrrt) return run;

  nlohmann::json& report = run.report;
  const DualMesh& dual = run.dual;
  if (on_dual) on_dual(dual);
  // An LRRT without triangles (a sample or two on the whole surface) fails the checks and has
  // nothing to measure.
  run.measurable = !dual.triangles.empty();
  if (run.measurable) run.quality = quality_metrics(input, dual.positions, dual.triangles);
  report["quality"] = run.measurable ? remesh_quality_json(run.quality, run.remesh_check) : nlohmann::json(nullptr);
  report["verification"] = run.remesh_check.to_json();
  if (!run.remesh_check.passed) {
    // Where the refusal points: the first defect the finder locates, and the input's own crossings.
    const std::vector<int> defects = lrrt_defect_samples(input, run.result, run.lrpd, dual);
    if (!defects.empty()) run.first_defect = run.result.samples.positions[defects.front()];
  }
  run.lrrt_refusal = lrrt_refusal(run, settings);
  report["remesh"] = {{"path", remesh_path},
                      {"vertices", dual.positions.size()},
                      {"triangles", dual.triangles.size()},
                      {"valid", run.remesh_check.passed},
                      {"refusal", run.lrrt_refusal.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.lrrt_refusal)},
                      {"smaller_disks", {{"rounds", run.smaller_disks.rounds},
                                         {"vertices", run.smaller_disks.vertices},
                                         {"smallest_radius", run.result.radius / run.result.scale},
                                         {"time_s", run.smaller_disks.time_s},
                                         {"cpu_s", run.smaller_disks.cpu_s}}},
                      {"input_crossings", run.remesh_check.passed ? nlohmann::json(nullptr) : nlohmann::json(run.input_crossings)}};
  return run;
}

}  // namespace lrvd
