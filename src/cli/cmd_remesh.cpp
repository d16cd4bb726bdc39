// `lrvd remesh` (CVT on the LRVD, output the dual with exactly N vertices, checked) and
// `lrvd quality` (the metrics alone, for any remesher's output).
#include "cli/cmd_remesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include <fmt/format.h>

#include "cli/common.h"
#include "common/error.h"
#include "diagram/dual.h"
#include "io/mesh_writers.h"
#include "metrics/quality.h"
#include "predicates/predicates.h"
#include "remesh/remesh.h"
#include "report/remesh_report.h"
#include "verification/remesh_check.h"
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
  RemeshSettings settings;
  bool no_fit = false;
  std::string output, report;
};

// Where the repair gave up, on the input surface, and what to try: a thin part or a handle too
// small for the cells.
void print_repair_advice(const RemeshRun& run) {
  const RemeshResult& remeshed = run.result;
  const ClosedOverHoles& holes = run.holes;
  const DualDefects& left = remeshed.defects;
  const int first = left.where_to_act().empty() ? -1 : left.where_to_act().front();
  std::string where;
  if (first >= 0) {
    const Vec3& p = remeshed.cvt.samples.positions[first];
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
  if (const NarrowPart& narrow = run.narrow; narrow.vertex >= 0) {
    const Vec3& p = remeshed.cvt.samples.positions[narrow.vertex];
    const long long given = static_cast<long long>(remeshed.cvt.samples.size());
    const std::string cells = narrow.other < 0 ? fmt::format("the cell of vertex {} wraps", narrow.vertex)
                                               : fmt::format("the cells of vertices {} and {} wrap", narrow.vertex,
                                                             narrow.other);
    std::printf("repair: %s a part about %.3g round (%.3g %% of the bounding-box diagonal) at (%.6g, %.6g, %.6g): a "
                "uniform density fits three cells round it from about %lld vertices (%lld given); the repair, "
                "denser there, may need fewer\n",
                cells.c_str(), narrow.around, 100 * narrow.around / run.diagonal, p.x, p.y, p.z,
                narrow.uniform_vertices, given);
  }
}

// Holes of the input too small for the cells: how many, and the --fill-holes that closes them.
void print_hole_advice(const ClosedOverHoles& holes, double diagonal) {
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
// For those, the command that draws the triangles each failed check is about, coloured: the
// picture goes beside the output (a file, not a device such as /dev/null), named after it, unless
// that name (with the writer's part suffix) is longer than a file name can be.
void print_defects_picture_command(const RemeshVerification& check, const DualMesh& dual, const std::string& output) {
  const bool drawable = !check.manifold.passed || !check.closed.passed || !check.non_degenerate.passed ||
                        !check.no_self_intersection.passed || !check.vertex_count.passed;
  std::error_code not_a_file;
  if (!drawable || dual.triangles.empty() || !std::filesystem::is_regular_file(output, not_a_file)) return;
  namespace fs = std::filesystem;
  fs::path picture = fs::path(output).replace_extension().string() + "_defects.png";
  if (picture.filename().string().size() + std::string(".lrvd-part").size() > 255)
    picture = fs::path(output).parent_path() / "lrvd_defects.png";
  // A path read as an option when it begins with '-'.
  auto argument = [](const std::string& path) { return shell_word(path.rfind('-', 0) == 0 ? "./" + path : path); };
  std::printf("see where: lrvd render %s --color defects -o %s\n", argument(output).c_str(),
              argument(picture.string()).c_str());
}

int run_remesh_command(const RemeshCommandOptions& opt) {
  RemeshSettings settings = opt.settings;
  settings.fit = !opt.no_fit;
  check_remesh_settings(settings);
  if (opt.output.empty()) throw InputError("give an output file with -o");
  check_outputs({{opt.output, "-o", kMeshWriteExtensions}, {opt.report, "--report", {}, kMeshReadExtensions}},
                read_files(opt.input));
  InputOptions read = opt.input;
  read.check_count = require_remesh_vertex_count;  // before sampling, which asks one per component
  Input input = load_input(read);
  const RemeshRun run = run_remesh(input, settings, opt.input.points_path.empty(), opt.input.seed, opt.input.mesh_path,
                             opt.output, progress,
                             [&](const DualMesh& dual) { write_mesh(opt.output, dual.positions, dual.triangles); });
  const RemeshResult& remeshed = run.result;
  const DualMesh& dual = remeshed.dual;
  const RemeshVerification& check = run.check;
  if (!opt.report.empty()) write_report(opt.report, run.report, {opt.output});

  std::printf("remesh (%s): %s, %s, %s, %.3f s -> %s\n", settings.kind.c_str(),
              counted(dual.positions.size(), "vertex", "vertices").c_str(),
              counted(dual.triangles.size(), "triangle", "triangles").c_str(),
              counted(remeshed.total_iterations, "iteration", "iterations").c_str(), remeshed.time_s, opt.output.c_str());
  print_quality(run.measurable ? &run.quality : nullptr, false);
  std::printf("verification: %s%s\n", check.passed ? "passed" : "FAILED", inherited_note(check).c_str());
  if (!check.passed) std::fputs(check.summary().c_str(), stdout);
  if (!check.passed && !remeshed.defects.empty()) print_repair_advice(run);
  if (!check.passed && run.holes.count > 0) print_hole_advice(run.holes, run.diagonal);
  print_defects_picture_command(check, dual, opt.output);
  return check.passed ? kOk : kCheckFailed;
}

struct QualityOptions {
  std::string reference, mesh, report;
  ReadOptions read;  //!< of the reference, as the remesh's input was
};

int run_quality_command(const QualityOptions& opt) {
  if (opt.mesh.empty()) throw InputError("give the mesh to measure after the reference: lrvd quality REFERENCE MESH");
  check_outputs({{opt.report, "--report", {}, kMeshReadExtensions}},
                {{opt.reference, "the reference mesh"}, {opt.mesh, "the measured mesh"}});
  const LoadedMesh loaded = read_mesh(opt.reference, opt.read);
  print_repair(loaded.repair, opt.read);
  const SurfaceMesh& reference = loaded.mesh;
  const PolygonSoup soup = read_polygon_soup(opt.mesh, true);
  const QualityRun run = run_quality(loaded, opt.read.repair, soup, opt.reference, opt.mesh);
  const bool measurable = run.measurable;
  const QualityMetrics& quality = run.quality;
  const RemeshVerification& check = run.check;
  const std::string& frame = run.frame_warning;
  const nlohmann::json& report = run.report;
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
  cmd->add_option("--diagram", opt->settings.kind, "Diagram of the CVT: lrvd (default) or rvd (the baseline)")
      ->check(CLI::IsMember({"lrvd", "rvd"}))
      ->capture_default_str();
  cmd->add_option("--optimizer", opt->settings.optimizer, "lbfgs or lloyd")->check(CLI::IsMember({"lbfgs", "lloyd"}))->capture_default_str();
  cmd->add_option("--iterations", opt->settings.iterations,
                  "Iteration cap of the first CVT, which usually stops there: more iterations give better "
                  "triangles, for more time (each repair round of a dual with defects runs up to 30 more, and 10 "
                  "more try the rounds' density eased back; with L-BFGS, a state without defects then takes one "
                  "Lloyd step)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--density", opt->settings.density,
                  "uniform, or curvature: smaller cells where the surface bends (at a few hundred vertices "
                  "uniform does better)")
      ->check(CLI::IsMember({"uniform", "curvature"}))
      ->capture_default_str();
  cmd->add_option("--priority", opt->settings.priority,
                  "distance (default): the fitting spends what the CVT's worst triangle allows on the distance to "
                  "the input; shape: the worst triangles' vertices first move towards their neighbours, which "
                  "raises the worst triangle and leaves the fitting less room on the bends")
      ->check(CLI::IsMember({"distance", "shape"}))
      ->capture_default_str();
  cmd->add_option("--repair-scope", opt->settings.repair_scope,
                  "whole (default): every repair round re-optimises every sample; local: after two whole rounds, "
                  "a round re-optimises only the samples near the dual's defects, on the part of the surface round "
                  "them (faster where many rounds are needed, with worse triangles where it ends the repair)")
      ->check(CLI::IsMember({"whole", "local"}))
      ->capture_default_str();
  cmd->add_flag("--no-fit", opt->no_fit,
                "Keep the vertices at the CVT samples (default: fit them to the planes of their cells, "
                "never lowering the CVT's worst triangle)");
  cmd->add_option("-o,--output", opt->output, "Output mesh (.off, .obj, .ply)")->required()->check(path_validator());
  cmd->add_option("--report", opt->report, "Write a JSON report")->check(path_validator());
  return [opt]() { return run_remesh_command(*opt); };
}

Action add_quality_command(CLI::App& app) {
  auto opt = std::make_shared<QualityOptions>();
  CLI::App* cmd = app.add_subcommand("quality", "Quality metrics and validity of any remesh against its reference");
  cmd->add_option("reference", opt->reference, "The input surface")->required()->check(path_validator());
  // Not required by CLI11, whose "mesh is required" reads oddly after one mesh was given.
  cmd->add_option("mesh", opt->mesh, "The remesh to measure (required; may be non-manifold)")->check(path_validator());
  add_repair_options(cmd, opt->read, "the reference (as for the remesh)");
  cmd->add_option("--report", opt->report, "Write a JSON report")->check(path_validator());
  return [opt]() { return run_quality_command(*opt); };
}

}  // namespace lrvd::cli
