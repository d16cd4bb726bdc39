// Inputs a hostile or careless user gives (issue #51's classes): every one ends in InputError with
// one line, never a crash, a hang or unbounded memory; and the replay of the fuzz targets' findings.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "fuzz/fuzz_entry.h"
#include "io/mesh_io.h"
#include "mesh/closest_point.h"
#include "samples/samples.h"

using namespace lrvd;

namespace {

const std::string kOut = std::string(LRVD_BINARY_DIR) + "/test_hostile_";

std::string written(const std::string& name, const std::string& bytes) {
  const std::string path = kOut + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::string refusal(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

// A tetrahedron as an ascii PLY whose coordinates have `type`, at `scale` times the unit corners.
std::string tetrahedron_ply(const std::string& type, int scale) {
  std::string text = fmt::format(
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty {0} x\nproperty {0} y\nproperty {0} z\nelement face 4\n"
      "property list uchar int vertex_indices\nend_header\n",
      type);
  text += fmt::format("0 0 0\n{0} 0 0\n0 {0} 0\n0 0 {0}\n", scale);
  return text + "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
}

}  // namespace

TEST_CASE("read_mesh reads PLY coordinates of every scalar type as doubles", "[hostile]") {
  // CGAL's point reader takes float and double only, and called through a null pointer on the rest.
  const struct {
    const char* type;
    int scale;
  } cases[] = {{"char", -100}, {"int8", 100},    {"uchar", 200},   {"uint8", 255},       {"short", -30000},
               {"int16", 1000}, {"ushort", 60000}, {"int", -2000000}, {"uint32", 4000000}, {"float", 3}};
  for (const auto& c : cases) {
    INFO(c.type);
    const SurfaceMesh mesh = read_mesh(written(std::string("tet_") + c.type + ".ply", tetrahedron_ply(c.type, c.scale))).mesh;
    REQUIRE(mesh.vertex_count() == 4);
    CHECK(mesh.position(1) == Vec3{double(c.scale), 0, 0});
    CHECK(mesh.position(3) == Vec3{0, 0, double(c.scale)});
  }
  // Binary, big-endian shorts.
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty short x\nproperty short y\nproperty short z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
  const int corners[4][3] = {{0, 0, 0}, {-300, 0, 0}, {0, 300, 0}, {0, 0, 300}};
  for (const auto& p : corners)
    for (int c : p) bytes += {static_cast<char>((c >> 8) & 0xff), static_cast<char>(c & 0xff)};
  const int faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  for (const auto& f : faces) {
    bytes += '\3';
    for (int v : f) bytes += std::string("\0\0\0", 3) + static_cast<char>(v);
  }
  const SurfaceMesh mesh = read_mesh(written("tet_short_be.ply", bytes)).mesh;
  CHECK(mesh.position(1) == Vec3{-300, 0, 0});
  CHECK(mesh.position(2) == Vec3{0, 300, 0});
}

TEST_CASE("read_mesh refuses a PLY property before any element with one line", "[hostile]") {
  std::string text = tetrahedron_ply("float", 1);
  text.insert(text.find("element vertex"), "property float x\n");
  CHECK(refusal([&] { read_mesh(written("property_first.ply", text)); }) ==
        kOut + "property_first.ply: has an invalid PLY header: line 3 declares a property before any 'element' line");
  // The same as the file's last line, without its line break.
  CHECK(refusal([&] { read_mesh(written("property_only.ply", "ply\nformat ascii 1.0\nproperty float x")); })
            .find("line 3 declares a property before any 'element' line") != std::string::npos);
}

TEST_CASE("read_mesh refuses an OFF edge count CGAL would overflow", "[hostile]") {
  // CGAL doubles the third count in an int: 2^30 and more overflow (undefined behaviour).
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  for (const std::string count : {"1073741824", "-1073741824", "2147483647"})
    CHECK(refusal([&] { read_mesh(written("edges.off", "OFF\n4 4 " + count + "\n" + body)); }) ==
          kOut + "edges.off: has an invalid OFF header: its edge count " + count + " is out of range (it is unused; write 0)");
  CHECK(read_mesh(written("edges_ok.off", "OFF\n4 4 1073741823\n" + body)).mesh.triangle_count() == 4);
  // Binary OFF: the three counts as big-endian int32.
  std::string binary = "OFF BINARY\n";
  for (std::uint32_t v : {4u, 4u, 0x40000000u})
    for (int shift = 24; shift >= 0; shift -= 8) binary += static_cast<char>((v >> shift) & 0xff);
  CHECK(refusal([&] { read_mesh(written("edges_binary.off", binary + std::string(100, '\0'))); })
            .find("its edge count 1073741824 is out of range") != std::string::npos);
}

TEST_CASE("Inputs that are not regular files are refused without reading them", "[hostile]") {
  // /dev/zero has no end (the line scan grew without bound), a FIFO blocks the opening for ever.
  const std::string fifo_mesh = kOut + "fifo.off", fifo_points = kOut + "fifo.xyz", zero = kOut + "zero.stl";
  for (const std::string& f : {fifo_mesh, fifo_points, zero}) std::filesystem::remove(f);
  REQUIRE(::mkfifo(fifo_mesh.c_str(), 0600) == 0);
  REQUIRE(::mkfifo(fifo_points.c_str(), 0600) == 0);
  std::filesystem::create_symlink("/dev/zero", zero);
  const std::string reason = ": is not a regular file but a device, a pipe or a socket; lrvd reads its inputs from regular files";
  CHECK(refusal([&] { read_mesh(fifo_mesh); }) == fifo_mesh + reason);
  CHECK(refusal([&] { read_mesh(zero); }) == zero + reason);
  CHECK(refusal([&] { read_polygon_soup(zero); }) == zero + reason);
  CHECK(refusal([&] { read_xyz(fifo_points); }) == "point file '" + fifo_points + "' " + reason.substr(2));
  CHECK(refusal([&] { read_weights("/dev/urandom"); }) == "weight file '/dev/urandom' " + reason.substr(2));
  // A regular file redirected to /dev/stdin is one: the convention for reading standard input.
  const std::string points = written("stdin.xyz", "1 0 0\n0 1 0\n");
  const std::string command = fmt::format("test -f /dev/stdin < {}", points);
  CHECK(std::system(command.c_str()) == 0);
}

TEST_CASE("A closest-point query with a hint gives the plain query's answer, never none", "[hostile]") {
  // The hint's radius had a margin of 1e-12, below the floats Embree compares box distances in: 42
  // of 600,000 such queries reached no box (triangle -1, which the remesh's fitting then indexed:
  // issue #51's pulled cube corner) and 271 another triangle than the plain query.
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  int none = 0, other = 0;
  for (int m = 0; m < 1000; ++m) {
    std::vector<Vec3> positions;
    std::vector<std::array<int, 3>> triangles;
    for (int k = 0; k < 14; ++k) {
      for (int c = 0; c < 3; ++c) positions.push_back({coordinate(random), coordinate(random), coordinate(random)});
      triangles.push_back({3 * k, 3 * k + 1, 3 * k + 2});
    }
    const ClosestPointIndex index(positions, triangles);
    for (int q = 0; q < 200; ++q) {
      const Vec3 x{float(2 * coordinate(random)), float(2 * coordinate(random)), float(2 * coordinate(random))};
      const int plain = index.query(x).triangle, hinted = index.query(x, plain).triangle;
      none += hinted < 0;
      other += hinted >= 0 && hinted != plain;
    }
  }
  CHECK(none == 0);
  CHECK(other == 0);
}

TEST_CASE("The fuzz targets' findings replay without a crash", "[hostile]") {
  // tests/data/fuzz/TARGET/*: inputs a fuzz target once crashed on (make fuzz keeps them there).
  // Each must now end as documented: returned, or InputError inside the entry.
  const std::filesystem::path root = std::filesystem::path(LRVD_SOURCE_DIR) / "tests/data/fuzz";
  int replayed = 0;
  for (const fuzz::Target& target : fuzz::kTargets) {
    const std::filesystem::path folder = root / target.name;
    if (!std::filesystem::exists(folder)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
      std::ifstream in(entry.path(), std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      INFO(entry.path().string());
      CHECK_NOTHROW(target.entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
      ++replayed;
    }
  }
  // The hand-made findings of issue #51 are there; more come from make fuzz.
  CHECK(replayed >= 1);
}
