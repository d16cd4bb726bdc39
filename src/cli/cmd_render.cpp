// `lrvd render`: a PNG of a mesh, or of the cells of a diagram of samples on it (stray pieces
// hatched, so an RVD's broken cells show beside the LRVD's whole ones).
#include "cli/cmd_render.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include <fmt/format.h>

#include "cli/common.h"
#include "common/error.h"
#include "render/render.h"
#include "render/render_scenes.h"
#include "voronoi/lrvd.h"

namespace lrvd::cli {

namespace {

struct RenderCommandOptions {
  InputOptions input;
  std::string kind = "lrvd";
  std::string output;
  std::string size = "1200x900";
  std::string view = "30,20";
  std::string up = "y";
  std::string color = "plain";
  bool edges = false;
  bool no_samples = false;
};

// "1200x900" -> width and height; "30,20" -> azimuth and elevation.
void parse_size(const std::string& text, RenderOptions& o) {
  std::istringstream in(text);
  char x = 0;
  std::string rest;
  if (!(in >> o.width >> x >> o.height) || (x != 'x' && x != 'X') || (in >> rest))
    throw InputError(fmt::format("--size takes WIDTHxHEIGHT in pixels, such as 1200x900, not '{}'", text));
  if (o.width < 16 || o.width > 4096 || o.height < 16 || o.height > 4096)
    throw InputError(fmt::format("--size: a picture is 16 to 4096 pixels wide and high, not {}", text));
}

void parse_view(const std::string& text, RenderOptions& o) {
  std::istringstream in(text);
  char comma = 0;
  std::string rest;
  if (!(in >> o.azimuth >> comma >> o.elevation) || comma != ',' || (in >> rest) || !std::isfinite(o.azimuth))
    throw InputError(fmt::format("--view takes AZIMUTH,ELEVATION in degrees, such as 30,20, not '{}'", text));
  if (!(o.elevation >= -90 && o.elevation <= 90))
    throw InputError(fmt::format("--view: the elevation is -90 to 90 degrees, not {}", o.elevation));
}

// Options that only mean something for a diagram, refused without samples rather than dropped.
void refuse_diagram_options_without_samples(const CLI::App& cmd) {
  if (cmd.count("--samples") > 0)
    throw InputError("give a sample count -n >= 1, or leave -n out to draw the mesh alone");
  for (const char* name : {"--diagram", "--weights", "--seed", "--refine", "--no-samples"})
    if (cmd.count(name) > 0)
      throw InputError(fmt::format("{} is for the cells of samples: give -n N or --points F, or leave it out to draw "
                                   "the mesh alone",
                                   name));
}

int run_render(const RenderCommandOptions& opt, const CLI::App& cmd) {
  RenderOptions view;
  parse_size(opt.size, view);
  parse_view(opt.view, view);
  set_up_axis(opt.up, view);
  view.edges = opt.edges;
  const DiagramKind kind = diagram_kind_from_string(opt.kind);
  check_outputs({{opt.output, "-o", {".png"}}}, read_files(opt.input));
  const bool cells = opt.input.count > 0 || !opt.input.points_path.empty();
  if (!cells) refuse_diagram_options_without_samples(cmd);
  if (cells && opt.color != "plain")
    throw InputError(fmt::format("--color {} colours a mesh's triangles: it takes no samples (-n, --points), whose cells "
                                 "have colours of their own",
                                 opt.color));
  const bool repair = opt.input.read.repair || opt.input.read.weld > 0 || opt.input.read.fill_holes > 0;

  RenderScene scene;
  std::string what;
  bool colored = false;
  if (!cells) {
    if (repair) {
      scene = mesh_scene(load_mesh(opt.input).mesh);
    } else {
      // As read, without the checks a diagram needs: a remesh that failed them is what one wants to see.
      const PolygonSoup soup = read_polygon_soup(opt.input.mesh_path, false, true);
      scene = mesh_scene(soup.positions, soup.triangles);
      if (!soup.face_color.empty() && opt.color == "plain") {
        // A PLY with face colours (lrvd compute's cells): drawn in them, with a line where the
        // colour changes (neighbouring cells have different colours).
        scene.color = soup.face_color;
        for (const Rgb& c : scene.color) scene.region.push_back(c[0] << 16 | c[1] << 8 | c[2]);
        colored = true;
      }
    }
    what = counted(static_cast<long long>(scene.triangles.size()), "triangle", "triangles");
    if (colored) what += " in the file's face colours";
    if (opt.color == "quality") what += fmt::format(" coloured by quality (worst Q {:.3f})", color_by_quality(scene));
    if (opt.color == "defects") {
      progress("looking for the triangles that cross others");
      const MeshDefectCounts d = color_by_defects(scene);
      what += fmt::format(", {} degenerate (dark red), {} on non-manifold edges or repeated (red), {} crossing others "
                          "(orange), {} on the boundary (blue), {} in no triangle (dots)",
                          d.degenerate, d.non_manifold, d.crossing, d.boundary,
                          counted(d.unused_vertices, "vertex", "vertices"));
    }
  } else {
    Input input = load_input(opt.input);
    check_diagram_samples(input, opt.kind);
    progress(fmt::format("computing the {} of {} samples", opt.kind, input.samples.size()));
    const Diagram diagram = compute_input_diagram(input, kind);
    DiagramScene cells_scene = diagram_scene(diagram, input.mesh, input.samples);
    scene = std::move(cells_scene.scene);
    if (opt.no_samples) scene.points.clear();
    what = fmt::format("{} {} cells on {}, {} in several pieces{}", input.samples.size(), opt.kind,
                       counted(input.mesh.triangle_count(), "triangle", "triangles"),
                       counted(cells_scene.cells_in_pieces, "cell", "cells"),
                       cells_scene.stray_polygons > 0
                           ? fmt::format(" (their {} away from the sample hatched)",
                                         counted(cells_scene.stray_polygons, "polygon", "polygons"))
                           : std::string());
  }
  progress(fmt::format("drawing {} x {} pixels", view.width, view.height));
  write_png(opt.output, render(scene, view));
  std::printf("render: %s, %d x %d -> %s\n", what.c_str(), view.width, view.height, opt.output.c_str());
  return kOk;
}

}  // namespace

Action add_render_command(CLI::App& app) {
  auto opt = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Draw a mesh, or the cells of a diagram on it, as a PNG");
  add_input_options(cmd, opt->input, true);
  cmd->add_option("--diagram", opt->kind, "Diagram of the samples: lrvd, rvd, lrpd (power, weighted) or rpd")
      ->check(CLI::IsMember({"lrvd", "rvd", "lrpd", "rpd"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", opt->output, "The picture (.png)")->required()->check(path_validator());
  cmd->add_option("--size", opt->size, "WIDTHxHEIGHT in pixels, 16 to 4096 each")->capture_default_str();
  cmd->add_option("--view", opt->view,
                  "AZIMUTH,ELEVATION in degrees: about the up axis from the next axis (+z for up y), then "
                  "towards the up axis")
      ->capture_default_str();
  cmd->add_option("--up", opt->up, "The axis drawn upwards: x, y, z, -x, -y or -z")->capture_default_str();
  cmd->add_option("--color", opt->color,
                  "Colour of a mesh drawn without samples: plain; quality (each triangle's Q: red below 0.3, "
                  "orange 0.5, yellow 0.7, grey from 0.9); or defects (degenerate triangles dark red, on non-manifold "
                  "edges red, crossing others orange, on the boundary blue)")
      ->check(CLI::IsMember({"plain", "quality", "defects"}))
      ->capture_default_str();
  cmd->add_flag("--edges", opt->edges, "Draw the mesh's edges too");
  cmd->add_flag("--no-samples", opt->no_samples, "Leave out the dots of the samples");
  return [opt, cmd]() { return run_render(*opt, *cmd); };
}

}  // namespace lrvd::cli
