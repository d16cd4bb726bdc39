// `lrvd remesh` (CVT on the LRVD, output the dual with exactly N vertices, checked) and
// `lrvd quality` (the metrics alone, for any remesher's output).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/common.h"
#include "common/error.h"
#include "metrics/quality.h"
#include "predicates/predicates.h"
#include "remesh/remesh_pipeline.h"
#include "verification/remesh_check.h"
#include "voronoi/dual.h"
#include "voronoi/lrvd.h"

namespace lrvd::cli {

namespace {

// The crossings the check let pass as the input's own, when there are any: " (N crossing pairs
// inherited ...)".
std::string inherited_note(const RemeshVerification& check) {
  if (check.inherited_intersecting_pairs == 0) return "";
  return fmt::format(" ({} inherited: between components that cross or touch in the input too)",
                     counted(check.inherited_intersecting_pairs, "crossing pair", "crossing pairs"));
}

struct RemeshCommandOptions {
  InputOptions input;
  std::string kind = "lrvd", optimizer = "lbfgs", density = "uniform", priority = "distance", repair = "whole";
  int iterations = 60;
  bool no_fit = false;
  std::string output, report;
};

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

// The holes the kept dual closes over (fewer than three cells meet their loop), the longest's length,
// and the smallest --fill-holes fraction of two significant digits above it: tried on the input,
// how many of those holes it fills (fill_small_holes leaves some open) and how many other holes.
struct ClosedOverHoles {
  int count = 0;
  double longest = 0;
  double fraction = 0;
  int fillable = 0;  //!< of the `count`, filled by --fill-holes `fraction`
  int others = 0;    //!< other holes it fills
};

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
  // `mesh` is `input`, maybe refined and renumbered (remesh_from): each of its loops runs
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

int run_remesh(const RemeshCommandOptions& opt) {
  const DiagramKind kind = diagram_kind_from_string(opt.kind);
  if (is_power(kind)) throw InputError("remesh uses a Voronoi diagram: --diagram lrvd or rvd");
  if (opt.output.empty()) throw InputError("give an output file with -o");
  check_outputs({{opt.output, "-o", kMeshWriteExtensions}, {opt.report, "--report", {}, kMeshReadExtensions}},
                read_files(opt.input));
  InputOptions read = opt.input;
  read.check_count = require_remesh_vertex_count;  // before sampling, which asks one per component
  Input input = load_input(read);
  if (input.samples.weighted())
    throw InputError("remesh computes a CVT of unweighted samples: weights (--weights or a 4th column in --points) do not apply");
  if (input.refined_from >= 0)
    progress(fmt::format("refined the mesh from {} to {} triangles", input.refined_from, input.mesh.triangle_count()));

  RemeshOptions remesh;
  CvtOptions& cvt = remesh.cvt;
  cvt.diagram = kind;
  cvt.optimizer = opt.optimizer == "lloyd" ? CvtOptimizer::Lloyd : CvtOptimizer::Lbfgs;
  cvt.density = opt.density == "curvature" ? CvtDensity::Curvature : CvtDensity::Uniform;
  cvt.iterations = opt.iterations;
  remesh.fit = !opt.no_fit;
  if (opt.priority == "shape") remesh.relax.rounds = kShapePriorityRounds;
  remesh.repair = opt.repair == "local" ? RepairScope::Local : RepairScope::Whole;
  remesh.on_progress = [](const std::string& message) { progress(message); };
  // The samples drawn per component unless given (--points), both renumbered: remesh_from.
  RemeshStart start;
  start.n = input.samples.size();
  start.seed = opt.input.seed;
  start.mesh = std::move(input.mesh);
  if (!opt.input.points_path.empty()) start.samples = std::move(input.samples);
  start.before_cvt = [&](const SurfaceMesh&, const Samples& samples) {
    reset_predicate_stats();
    progress(fmt::format("CVT of {} samples on the {}", samples.size(), opt.kind));
  };
  const RemeshResult remeshed = remesh_from(input.loaded.mesh, start, remesh);
  input.mesh = std::move(*start.mesh);
  input.samples = std::move(*start.samples);
  const CvtResult& result = remeshed.cvt;
  const DualMesh& dual = remeshed.dual;
  write_mesh(opt.output, dual.positions, dual.triangles);

  progress("checking the remesh");
  const RemeshVerification check = verify_remesh(input.loaded.mesh, dual.positions, dual.triangles, input.samples.size());
  // A dual without triangles (too few vertices for the surface's shape) fails the checks; there
  // is nothing to measure.
  const bool measurable = !dual.triangles.empty();
  const QualityMetrics quality =
      measurable ? quality_metrics(input.loaded.mesh, dual.positions, dual.triangles) : QualityMetrics{};

  nlohmann::json report;
  report["input"] = input_json(input);
  report["input"]["path"] = opt.input.mesh_path;
  report["output"] = {{"path", opt.output}, {"vertices", dual.positions.size()}, {"triangles", dual.triangles.size()}};
  report["quality"] = measurable ? remesh_quality_json(quality, check) : nlohmann::json(nullptr);
  report["verification"] = check.to_json();
  report["diagram"] = opt.kind;
  report["optimizer"] = opt.optimizer;
  report["density"] = opt.density;
  report["priority"] = opt.priority;
  report["repair_scope"] = opt.repair;
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
  const double diagonal = input.loaded.mesh.bounding_box().diagonal();
  const ClosedOverHoles holes = closed_over_holes(remeshed.defects, input.mesh, input.loaded.mesh, diagonal);
  report["defects_left"]["closed_over_holes"] = {{"count", holes.count}};
  if (holes.count > 0) {
    report["defects_left"]["closed_over_holes"]["longest"] = holes.longest;
    report["defects_left"]["closed_over_holes"]["fillable"] = holes.fillable;
    if (holes.fillable > 0) report["defects_left"]["closed_over_holes"]["fill_holes"] = holes.fraction;
  }
  auto percent = [diagonal](double length) { return 100.0 * length / diagonal; };
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
  report["predicates"] = predicates_json();
  if (!opt.report.empty()) write_report(opt.report, report, {opt.output});

  std::printf("remesh (%s): %s, %s, %s, %.3f s -> %s\n", opt.kind.c_str(),
              counted(dual.positions.size(), "vertex", "vertices").c_str(),
              counted(dual.triangles.size(), "triangle", "triangles").c_str(),
              counted(remeshed.total_iterations, "iteration", "iterations").c_str(), remeshed.time_s, opt.output.c_str());
  print_quality(measurable ? &quality : nullptr, false);
  std::printf("verification: %s%s\n", check.passed ? "passed" : "FAILED", inherited_note(check).c_str());
  if (!check.passed) std::fputs(check.summary().c_str(), stdout);
  if (!check.passed && !remeshed.defects.empty()) {
    // Where the repair gave up, on the input surface: a thin part or a handle too small for the cells.
    const DualDefects& left = remeshed.defects;
    const int first = left.where_to_act().empty() ? -1 : left.where_to_act().front();
    std::string where;
    if (first >= 0) {
      const Vec3& p = result.samples.positions[first];
      where = fmt::format("; the first at vertex {}, ({:.6g}, {:.6g}, {:.6g})", first, p.x, p.y, p.z);
    }
    std::printf("repair: %s left after %d rounds%s\n", left.describe().c_str(), remeshed.repair_rounds, where.c_str());
    if (remeshed.path.repair_saturated)
      // A 10 x 1 x 0.01 plate fails so at 50 vertices and is valid at 20 and at 100 (an audit).
      std::printf("repair: every cell was at a defect or next to one, where a higher density changes nothing: the "
                  "surface is thinner than the cells everywhere; more vertices (smaller cells) usually mend it, and "
                  "on a part only a few cells wide, fewer sometimes do\n");
    else if (holes.count == 0)
      // CGAL's couplingdown (genus 9) fails at 200 vertices with seeds 1-3 and is valid at 500.
      std::printf("repair: there the surface is thinner, or a handle narrower, than the cells can follow; more "
                  "vertices (smaller cells) may mend it\n");
  }
  if (!check.passed && holes.count > 0) {
    const std::string which = holes.fillable == holes.count ? (holes.count == 1 ? "it" : "them")
                                                            : fmt::format("{} of them", holes.fillable);
    const std::string advice =
        holes.fillable == 0
            ? fmt::format("--fill-holes cannot close {} (docs/guide/input.md), give more vertices",
                          holes.count == 1 ? "it" : "them")
            : fmt::format("--fill-holes {:.2g} closes {} and {} other hole{}{}, or give more vertices", holes.fraction,
                          which, holes.others, holes.others == 1 ? "" : "s",
                          holes.fillable < holes.count ? " (it leaves the rest open)" : "");
    std::printf("repair: %d hole%s met by fewer than three cells, the longest %.6g around (%.3g of the bounding-box "
                "diagonal): %s\n",
                holes.count, holes.count == 1 ? " is" : "s are", holes.longest, holes.longest / diagonal,
                advice.c_str());
  }
  // The failures a picture shows (render --color defects): non-manifold edges and repeated
  // triangles, holes, degenerate and crossing triangles, unused vertices; not a wrong genus alone.
  const bool drawable = !check.manifold.passed || !check.closed.passed || !check.non_degenerate.passed ||
                        !check.no_self_intersection.passed || !check.vertex_count.passed;
  std::error_code not_a_file;
  if (drawable && !dual.triangles.empty() && std::filesystem::is_regular_file(opt.output, not_a_file)) {
    // A picture shows where at a glance: the triangles each failed check is about, coloured. It
    // goes beside the output (a file, not a device such as /dev/null), named after it, unless that
    // name (with the writer's part suffix) is longer than a file name can be.
    namespace fs = std::filesystem;
    fs::path picture = fs::path(opt.output).replace_extension().string() + "_defects.png";
    if (picture.filename().string().size() + std::string(".lrvd-part").size() > 255)
      picture = fs::path(opt.output).parent_path() / "lrvd_defects.png";
    // A path read as an option when it begins with '-'.
    auto argument = [](const std::string& path) { return shell_word(path.rfind('-', 0) == 0 ? "./" + path : path); };
    std::printf("see where: lrvd render %s --color defects -o %s\n", argument(opt.output).c_str(),
                argument(picture.string()).c_str());
  }
  return check.passed ? kOk : kCheckFailed;
}

struct QualityOptions {
  std::string reference, mesh, report;
  ReadOptions read;  //!< of the reference, as the remesh's input was
};

// A mesh measured against a reference of another size or place: its bounding box's diagonal more
// than 1.5 times the reference's or less than 1/1.5 of it, or its centre further from the
// reference's than half the reference's diagonal. "" when neither holds.
std::string frame_mismatch(const BoundingBox& reference, const BoundingBox& mesh) {
  constexpr double kSizeRatio = 1.5;
  const double size = mesh.diagonal() / reference.diagonal();
  const double offset = distance(0.5 * (mesh.min + mesh.max), 0.5 * (reference.min + reference.max));
  if (size <= kSizeRatio && size >= 1 / kSizeRatio && offset <= 0.5 * reference.diagonal()) return std::string();
  return fmt::format("the mesh's bounding box has {:.3g} times the reference's diagonal ({:.4g} against {:.4g}) and "
                     "its centre is {:.3g} reference diagonals away: the distances measure that; are both in one unit "
                     "and frame?",
                     size, mesh.diagonal(), reference.diagonal(), offset / reference.diagonal());
}

int run_quality(const QualityOptions& opt) {
  if (opt.mesh.empty()) throw InputError("give the mesh to measure after the reference: lrvd quality REFERENCE MESH");
  check_outputs({{opt.report, "--report", {}, kMeshReadExtensions}},
                {{opt.reference, "the reference mesh"}, {opt.mesh, "the measured mesh"}});
  const LoadedMesh loaded = read_mesh(opt.reference, opt.read);
  print_repair(loaded.repair, opt.read);
  const SurfaceMesh& reference = loaded.mesh;
  const PolygonSoup soup = read_polygon_soup(opt.mesh, true);
  // A mesh of vertices only (what remesh writes when its dual has no triangle) is checked, not measured.
  const bool measurable = !soup.triangles.empty();
  const QualityMetrics quality =
      measurable ? quality_metrics(reference, soup.positions, soup.triangles) : QualityMetrics{};
  const RemeshVerification check = verify_remesh(reference, soup.positions, soup.triangles, -1);
  nlohmann::json report = {{"reference", opt.reference}, {"mesh", opt.mesh}};
  if (opt.read.repair) report["reference_repair_changes"] = repair_changes(loaded.repair);
  if (!loaded.repair.notes.empty()) report["reference_repair"] = loaded.repair.notes;
  // Two meshes in different units or frames give distances that measure that, not the remesh. The
  // distances read the triangles only, so does the frame: a vertex no triangle uses does not count.
  std::vector<Vec3> used;
  {
    std::vector<char> in_triangle(soup.positions.size(), 0);
    for (const Triangle& t : soup.triangles)
      for (int v : t)
        if (v >= 0 && static_cast<std::size_t>(v) < in_triangle.size()) in_triangle[v] = 1;
    for (std::size_t v = 0; v < soup.positions.size(); ++v)
      if (in_triangle[v]) used.push_back(soup.positions[v]);
  }
  const std::string frame =
      measurable && !used.empty() ? frame_mismatch(reference.bounding_box(), bounding_box(used)) : std::string();
  if (!frame.empty()) report["frame_warning"] = frame;
  report["quality"] = measurable ? remesh_quality_json(quality, check) : nlohmann::json(nullptr);
  report["verification"] = check.to_json();
  if (!opt.report.empty()) write_json(opt.report, report);
  std::printf("%s: %s, %s\n", opt.mesh.c_str(),
              counted(static_cast<long long>(soup.positions.size()), "vertex", "vertices").c_str(),
              counted(static_cast<long long>(soup.triangles.size()), "triangle", "triangles").c_str());
  if (measurable)
    std::printf("quality: Qmin %.3f Qavg %.3f theta %.1f/%.1f, %.2f%% triangles < 30 deg, Hausdorff %.3f%% RMS %.3f%%\n",
                quality.q_min, quality.q_avg, quality.theta_min, quality.theta_max, quality.pct_triangles_below_30,
                quality.hausdorff_pct, quality.rms_pct);
  else
    std::printf("quality: not measured (the mesh has no triangles)\n");
  if (!frame.empty()) std::printf("warning: %s\n", frame.c_str());
  // The key `closed_manifold` asks for a closed mesh only when the reference is closed.
  std::printf("%s: %s, genus preserved: %s, self-intersecting pairs: %d%s\n",
              reference.is_closed() ? "closed manifold" : "manifold (open, as the reference)",
              measurable && check.manifold.passed && check.closed.passed ? "yes" : "no",  // no triangle: no surface
              check.topology.passed ? "yes" : "no",
              check.self_intersecting_pairs, inherited_note(check).c_str());
  // Like a remesh of our own: 3 when the mesh fails a check, so that a script can tell.
  std::printf("verification: %s\n", check.passed ? "passed" : "FAILED");
  if (!check.passed) std::fputs(check.summary().c_str(), stdout);
  return check.passed ? kOk : kCheckFailed;
}

}  // namespace

Action add_remesh_command(CLI::App& app) {
  auto opt = std::make_shared<RemeshCommandOptions>();
  CLI::App* cmd = app.add_subcommand("remesh", "Remesh to exactly N vertices with a CVT on the LRVD, check the output");
  add_input_options(cmd, opt->input, true, false);
  cmd->add_option("--diagram", opt->kind, "Diagram of the CVT: lrvd (default) or rvd (the baseline)")
      ->check(CLI::IsMember({"lrvd", "rvd"}))
      ->capture_default_str();
  cmd->add_option("--optimizer", opt->optimizer, "lbfgs or lloyd")->check(CLI::IsMember({"lbfgs", "lloyd"}))->capture_default_str();
  cmd->add_option("--iterations", opt->iterations,
                  "Iteration cap of the first CVT, which usually stops there: more iterations give better "
                  "triangles, for more time (each repair round of a dual with defects runs up to 30 more, and 10 "
                  "more try the rounds' density eased back; with L-BFGS, a state without defects then takes one "
                  "Lloyd step)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--density", opt->density,
                  "uniform, or curvature: smaller cells where the surface bends (at a few hundred vertices "
                  "uniform does better)")
      ->check(CLI::IsMember({"uniform", "curvature"}))
      ->capture_default_str();
  cmd->add_option("--priority", opt->priority,
                  "distance (default): the fitting spends what the CVT's worst triangle allows on the distance to "
                  "the input; shape: the worst triangles' vertices first move towards their neighbours, which "
                  "raises the worst triangle and leaves the fitting less room on the bends")
      ->check(CLI::IsMember({"distance", "shape"}))
      ->capture_default_str();
  cmd->add_option("--repair-scope", opt->repair,
                  "whole (default): every repair round re-optimises every sample; local: after two whole rounds, "
                  "a round re-optimises only the samples near the dual's defects, on the part of the surface round "
                  "them (faster where many rounds are needed, with worse triangles where it ends the repair)")
      ->check(CLI::IsMember({"local", "whole"}))
      ->capture_default_str();
  cmd->add_flag("--no-fit", opt->no_fit,
                "Keep the vertices at the CVT samples (default: fit them to the planes of their cells, "
                "never lowering the CVT's worst triangle)");
  cmd->add_option("-o,--output", opt->output, "Output mesh (.off, .obj, .ply)")->required()->check(path_validator());
  cmd->add_option("--report", opt->report, "Write a JSON report")->check(path_validator());
  return [opt]() { return run_remesh(*opt); };
}

Action add_quality_command(CLI::App& app) {
  auto opt = std::make_shared<QualityOptions>();
  CLI::App* cmd = app.add_subcommand("quality", "Quality metrics and validity of any remesh against its reference");
  cmd->add_option("reference", opt->reference, "The input surface")->required()->check(path_validator());
  // Not required by CLI11, whose "mesh is required" reads oddly after one mesh was given.
  cmd->add_option("mesh", opt->mesh, "The remesh to measure (required; may be non-manifold)")->check(path_validator());
  add_repair_options(cmd, opt->read, "the reference (as for the remesh)");
  cmd->add_option("--report", opt->report, "Write a JSON report")->check(path_validator());
  return [opt]() { return run_quality(*opt); };
}

}  // namespace lrvd::cli
