// The `lrvd` Python module: the command's subcommands as functions of NumPy arrays, returning
// arrays and the command's JSON reports as dicts (docs/guide/python.md).
// The module's entry point: no header.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <tbb/global_control.h>

#include "arrays.h"
#include "common/error.h"
#include "diagram/cells_output.h"
#include "io/mesh_writers.h"
#include "mesh/stress.h"
#include "predicates/predicates.h"
#include "render/render.h"
#include "report/mps_report.h"
#include "report/remesh_report.h"
#include "report/report.h"
#include "verification/diagram_check.h"
#include "voronoi/lrvd.h"

namespace lrvd::python {

namespace {

using py::arg;

// A real number, or a TypeError naming the argument.
double number(const py::object& value, const char* name) {
  if (!py::isinstance<py::float_>(value) && !py::isinstance<py::int_>(value))
    throw py::type_error(fmt::format("{} must be a number, not {}", name, py::repr(value).cast<std::string>()));
  return value.cast<double>();
}

// A diagram of samples on a mesh, its cells as arrays, its report.
class PyDiagram {
 public:
  PyDiagram(Input input, std::string kind) : input_(std::move(input)), kind_(std::move(kind)) {}

  void compute() {
    reset_predicate_stats();
    diagram_ = compute_input_diagram(input_, diagram_kind_from_string(kind_), &components_);
    report_ = compute_report(input_, "", kind_, diagram_, components_);
    report_["verification"] = nullptr;
  }
  // Runs the exact verification; a failed property is in the report, not an exception.
  py::object verify(const py::object& threads) {
    ThreadLimit limit(threads);
    {
      py::gil_scoped_release release;
      const DiagramVerification check = verify_diagram(input_.mesh, input_.samples, diagram_);
      report_["verification"] = check.to_json();
      passed_ = check.passed;
    }
    return to_python(report_["verification"]);
  }
  py::object report() const { return to_python(report_); }
  std::optional<bool> passed() const { return passed_; }
  const std::string& kind() const { return kind_; }
  int cells_in_pieces() const { return lrvd::cells_in_pieces(components_); }
  py::tuple mesh() const {
    return py::make_tuple(points_array(std::vector<Vec3>(input_.mesh.positions())),
                          triangles_array(std::vector<Triangle>(input_.mesh.triangles())));
  }
  py::array_t<double> samples() const { return points_array(std::vector<Vec3>(input_.samples.positions)); }
  // Polygons: vertices (p, 3), the polygons' corners one after the other, offsets into them, and per
  // polygon its cell, its triangle of mesh() and its piece of the cell.
  py::dict cells() const {
    if (cells_) return *cells_;
    PolygonMesh polygons;
    {
      py::gil_scoped_release release;
      polygons = diagram_polygon_mesh(diagram_, input_.mesh);
    }
    std::vector<std::int64_t> offsets{0};
    std::vector<int> corners, triangle;
    for (const std::vector<int>& face : polygons.faces) {
      corners.insert(corners.end(), face.begin(), face.end());
      offsets.push_back(static_cast<std::int64_t>(corners.size()));
    }
    for (const CellPolygon& p : diagram_.polygons) triangle.push_back(p.triangle);
    py::dict d;
    d["vertices"] = points_array(std::move(polygons.positions));
    d["polygon_offsets"] = values_array(std::move(offsets));
    d["polygon_vertices"] = values_array(std::move(corners));
    d["polygon_cell"] = values_array(std::move(polygons.face_cell));
    d["polygon_triangle"] = values_array(std::move(triangle));
    d["polygon_component"] = values_array(std::vector<int>(components_.polygon_component));
    d["cell_components"] = values_array(std::vector<int>(components_.count));
    cells_ = d;
    return d;
  }

 private:
  Input input_;
  std::string kind_;
  Diagram diagram_;
  CellComponents components_;
  nlohmann::json report_;
  std::optional<bool> passed_;
  mutable std::optional<py::dict> cells_;  //!< made on first use
};

std::shared_ptr<PyDiagram> compute(const py::object& V, const py::object& F, const py::object& points,
                                   const py::object& n, const py::object& seed, const std::string& diagram,
                                   const py::object& weights, bool verify, const std::string& refine,
                                   const py::object& threads) {
  diagram_kind_from_string(diagram);
  ThreadLimit limit(threads);
  Input input = diagram_input(V, F, points, n, seed, weights, refine);
  check_diagram_weights(input.samples, diagram);
  auto result = std::make_shared<PyDiagram>(std::move(input), diagram);
  {
    py::gil_scoped_release release;
    result->compute();
  }
  if (verify) result->verify(py::none());
  return result;
}

py::tuple read_mesh_py(const std::string& path, bool repair, const py::object& weld, const py::object& fill_holes) {
  ReadOptions read;
  read.repair = repair;
  auto fraction = [](const py::object& value, const char* name) {
    const double x = number(value, name);
    if (!(x > 0) || !std::isfinite(x))
      throw InputError(fmt::format("{}: a positive fraction of the bounding-box diagonal, not '{}'", name, x));
    return x;
  };
  if (!weld.is_none()) {
    read.weld = fraction(weld, "weld");
    read.repair = true;
  }
  if (!fill_holes.is_none()) read.fill_holes = fraction(fill_holes, "fill_holes");
  LoadedMesh loaded;
  {
    py::gil_scoped_release release;
    loaded = read_mesh(path, read);
  }
  return py::make_tuple(points_array(std::vector<Vec3>(loaded.mesh.positions())),
                        triangles_array(std::vector<Triangle>(loaded.mesh.triangles())));
}

void write_mesh_py(const std::string& path, const py::object& V, const py::object& F) {
  std::vector<Vec3> positions = to_points(V, "V", 0);
  std::vector<Triangle> triangles = to_triangles(F, positions.size(), "F");
  py::gil_scoped_release release;
  write_mesh(path, positions, triangles);
}

py::tuple remesh(const py::object& V, const py::object& F, const py::object& n, const py::object& seed,
                 const std::string& diagram, const std::string& optimizer, const std::string& density,
                 const std::string& priority, const std::string& repair_scope, int iterations, bool fit,
                 const std::string& refine, const py::object& threads) {
  RemeshSettings settings;
  settings.kind = diagram;
  settings.optimizer = optimizer;
  settings.density = density;
  settings.priority = priority;
  settings.repair_scope = repair_scope;
  settings.iterations = iterations;
  settings.fit = fit;
  check_remesh_settings(settings);
  ThreadLimit limit(threads);
  Input input;
  input.loaded = loaded_mesh(V, F);
  SampleRequest request;
  request.count = sample_count(n, "a vertex count is a whole number");
  request.seed = to_seed(seed);
  request.refine = refine;
  request.mesh_name = "the mesh";
  request.check_count = require_remesh_vertex_count;
  RemeshRun run;
  {
    py::gil_scoped_release release;
    require_workable_model(input.loaded.mesh, "lrvd");
    prepare_samples(input, request);
    run = run_remesh(input, settings, true, request.seed, "", "", nullptr, nullptr);
  }
  DualMesh& dual = run.result.dual;
  return py::make_tuple(points_array(std::move(dual.positions)), triangles_array(std::move(dual.triangles)),
                        to_python(run.report));
}

py::tuple mps(const py::object& V, const py::object& F, double radius, bool adaptive, const py::object& max_radius_ratio,
              const py::object& seed, const std::string& gap_update, const std::string& split_to,
              const py::object& split_factor, bool features, const py::object& feature_angle, bool exact, bool lrrt,
              const py::object& threads, const std::string& conflict, bool keep_radius) {
  MpsSettings settings;
  settings.radius = radius;
  settings.adaptive = adaptive;
  settings.seed = to_seed(seed);
  settings.gap_update = gap_update;
  settings.split_to = split_to;
  settings.exact = exact;
  settings.features = features;
  settings.conflict = conflict;
  if (keep_radius && !lrrt) throw InputError("keep_radius applies to lrrt=True");
  settings.keep_radius = keep_radius;
  if ((settings.max_radius_ratio_given = !max_radius_ratio.is_none())) settings.max_radius_ratio = number(max_radius_ratio, "max_radius_ratio");
  if ((settings.split_factor_given = !split_factor.is_none())) settings.split_factor = number(split_factor, "split_factor");
  if ((settings.feature_angle_given = !feature_angle.is_none())) settings.feature_angle = number(feature_angle, "feature_angle");
  check_mps_settings(settings);
  ThreadLimit limit(threads);
  const LoadedMesh loaded = loaded_mesh(V, F);
  MpsRun run;
  {
    py::gil_scoped_release release;
    run = run_mps(loaded, false, settings, "", "", lrrt, "", nullptr, nullptr, nullptr);
    run.report["predicates"] = predicates_json();
  }
  py::object points = points_array(std::move(run.result.samples.positions));
  if (!lrrt) return py::make_tuple(points, to_python(run.report));
  return py::make_tuple(points, to_python(run.report), points_array(std::move(run.dual.positions)),
                        triangles_array(std::move(run.dual.triangles)));
}

py::object quality(const py::object& V_ref, const py::object& F_ref, const py::object& V, const py::object& F,
                   const py::object& threads) {
  ThreadLimit limit(threads);
  const LoadedMesh reference = loaded_mesh(V_ref, F_ref, "V_ref", "F_ref");
  PolygonSoup soup;
  soup.positions = to_points(V, "V", 0);
  soup.triangles = to_triangles(F, soup.positions.size(), "F");
  nlohmann::json report;
  {
    py::gil_scoped_release release;
    report = run_quality(reference, false, soup, "", "").report;
  }
  return to_python(report);
}

py::tuple stress(const std::string& name, double scale) {
  if (!(scale >= 0.05 && scale <= 10))
    throw InputError(fmt::format("--scale: a resolution scale from 0.05 to 10, not {}", scale));
  SurfaceMesh mesh;
  {
    py::gil_scoped_release release;
    mesh = make_stress_mesh(name, scale);
  }
  return py::make_tuple(points_array(std::vector<Vec3>(mesh.positions())),
                        triangles_array(std::vector<Triangle>(mesh.triangles())));
}

std::vector<std::string> stress_names() {
  std::vector<std::string> names;
  for (const StressMeshInfo& info : stress_mesh_catalog()) names.push_back(info.name);
  return names;
}

}  // namespace

void add_render(py::module_& m);

}  // namespace lrvd::python

PYBIND11_MODULE(lrvd, m) {
  using namespace lrvd::python;
  namespace py = pybind11;
  m.doc() = "Localized restricted Voronoi diagrams of points on triangle meshes, CVT remeshing and maximal "
            "Poisson-disk sampling, every result checked (docs/guide/python.md).";
  m.attr("__version__") = LRVD_VERSION;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const lrvd::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });

  py::class_<PyDiagram, std::shared_ptr<PyDiagram>>(m, "Diagram", "A diagram of samples on a mesh (lrvd.compute).")
      .def_property_readonly("kind", &PyDiagram::kind, "lrvd, rvd, lrpd or rpd")
      .def_property_readonly("report", &PyDiagram::report, "The report `lrvd compute --report` writes, as a dict")
      .def_property_readonly("passed", &PyDiagram::passed, "The verification's verdict; None before verify()")
      .def_property_readonly("cells_in_pieces", &PyDiagram::cells_in_pieces, "Cells of more than one piece")
      .def_property_readonly("mesh", &PyDiagram::mesh, "(V, F) of the mesh the cells lie on (refined when the "
                                                       "samples would crowd the input)")
      .def_property_readonly("samples", &PyDiagram::samples, "(k, 3) samples, on the surface")
      .def_property_readonly("cells", &PyDiagram::cells,
                             "dict of arrays: vertices (p, 3); polygon_vertices and polygon_offsets (polygon i's "
                             "corners are polygon_vertices[polygon_offsets[i]:polygon_offsets[i + 1]]); per polygon "
                             "polygon_cell, polygon_triangle (of mesh) and polygon_component; per cell "
                             "cell_components")
      .def("verify", &PyDiagram::verify, py::arg("threads") = py::none(),
           "Checks every property in exact arithmetic; returns the report's `verification` dict");

  m.def("read_mesh", &read_mesh_py, py::arg("path"), py::arg("repair") = false, py::arg("weld") = py::none(),
        py::arg("fill_holes") = py::none(), "Reads OFF, OBJ, PLY or STL: (V float64 (n, 3), F int32 (m, 3))");
  m.def("write_mesh", &write_mesh_py, py::arg("path"), py::arg("V"), py::arg("F"), "Writes OFF, OBJ or PLY");
  m.def("compute", &compute, py::arg("V"), py::arg("F"), py::arg("points") = py::none(), py::arg("n") = py::none(),
        py::arg("seed") = 1, py::arg("diagram") = "lrvd", py::arg("weights") = py::none(), py::arg("verify") = true,
        py::arg("refine") = "auto", py::arg("threads") = py::none(),
        "The diagram of `points` (k, 3) or of `n` random samples: a Diagram");
  m.def("remesh", &remesh, py::arg("V"), py::arg("F"), py::arg("n"), py::arg("seed") = 1, py::arg("diagram") = "lrvd",
        py::arg("optimizer") = "lbfgs", py::arg("density") = "uniform", py::arg("priority") = "distance",
        py::arg("repair_scope") = "whole", py::arg("iterations") = 60, py::arg("fit") = true, py::arg("refine") = "auto", py::arg("threads") = py::none(),
        "CVT remesh to exactly n vertices: (V2, F2, report)");
  m.def("mps", &mps, py::arg("V"), py::arg("F"), py::arg("radius"), py::arg("adaptive") = false,
        py::arg("max_radius_ratio") = py::none(), py::arg("seed") = 1, py::arg("gap_update") = "local",
        py::arg("split_to") = "field", py::arg("split_factor") = py::none(), py::arg("features") = true,
        py::arg("feature_angle") = py::none(), py::arg("exact") = false, py::arg("lrrt") = false,
        py::arg("threads") = py::none(), py::arg("conflict") = "reach", py::arg("keep_radius") = false,
        "Maximal Poisson-disk sampling: (points, report), with lrrt=True (points, report, V2, F2)");
  m.def("quality", &quality, py::arg("V_ref"), py::arg("F_ref"), py::arg("V"), py::arg("F"),
        py::arg("threads") = py::none(), "Quality and validity of (V, F) against the reference: the report dict");
  m.def("stress", &stress, py::arg("name"), py::arg("scale") = 1.0, "A stress mesh: (V, F)");
  m.def("stress_names", &stress_names, "The stress meshes' names");
  add_render(m);
}
