// `lrvd stress`: list and write the stress meshes (nearby sheets, thin walls, tubes, ...).
#include "cli/cmd_stress.h"

#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "cli/common.h"
#include "common/error.h"
#include "io/mesh_writers.h"
#include "mesh/refine.h"
#include "mesh/stress.h"
#include "render/render.h"
#include "render/render_scenes.h"
#include "verification/diagram_check.h"
#include "voronoi/lrvd.h"
#include "voronoi/rvd.h"

namespace lrvd::cli {

namespace {

// RVD against LRVD on every stress mesh and sample count: the disconnected cells of the RVD and
// the verification of the LRVD, as markdown and JSON tables.
int write_stress_report(const std::string& dir, double scale, int seeds) {
  // The folder itself is made, not its parents: a mistyped path is refused, as for every other output.
  namespace fs = std::filesystem;
  std::error_code error;
  fs::path folder = fs::path(dir).lexically_normal();
  if (!folder.has_filename()) folder = folder.parent_path();  // "out/"
  const fs::path parent = folder.parent_path();
  if (!parent.empty() && !fs::is_directory(parent, error))
    throw InputError(fmt::format("--report {}: the folder {} does not exist", dir, parent.string()));
  fs::create_directory(dir, error);
  if (error || !std::filesystem::is_directory(dir))
    throw InputError(fmt::format("cannot make the report directory {}: {}", dir,
                                 error ? error.message() : "a file of that name is in the way"));
  nlohmann::json rows = nlohmann::json::array();
  std::string md =
      "| mesh | triangles | n | RVD disconnected cells | RVD time (s) | LRVD disconnected cells | LRVD verified | "
      "LRVD time (s) |\n|---|---|---|---|---|---|---|---|\n";
  bool all_passed = true;
  constexpr int kPictureSamples = 100;
  std::string pictures = "| mesh | LRVD | RVD |\n|---|---|---|\n";
  for (const StressMeshInfo& info : stress_mesh_catalog()) {
    const SurfaceMesh base = make_stress_mesh(info.name, scale);
    for (int n : {10, 30, 100, 300, 1000}) {
      if (n < base.component_count()) continue;
      const double length = suggested_refinement_length(base, n);
      const SurfaceMesh mesh = length > 0 && base.max_edge_length() > length ? refine_long_edges(base, length) : base;
      double rvd_time = 0, lrvd_time = 0, rvd_disconnected = 0, lrvd_disconnected = 0;
      int verified = 0;
      for (int seed = 1; seed <= seeds; ++seed) {
        progress(fmt::format("{} n={} seed={}", info.name, n, seed));
        const Samples samples = sample_uniform(mesh, n, seed);
        const Diagram rvd = compute_rvd(mesh, samples);
        const Diagram lrvd = compute_lrvd(mesh, samples);
        if (n == kPictureSamples && seed == 1) {
          // The two diagrams side by side, stray pieces hatched (docs/reference/render.md).
          RenderOptions view;
          view.width = 480;
          view.height = 360;
          for (const auto& [diagram, kind] : {std::pair<const Diagram&, const char*>{lrvd, "lrvd"}, {rvd, "rvd"}})
            write_png(fmt::format("{}/{}_{}.png", dir, info.name, kind),
                      render(diagram_scene(diagram, mesh, samples).scene, view));
          pictures += fmt::format("| {} | ![{} LRVD]({}_lrvd.png) | ![{} RVD]({}_rvd.png) |\n", info.name, info.name,
                                  info.name, info.name, info.name);
        }
        for (int c : cell_components(rvd, mesh).count) rvd_disconnected += c > 1;
        const DiagramVerification check = verify_diagram(mesh, samples, lrvd);
        lrvd_disconnected += check.cells_with_multiple_components;
        verified += check.passed;
        rvd_time += rvd.stats.time_s;
        lrvd_time += lrvd.stats.time_s;
      }
      all_passed = all_passed && verified == seeds;
      rows.push_back({{"mesh", info.name}, {"triangles", mesh.triangle_count()}, {"n", n}, {"seeds", seeds},
                      {"rvd_disconnected_cells_mean", rvd_disconnected / seeds}, {"rvd_time_s_mean", rvd_time / seeds},
                      {"lrvd_disconnected_cells_mean", lrvd_disconnected / seeds}, {"lrvd_verified", verified},
                      {"lrvd_time_s_mean", lrvd_time / seeds}});
      md += fmt::format("| {} | {} | {} | {:.1f} | {:.4f} | {:.1f} | {}/{} | {:.4f} |\n", info.name,
                        mesh.triangle_count(), n, rvd_disconnected / seeds, rvd_time / seeds,
                        lrvd_disconnected / seeds, verified, seeds, lrvd_time / seeds);
    }
  }
  write_json(dir + "/stress_report.json", {{"scale", scale}, {"seeds", seeds}, {"rows", rows}});
  write_text_file(dir + "/stress_report.md",
                  fmt::format("# RVD vs LRVD on the stress meshes\n\nMeans over {} seed(s); meshes refined where n "
                              "would crowd the triangles.\n\n{}\n## Pictures\n\nThe cells of {} samples (seed 1), "
                              "drawn by `lrvd render`: each cell in its own colour, the pieces of a cell away from its "
                              "sample hatched.\n\n{}",
                              seeds, md, kPictureSamples, pictures));
  std::printf("%s", md.c_str());
  std::printf("wrote %s/stress_report.md, %s/stress_report.json and the pictures NAME_lrvd.png, NAME_rvd.png\n",
              dir.c_str(), dir.c_str());
  return all_passed ? kOk : kCheckFailed;
}

}  // namespace

Action add_stress_command(CLI::App& app) {
  struct Options {
    bool list = false;
    std::string name, output, report_dir;
    double scale = 1.0;
    int seeds = 1;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("stress", "Stress meshes: list them, write one, or report RVD vs LRVD on all");
  CLI::Option* list = cmd->add_flag("--list", opt->list, "List the stress meshes");
  CLI::Option* name = cmd->add_option("name", opt->name, "Stress mesh to write");
  CLI::Option* output =
      cmd->add_option("-o,--output", opt->output, "Output mesh file (.off, .obj, .ply)")->check(path_validator());
  CLI::Option* scale = cmd->add_option("--scale", opt->scale, "Resolution scale (multiplies subdivision counts)")
                           ->check(CLI::Range(0.05, 10.0))
                           ->capture_default_str();
  CLI::Option* report = cmd->add_option("--report", opt->report_dir, "Compute RVD and LRVD on every stress mesh, write tables to DIR")
                             ->check(path_validator());
  cmd->add_option("--seeds", opt->seeds, "Seeds per (mesh, n) for --report")
      ->check(CLI::Range(1, 100))
      ->needs(report)
      ->capture_default_str();
  // The three uses exclude each other: a listing, one mesh written, or the report over all.
  list->excludes(name)->excludes(output)->excludes(report)->excludes(scale);
  report->excludes(name)->excludes(output);
  return [opt]() -> int {
    if (!opt->report_dir.empty()) return write_stress_report(opt->report_dir, opt->scale, opt->seeds);
    if (opt->list) {
      for (const StressMeshInfo& info : stress_mesh_catalog())
        std::printf("%-26s %s\n", info.name.c_str(), info.description.c_str());
      return kOk;
    }
    if (opt->name.empty()) throw InputError("name a stress mesh (see `lrvd stress --list`)");
    if (opt->output.empty()) throw InputError("give an output file with -o");
    check_outputs({{opt->output, "-o", kMeshWriteExtensions}});
    const SurfaceMesh mesh = make_stress_mesh(opt->name, opt->scale);
    write_mesh(opt->output, mesh);
    std::printf("%s: %s, %s -> %s\n", opt->name.c_str(), counted(mesh.vertex_count(), "vertex", "vertices").c_str(),
                counted(mesh.triangle_count(), "triangle", "triangles").c_str(), opt->output.c_str());
    return kOk;
  };
}

}  // namespace lrvd::cli
