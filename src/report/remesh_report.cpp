// The remesh the `lrvd remesh` command and the Python module share (remesh_report.h).
#include "report/remesh_report.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "predicates/predicates.h"
#include "verification/remesh_check.h"
#include "voronoi/lrvd.h"

namespace lrvd {

NarrowPart narrowest_ring(const DualDefects& defects, double area) {
  NarrowPart narrow;
  for (const RingCell& ring : defects.rings)
    if (narrow.vertex < 0 || ring.around < narrow.around) narrow = {ring.cell, ring.other, ring.around, 0};
  if (narrow.vertex >= 0) {
    const double hexagon = std::sqrt(3.0) / 18 * narrow.around * narrow.around;
    narrow.uniform_vertices = static_cast<long long>(std::ceil(std::min(area / hexagon, 1e15)));
  }
  return narrow;
}

namespace {

// What the repair left (RemeshResult::defects), by kind: the count and the first few samples, each
// the output's vertex of the same index, with its place on the input surface (where a thin part or
// a handle was not caught).
nlohmann::json defects_json(const DualDefects& defects, const Samples& samples) {
  constexpr size_t kListed = 10;
  auto kind = [&](const std::vector<int>& ids) {
    nlohmann::json first = nlohmann::json::array();
    for (size_t k = 0; k < ids.size() && k < kListed; ++k) {
      const Vec3& p = samples.positions[ids[k]];
      first.push_back({{"vertex", ids[k]}, {"position", {p.x, p.y, p.z}}});
    }
    return nlohmann::json{{"count", ids.size()}, {"first", first}};
  };
  return {{"summary", defects.describe()},
          {"euler_characteristic_ok", defects.euler_ok},
          {"topological", kind(defects.topological)},
          {"crossing", kind(defects.crossing)},
          {"cell_topology", kind(defects.cell_topology)}};
}

ClosedOverHoles closed_over_holes(const DualDefects& defects, const SurfaceMesh& mesh, const SurfaceMesh& input,
                                  double diagonal) {
  ClosedOverHoles holes;
  holes.count = static_cast<int>(defects.closed_over_loops.size());
  if (holes.count == 0) return holes;
  for (int l : defects.closed_over_loops) holes.longest = std::max(holes.longest, mesh.boundary_loop_length(l));
  const double ratio = 1.05 * holes.longest / diagonal;  // a margin over the rounding of the lengths
  const double unit = std::pow(10.0, std::floor(std::log10(ratio)) - 1);
  holes.fraction = std::stod(fmt::format("{:.2g}", std::ceil(ratio / unit) * unit));  // as printed
  RepairReport trial;
  SurfaceMesh filled;
  try {
    filled = fill_small_holes(input, holes.fraction * diagonal, &trial);
  } catch (const InputError&) {
    return holes;  // the fill would not give a valid mesh: nothing to suggest
  }
  // `mesh` is `input`, maybe refined and renumbered (order_for_remeshing): each of its loops runs
  // through the input loop's own vertices, at the same positions, with midpoints between them.
  std::vector<char> still_open(input.vertex_count(), 0);
  for (const std::vector<int>& loop : filled.boundary_loops())
    for (int v : loop) still_open[v] = 1;
  std::map<std::array<double, 3>, int> input_vertex_at;
  for (const std::vector<int>& loop : input.boundary_loops())
    for (int v : loop) input_vertex_at[{input.position(v).x, input.position(v).y, input.position(v).z}] = v;
  for (int l : defects.closed_over_loops)
    for (int v : mesh.boundary_loops()[l]) {
      const auto at = input_vertex_at.find({mesh.position(v).x, mesh.position(v).y, mesh.position(v).z});
      if (at == input_vertex_at.end()) continue;  // a midpoint of the refinement
      holes.fillable += !still_open[at->second];
      break;
    }
  holes.others = std::max(0, trial.filled_holes - holes.fillable);
  return holes;
}

}  // namespace

void check_remesh_settings(const RemeshSettings& settings) {
  if (is_power(diagram_kind_from_string(settings.kind))) throw InputError("remesh uses a Voronoi diagram: --diagram lrvd or rvd");
  auto require = [](const std::string& value, const char* option, const char* a, const char* b) {
    if (value != a && value != b) throw InputError(fmt::format("{} is {} or {}, not '{}'", option, a, b, value));
  };
  require(settings.optimizer, "--optimizer", "lbfgs", "lloyd");
  require(settings.density, "--density", "uniform", "curvature");
  require(settings.priority, "--priority", "distance", "shape");
  require(settings.repair_scope, "--repair-scope", "whole", "local");
  if (settings.iterations < 1 || settings.iterations > 100000)
    throw InputError(fmt::format("--iterations is 1 to 100000, not {}", settings.iterations));
}

namespace {

// The options of a remesh, as the settings name them.
RemeshOptions remesh_options(const RemeshSettings& settings, const ProgressFn& on_progress) {
  RemeshOptions remesh;
  CvtOptions& cvt = remesh.cvt;
  cvt.diagram = diagram_kind_from_string(settings.kind);
  cvt.optimizer = settings.optimizer == "lloyd" ? CvtOptimizer::Lloyd : CvtOptimizer::Lbfgs;
  cvt.density = settings.density == "curvature" ? CvtDensity::Curvature : CvtDensity::Uniform;
  cvt.iterations = settings.iterations;
  remesh.fit = settings.fit;
  if (settings.priority == "shape") remesh.relax.rounds = kShapePriorityRounds;
  remesh.repair = settings.repair_scope == "local" ? RepairScope::Local : RepairScope::Whole;
  remesh.on_progress = on_progress;
  return remesh;
}

// CPU seconds of the process at the steps of run_remesh.
struct RunClock {
  double start = 0, before_cvt = 0;  // run_remesh's start, the first CVT's
  double written = 0;                // the remesh done, before its output is written (on_dual)
  double checks = 0, metrics = 0, end = 0;
};

// report["time_cpu_s"]: the remesh driver's stages, and the steps of run_remesh around them; the
// same on the progress line.
void write_cpu_times(nlohmann::json& report, const RemeshStageTimes& stages, const RunClock& clock,
                     const ProgressFn& on_progress) {
  // The rest of the time from the samples to the checks, but for writing the output, is "other".
  const double other = stages.other + (clock.written - clock.before_cvt) - stages.total();
  report["time_cpu_s"] = {{"prepare", clock.before_cvt - clock.start},
                          {"first_cvt", stages.first_cvt},
                          {"repair_round_cvts", stages.round_cvts},
                          {"duals_and_defects", stages.defects},
                          {"untangle_in_rounds", stages.round_untangle},
                          {"polish_and_ease", stages.polish_ease},
                          {"fit", stages.fit},
                          {"untangle", stages.untangle},
                          {"other", other},
                          {"checks", clock.metrics - clock.checks},
                          {"metrics", clock.end - clock.metrics},
                          {"total", (clock.end - clock.start) - (clock.checks - clock.written)}};
  if (on_progress)
    on_progress(fmt::format("CPU s: prepare {:.2f}, first CVT {:.2f}, repair rounds' CVTs {:.2f}, duals and defects "
                            "{:.2f}, untangling in the rounds {:.2f}, polish and ease {:.2f}, fit {:.2f}, untangle "
                            "{:.2f}, other {:.2f}, checks {:.2f}, metrics {:.2f}",
                            clock.before_cvt - clock.start, stages.first_cvt, stages.round_cvts, stages.defects,
                            stages.round_untangle, stages.polish_ease, stages.fit, stages.untangle, other,
                            clock.metrics - clock.checks, clock.end - clock.metrics));
}

// run.report, the JSON report of a finished remesh of `input` (and run.diagonal, run.holes).
void write_remesh_report(RemeshRun& run, const Input& input, const RemeshSettings& settings,
                         const std::string& mesh_path, const std::string& output_path, const RunClock& clock,
                         const ProgressFn& on_progress) {
  const RemeshOptions& remesh = run.options;
  const RemeshResult& remeshed = run.result;
  const CvtResult& result = remeshed.cvt;
  const DualMesh& dual = remeshed.dual;
  const RemeshVerification& check = run.check;
  nlohmann::json& report = run.report;
  report["input"] = input_json(input);
  report["input"]["path"] = mesh_path;
  report["output"] = {{"path", output_path}, {"vertices", dual.positions.size()}, {"triangles", dual.triangles.size()}};
  report["quality"] = run.measurable ? remesh_quality_json(run.quality, check) : nlohmann::json(nullptr);
  report["verification"] = check.to_json();
  report["diagram"] = settings.kind;
  report["optimizer"] = settings.optimizer;
  report["density"] = settings.density;
  report["priority"] = settings.priority;
  report["repair_scope"] = settings.repair_scope;
  // With `--priority shape`: the vertices of the worst triangles moved before the fitting.
  report["relaxed"] = {{"rounds", remesh.relax.rounds},
                       {"moved", remeshed.relax.moved},
                       {"reverted", remeshed.relax.reverted}};
  report["iterations"] = remeshed.total_iterations;
  report["repair_rounds"] = remeshed.repair_rounds;
  report["diagram_evaluations"] = remeshed.diagram_evaluations;
  // The repair ended with defects and the second run, samples kept to their own sheets, did better.
  report["kept_to_sheets"] = remeshed.path.kept_to_sheets;
  report["tip_caps_lowered"] = remeshed.path.tip_caps_lowered;
  report["samples_reallocated"] = remeshed.path.samples_reallocated;
  report["reallocation_tried"] = remeshed.path.reallocation_tried;
  report["lloyd_rounds"] = remeshed.path.lloyd_rounds;
  report["runs"] = remeshed.path.runs;
  // The kept state took RemeshOptions::polish_steps Lloyd steps after L-BFGS.
  report["polished"] = remeshed.path.polished;
  // The kept state took RemeshOptions::ease_iterations with the repair's raised density eased back.
  report["density_eased"] = remeshed.path.eased;
  // A run stopped because every cell was at a defect or next to one (docs/reference/metrics.md,
  // "What the repair left").
  report["repair_saturated"] = remeshed.path.repair_saturated;
  report["defects_left"] = defects_json(remeshed.defects, result.samples);
  report["line_search_stopped"] = result.line_search_stopped;
  // Lengths in % of the input's bounding-box diagonal, as the distances are.
  const double diagonal = run.diagonal = input.loaded.mesh.bounding_box().diagonal();
  const ClosedOverHoles& holes = run.holes = closed_over_holes(remeshed.defects, input.mesh, input.loaded.mesh, diagonal);
  report["defects_left"]["closed_over_holes"] = {{"count", holes.count}};
  if (holes.count > 0) {
    report["defects_left"]["closed_over_holes"]["longest"] = holes.longest;
    report["defects_left"]["closed_over_holes"]["fillable"] = holes.fillable;
    if (holes.fillable > 0) report["defects_left"]["closed_over_holes"]["fill_holes"] = holes.fraction;
  }
  auto percent = [diagonal](double length) { return 100.0 * length / diagonal; };
  const NarrowPart& narrow = run.narrow = narrowest_ring(remeshed.defects, input.loaded.mesh.area());
  report["defects_left"]["rings"] = {{"count", remeshed.defects.rings.size()}};
  if (narrow.vertex >= 0) {
    const Vec3& p = result.samples.positions[narrow.vertex];
    report["defects_left"]["rings"]["narrowest"] = {{"vertex", narrow.vertex},
                                                    {"other_vertex", narrow.other},
                                                    {"position", {p.x, p.y, p.z}},
                                                    {"around_pct", percent(narrow.around)},
                                                    {"uniform_vertices", narrow.uniform_vertices}};
  }
  report["fit"] = {{"enabled", remesh.fit},
                   {"moved", remeshed.fit.moved},
                   {"reverted", remeshed.fit.reverted},
                   {"max_displacement_pct", percent(remeshed.fit.max_displacement)},
                   {"balanced_distance_pct_before", percent(remeshed.fit.offsets.max_before)},
                   {"balanced_distance_pct_after", percent(remeshed.fit.offsets.max_after)}};
  report["untangle"] = {{"crossings_before", remeshed.untangle.crossings_before},
                        {"crossings_after", remeshed.untangle.crossings_after},
                        {"moved", remeshed.untangle.moved},
                        {"flipped", remeshed.untangle.flipped},
                        {"max_displacement_pct", percent(remeshed.untangle.max_displacement)}};
  report["energy"] = result.energy;
  report["initial_energy"] = result.energy_history.front();
  report["time_s"] = remeshed.time_s;
  write_cpu_times(report, remeshed.stage_cpu_s, clock, on_progress);
  report["predicates"] = predicates_json();
}

}  // namespace

RemeshRun run_remesh(Input& input, const RemeshSettings& settings, bool random_samples, std::uint64_t seed,
                     const std::string& mesh_path, const std::string& output_path, const ProgressFn& on_progress,
                     const std::function<void(const DualMesh&)>& on_dual) {
  if (input.samples.weighted())
    throw InputError("remesh computes a CVT of unweighted samples: weights (--weights or a 4th column in --points) do not apply");
  if (input.refined_from >= 0 && on_progress)
    on_progress(fmt::format("refined the mesh from {} to {} triangles", input.refined_from, input.mesh.triangle_count()));
  RunClock clock;
  clock.start = clock.before_cvt = process_cpu_seconds();
  RemeshRun run;
  run.options = remesh_options(settings, on_progress);
  const RemeshOptions& remesh = run.options;
  // The samples drawn per component unless given (--points), both renumbered: remesh_from.
  RemeshStart start;
  start.n = input.samples.size();
  start.seed = seed;
  start.mesh = std::move(input.mesh);
  if (!random_samples) start.samples = std::move(input.samples);
  start.before_cvt = [&](const SurfaceMesh&, const Samples& samples) {
    reset_predicate_stats();
    clock.before_cvt = process_cpu_seconds();
    if (on_progress) on_progress(fmt::format("CVT of {} samples on the {}", samples.size(), settings.kind));
  };
  run.result = remesh_from(input.loaded.mesh, start, remesh);
  input.mesh = std::move(*start.mesh);
  input.samples = std::move(*start.samples);
  const DualMesh& dual = run.result.dual;
  clock.written = process_cpu_seconds();
  if (on_dual) on_dual(dual);

  if (on_progress) on_progress("checking the remesh");
  clock.checks = process_cpu_seconds();
  run.check = verify_remesh(input.loaded.mesh, dual.positions, dual.triangles, input.samples.size());
  clock.metrics = process_cpu_seconds();
  // A dual without triangles (too few vertices for the surface's shape) fails the checks; there
  // is nothing to measure.
  run.measurable = !dual.triangles.empty();
  if (run.measurable) run.quality = quality_metrics(input.loaded.mesh, dual.positions, dual.triangles);
  clock.end = process_cpu_seconds();

  write_remesh_report(run, input, settings, mesh_path, output_path, clock, on_progress);
  return run;
}

}  // namespace lrvd
