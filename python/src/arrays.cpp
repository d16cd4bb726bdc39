// Checked NumPy conversions of the lrvd module (arrays.h).
#include "arrays.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <fmt/format.h>

#include "common/error.h"

namespace lrvd::python {

namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 is read and written as three doubles");

std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// The argument as an array, or a TypeError naming what it should be.
py::array as_array(const py::handle& value, const char* name, const char* what) {
  if (value.is_none()) throw py::type_error(fmt::format("{} must be {}, not None", name, what));
  py::array a = py::array::ensure(value);
  if (!a) throw py::type_error(fmt::format("{} must be {}", name, what));
  return a;
}

void require_kind(const py::array& a, const char* name, const char* kinds, const char* what) {
  const char kind = a.dtype().kind();
  if (!std::strchr(kinds, kind) || kind == '\0')
    throw py::type_error(fmt::format("{} must be {}, not an array of dtype {}", name, what,
                                     py::str(a.dtype()).cast<std::string>()));
}

}  // namespace

std::vector<Vec3> to_points(const py::handle& value, const char* name, std::size_t at_least) {
  const char* what = "a float64 array of shape (n, 3)";
  py::array a = as_array(value, name, what);
  require_kind(a, name, "fiu", what);
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(fmt::format("{} must have shape (n, 3), not {}", name, shape_of(a)));
  if (static_cast<std::size_t>(a.shape(0)) < at_least)
    throw py::value_error(fmt::format("{} must have at least {} rows, not {}", name, at_least, a.shape(0)));
  // float64 in C order is read where it is; any other real dtype or order is converted once.
  auto doubles = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  std::vector<Vec3> points(static_cast<std::size_t>(a.shape(0)));
  std::memcpy(static_cast<void*>(points.data()), doubles.data(), points.size() * sizeof(Vec3));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) || !std::isfinite(points[i].z))
      throw py::value_error(fmt::format("{} row {} is not finite: ({}, {}, {})", name, i, points[i].x, points[i].y,
                                        points[i].z));
  return points;
}

std::vector<std::array<int, 3>> to_triangles(const py::handle& value, std::size_t vertex_count, const char* name) {
  const char* what = "an integer array of shape (m, 3)";
  py::array a = as_array(value, name, what);
  require_kind(a, name, "iu", what);
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(fmt::format("{} must have shape (m, 3), not {}", name, shape_of(a)));
  auto ints = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!ints) throw py::type_error(fmt::format("{} must be {}", name, what));
  const std::int64_t* data = ints.data();
  std::vector<std::array<int, 3>> triangles(static_cast<std::size_t>(a.shape(0)));
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      const std::int64_t v = data[3 * t + c];
      // A uint64 above 2^63 arrives negative here, and is refused as such.
      if (v < 0 || static_cast<std::uint64_t>(v) >= vertex_count)
        throw py::value_error(fmt::format("{} row {} has vertex index {}, outside 0..{} (the vertices' rows)", name, t,
                                          v, static_cast<std::int64_t>(vertex_count) - 1));
      triangles[t][c] = static_cast<int>(v);
    }
  return triangles;
}

std::vector<double> to_values(const py::handle& value, const char* name) {
  const char* what = "a float64 array of shape (k,)";
  py::array a = as_array(value, name, what);
  require_kind(a, name, "fiu", what);
  if (a.ndim() != 1) throw py::value_error(fmt::format("{} must have shape (k,), not {}", name, shape_of(a)));
  auto doubles = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  std::vector<double> values(doubles.data(), doubles.data() + a.shape(0));
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i])) throw py::value_error(fmt::format("{}[{}] is not finite: {}", name, i, values[i]));
  return values;
}

py::array_t<double> points_array(std::vector<Vec3>&& points) {
  auto* owned = new std::vector<Vec3>(std::move(points));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<Vec3>*>(p); });
  return py::array_t<double>({static_cast<py::ssize_t>(owned->size()), py::ssize_t{3}},
                             reinterpret_cast<const double*>(owned->data()), owner);
}

py::array_t<int> triangles_array(std::vector<std::array<int, 3>>&& triangles) {
  auto* owned = new std::vector<std::array<int, 3>>(std::move(triangles));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<std::array<int, 3>>*>(p); });
  return py::array_t<int>({static_cast<py::ssize_t>(owned->size()), py::ssize_t{3}},
                          reinterpret_cast<const int*>(owned->data()), owner);
}

py::object to_python(const nlohmann::json& report) {
  return py::module_::import("json").attr("loads")(report.dump());
}

// `threads=`: the worker threads of one call, as the command's --threads (none: every core).
ThreadLimit::ThreadLimit(const py::object& threads) {
  if (threads.is_none()) return;
  const long long n = whole_number(threads, "threads", "a thread count is a whole number from 1 to 4096");
  if (n < 1 || n > 4096) throw InputError(fmt::format("a thread count is a whole number from 1 to 4096, not '{}'", n));
  limit_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, static_cast<int>(n));
}

long long whole_number(const py::object& value, const char* name, const char* what) {
  if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value))
    throw py::type_error(fmt::format("{}: {}, not {}", name, what, py::repr(value).cast<std::string>()));
  try {
    return value.cast<long long>();
  } catch (const py::cast_error&) {
    throw InputError(fmt::format("{}: {}, not {}", name, what, py::repr(value).cast<std::string>()));
  }
}

int sample_count(const py::object& n, const char* what) {
  const long long count = whole_number(n, "n", what);
  if (count > kMaxSamples)
    throw InputError(fmt::format("{} samples are more than lrvd takes (limit {})", count, kMaxSamples));
  return static_cast<int>(std::max<long long>(count, std::numeric_limits<int>::min()));
}

std::uint64_t to_seed(const py::object& seed) {
  const char* what = "a seed is a whole number from 0 to 18446744073709551615";
  if (!py::isinstance<py::int_>(seed) || py::isinstance<py::bool_>(seed))
    throw py::type_error(fmt::format("{}, not {}", what, py::repr(seed).cast<std::string>()));
  try {
    if (seed.cast<py::int_>() < py::int_(0)) throw py::cast_error();
    return seed.cast<std::uint64_t>();
  } catch (const py::cast_error&) {
    throw InputError(fmt::format("{}, not '{}'", what, py::str(seed).cast<std::string>()));
  }
}

// A valid mesh of the arrays, as a file read without --repair gives it.
LoadedMesh loaded_mesh(const py::handle& V, const py::handle& F, const char* v_name, const char* f_name) {
  std::vector<Vec3> positions = to_points(V, v_name, 3);
  std::vector<Triangle> triangles = to_triangles(F, positions.size(), f_name);
  if (triangles.empty()) throw InputError(fmt::format("{} holds no triangles", f_name));
  py::gil_scoped_release release;
  LoadedMesh loaded;
  loaded.mesh = SurfaceMesh(std::move(positions), std::move(triangles));
  return loaded;
}

// The mesh and the samples of compute and render: `points` (with `weights`) or `n` random ones.
Input diagram_input(const py::handle& V, const py::handle& F, const py::object& points, const py::object& n,
                    const py::object& seed, const py::object& weights, const std::string& refine) {
  Input input;
  input.loaded = loaded_mesh(V, F);
  SampleRequest request;
  request.points_given = !points.is_none();
  if (request.points_given && !n.is_none()) throw InputError("give points or n, not both");
  if (request.points_given) request.points.points = to_points(points, "points");
  if (!n.is_none()) request.count = sample_count(n, "a sample count is a whole number");
  if (!weights.is_none()) {
    request.points.weights = to_values(weights, "weights");
    if (request.points_given && request.points.weights.size() != request.points.points.size())
      throw InputError(fmt::format("{} weights were given for the {} points", request.points.weights.size(),
                                   request.points.points.size()));
  }
  request.seed = to_seed(seed);
  request.refine = refine;
  request.mesh_name = "the mesh";
  request.points_name = "points";
  py::gil_scoped_release release;
  require_workable_model(input.loaded.mesh, "lrvd");
  prepare_samples(input, request);
  return input;
}

}  // namespace lrvd::python
