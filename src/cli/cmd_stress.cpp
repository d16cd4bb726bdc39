// `lrvd stress`: list and write the stress meshes (nearby sheets, thin walls, tubes, ...).
#include <cstdio>

#include <fmt/format.h>

#include "cli/commands.h"
#include "common/error.h"
#include "mesh/mesh_io.h"
#include "mesh/stress.h"

namespace lrvd::cli {

Action add_stress_command(CLI::App& app) {
  struct Options {
    bool list = false;
    std::string name, output, report_dir;
    double scale = 1.0;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("stress", "Stress meshes: list them, write one, or report RVD vs LRVD on all");
  cmd->add_flag("--list", opt->list, "List the stress meshes");
  cmd->add_option("name", opt->name, "Stress mesh to write");
  cmd->add_option("-o,--output", opt->output, "Output mesh file (.off, .obj, .ply)");
  cmd->add_option("--scale", opt->scale, "Resolution scale (multiplies subdivision counts)")->check(CLI::PositiveNumber);
  return [opt]() -> int {
    if (opt->list) {
      for (const StressMeshInfo& info : stress_mesh_catalog())
        std::printf("%-26s %s\n", info.name.c_str(), info.description.c_str());
      return kOk;
    }
    if (opt->name.empty()) throw InputError("name a stress mesh (see `lrvd stress --list`)");
    if (opt->output.empty()) throw InputError("give an output file with -o");
    const SurfaceMesh mesh = make_stress_mesh(opt->name, opt->scale);
    write_mesh(opt->output, mesh);
    std::printf("%s: %d vertices, %d triangles -> %s\n", opt->name.c_str(), mesh.vertex_count(),
                mesh.triangle_count(), opt->output.c_str());
    return kOk;
  };
}

}  // namespace lrvd::cli
