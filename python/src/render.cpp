// lrvd.render: the picture `lrvd render` draws, as an (h, w, 3) uint8 array.
// Its one function, add_render, is declared in module.cpp, which calls it: no header.
#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <tbb/global_control.h>

#include "arrays.h"
#include "common/error.h"
#include "render/render.h"
#include "render/render_scenes.h"
#include "report/report.h"
#include "voronoi/lrvd.h"

namespace lrvd::python {

namespace {

RenderOptions view_options(const std::pair<int, int>& size, const std::pair<double, double>& view, const std::string& up,
                           bool edges) {
  RenderOptions o;
  o.width = size.first;
  o.height = size.second;
  if (o.width < 16 || o.width > 4096 || o.height < 16 || o.height > 4096)
    throw InputError(fmt::format("--size: a picture is 16 to 4096 pixels wide and high, not {}x{}", o.width, o.height));
  o.azimuth = view.first;
  o.elevation = view.second;
  if (!std::isfinite(o.azimuth))
    throw InputError(fmt::format("--view takes AZIMUTH,ELEVATION in degrees, such as 30,20, not '{},{}'", view.first,
                                 view.second));
  if (!(o.elevation >= -90 && o.elevation <= 90))
    throw InputError(fmt::format("--view: the elevation is -90 to 90 degrees, not {}", o.elevation));
  set_up_axis(up, o);
  o.edges = edges;
  return o;
}

py::array_t<unsigned char> image_array(Image&& image) {
  auto* owned = new std::vector<unsigned char>(std::move(image.rgb));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<unsigned char>*>(p); });
  return py::array_t<unsigned char>({py::ssize_t{image.height}, py::ssize_t{image.width}, py::ssize_t{3}},
                                    owned->data(), owner);
}

}  // namespace

py::array_t<unsigned char> render_py(const py::object& V, const py::object& F, const py::object& points,
                                     const py::object& n, const py::object& seed, const std::string& diagram,
                                     const py::object& weights, const std::pair<int, int>& size,
                                     const std::pair<double, double>& view, const std::string& up,
                                     const std::string& color, bool edges, bool show_samples,
                                     const std::string& refine, const py::object& threads) {
  const RenderOptions options = view_options(size, view, up, edges);
  const DiagramKind kind = diagram_kind_from_string(diagram);
  if (color != "plain" && color != "quality" && color != "defects")
    throw InputError(fmt::format("--color is plain, quality or defects, not '{}'", color));
  const bool cells = !points.is_none() || !n.is_none();
  if (cells && color != "plain")
    throw InputError(fmt::format("--color {} colours a mesh's triangles: it takes no samples (-n, --points), whose cells "
                                 "have colours of their own",
                                 color));
  ThreadLimit limit(threads);
  Image image;
  if (!cells) {
    // As given, without the checks a diagram needs: a remesh that failed them is what one wants to see.
    std::vector<Vec3> positions = to_points(V, "V", 1);
    std::vector<std::array<int, 3>> triangles = to_triangles(F, positions.size(), "F");
    py::gil_scoped_release release;
    RenderScene scene = mesh_scene(positions, triangles);
    if (color == "quality") color_by_quality(scene);
    if (color == "defects") color_by_defects(scene);
    image = render(scene, options);
  } else {
    Input input = diagram_input(V, F, points, n, seed, weights, refine);
    check_diagram_weights(input.samples, diagram);
    py::gil_scoped_release release;
    const Diagram d = compute_diagram(input.mesh, input.samples, kind);
    RenderScene scene = diagram_scene(d, input.mesh, input.samples).scene;
    if (!show_samples) scene.points.clear();
    image = render(scene, options);
  }
  return image_array(std::move(image));
}

void add_render(py::module_& m) {
  m.def("render", &render_py, py::arg("V"), py::arg("F"), py::arg("points") = py::none(), py::arg("n") = py::none(),
        py::arg("seed") = 1, py::arg("diagram") = "lrvd", py::arg("weights") = py::none(),
        py::arg("size") = std::pair<int, int>{1200, 900}, py::arg("view") = std::pair<double, double>{30, 20},
        py::arg("up") = "y", py::arg("color") = "plain", py::arg("edges") = false, py::arg("show_samples") = true,
        py::arg("refine") = "auto", py::arg("threads") = py::none(),
        "The picture `lrvd render` draws of the mesh, or of the cells of `points` or `n` samples: (h, w, 3) uint8");
}

}  // namespace lrvd::python
