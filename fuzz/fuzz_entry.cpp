// The fuzz entry points: bytes into a file in the temporary folder, then lrvd's own reader of it.
#include "fuzz_entry.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "io/mesh_io.h"
#include "mesh/surface_mesh.h"
#include "report/report.h"
#include "samples/samples.h"
#include "verification/diagram_check.h"

namespace lrvd::fuzz {

const Target kTargets[3] = {{"mesh_file", mesh_file}, {"point_files", point_files}, {"compute", compute}};

namespace {

// Triangles a compute input may be refined to: enough for 16 samples, few enough for thousands of
// runs a second.
constexpr double kFuzzRefinedTriangles = 20000;

// `bytes` in a file of this process with extension `ext`, replaced at each call.
std::string temporary_file(const std::uint8_t* bytes, std::size_t size, const char* ext) {
  const std::string path =
      (std::filesystem::temp_directory_path() / fmt::format("lrvd_fuzz_{}{}", ::getpid(), ext)).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error("fuzz: cannot write " + path);
  return path;
}

SurfaceMesh octahedron() {
  return SurfaceMesh({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                     {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
}

}  // namespace

void mesh_file(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return;
  static const char* const extensions[] = {".off", ".obj", ".ply", ".stl"};
  const std::string path = temporary_file(data + 1, size - 1, extensions[data[0] & 3]);
  try {
    if (data[0] & 8) {
      read_polygon_soup(path, true, true);
    } else {
      ReadOptions options;
      options.repair = (data[0] & 4) != 0;
      read_mesh(path, options);
    }
  } catch (const InputError&) {
  }
}

void point_files(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return;
  const bool points = (data[0] & 1) != 0;
  const std::string path = temporary_file(data + 1, size - 1, points ? ".xyz" : ".txt");
  try {
    if (points) {
      const PointFile file = read_xyz(path);
      locate_points(octahedron(), file.points, file.weights, file.lines);
    } else {
      read_weights(path);
    }
  } catch (const InputError&) {
  }
}

void compute(const std::uint8_t* data, std::size_t size) {
  std::size_t at = 0;
  auto next = [&]() -> int { return at < size ? data[at++] : 0; };
  const int n = 1 + next() % 16, seed = next(), nv = 4 + next() % 13, nf = 4 + next() % 29;
  const int scale = std::max(-60, std::min(60, next() - 128));
  std::string off = fmt::format("OFF\n{} {} 0\n", nv, nf);
  for (int v = 0; v < nv; ++v) {
    for (int c = 0; c < 3; ++c) {
      const int low = next(), high = next();
      const auto value = static_cast<std::int16_t>(static_cast<std::uint16_t>(low | high << 8));
      off += fmt::format("{:.17g}{}", std::ldexp(static_cast<double>(value), scale), c < 2 ? " " : "\n");
    }
  }
  for (int f = 0; f < nf; ++f) {
    const int a = next() % nv, b = next() % nv, c = next() % nv;
    off += fmt::format("3 {} {} {}\n", a, b, c);
  }
  const std::string path =
      temporary_file(reinterpret_cast<const std::uint8_t*>(off.data()), off.size(), ".off");
  try {
    // The samples and the diagram as `lrvd compute` makes them (refinement auto), within a smaller
    // budget of triangles.
    Input input;
    input.loaded = read_mesh(path);
    require_workable_model(input.loaded.mesh, "lrvd");
    SampleRequest request;
    request.count = n;
    request.seed = static_cast<std::uint64_t>(seed);
    request.max_refined_triangles = kFuzzRefinedTriangles;
    prepare_samples(input, request);
    const Diagram diagram = compute_input_diagram(input, DiagramKind::Lrvd);
    const DiagramVerification check = verify_diagram(input.mesh, input.samples, diagram);
    if (!check.passed) throw std::logic_error("fuzz: the LRVD failed its verification: " + check.summary());
  } catch (const InputError&) {
  }
}

}  // namespace lrvd::fuzz
