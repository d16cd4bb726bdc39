// NumPy arrays in and out of the lrvd module: checked conversions of the caller's arrays into the
// library's vectors, and arrays that own a library vector moved into them (no copy on the way out).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <tbb/global_control.h>

#include "predicates/vec3.h"
#include "report/report.h"

namespace lrvd::python {

namespace py = pybind11;

//! An (n, 3) array of real numbers (float64 read in place when it is one and C-ordered, else
//! converted), as points. `name` says which argument in the messages.
//! \throw py::type_error for a dtype that is not a real number, py::value_error for another shape,
//!        fewer than `at_least` rows, or a coordinate that is not finite.
std::vector<Vec3> to_points(const py::handle& array, const char* name, std::size_t at_least = 1);
//! An (m, 3) array of integers, each in [0, vertex_count).
//! \throw py::type_error for a dtype that is not an integer, py::value_error for another shape or
//!        an index out of range.
std::vector<std::array<int, 3>> to_triangles(const py::handle& array, std::size_t vertex_count, const char* name);
//! A (k,) array of finite real numbers. \throw py::type_error, py::value_error as above.
std::vector<double> to_values(const py::handle& array, const char* name);

//! The vector moved into an array that keeps it alive: (n, 3) float64.
py::array_t<double> points_array(std::vector<Vec3>&& points);
//! (m, 3) int32.
py::array_t<int> triangles_array(std::vector<std::array<int, 3>>&& triangles);
//! (k,) of the vector's type.
template <class T>
py::array_t<T> values_array(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({static_cast<py::ssize_t>(owned->size())}, owned->data(), owner);
}

//! `threads=`: the worker threads of one call, as the command's --threads (None: every core).
class ThreadLimit {
 public:
  explicit ThreadLimit(const py::object& threads);

 private:
  std::unique_ptr<tbb::global_control> limit_;
};
//! A Python int (not a bool) as a long long. \throw py::type_error, InputError beyond its range.
long long whole_number(const py::object& value, const char* name, const char* what);
//! `n`: a whole number up to kMaxSamples. \throw py::type_error, InputError above it.
int sample_count(const py::object& n, const char* what);
//! A seed, 0 to 2^64 - 1. \throw InputError
std::uint64_t to_seed(const py::object& seed);
//! The valid mesh of the arrays, as a file read without --repair gives it. \throw InputError
LoadedMesh loaded_mesh(const py::handle& V, const py::handle& F, const char* v_name = "V", const char* f_name = "F");
//! The mesh and the samples of compute and render: `points` (with `weights`) or `n` random ones,
//! prepared as the command prepares them (prepare_samples). \throw InputError
Input diagram_input(const py::handle& V, const py::handle& F, const py::object& points, const py::object& n,
                    const py::object& seed, const py::object& weights, const std::string& refine);

//! The report as the dict json.loads gives for the file the command writes.
py::object to_python(const nlohmann::json& report);

}  // namespace lrvd::python
