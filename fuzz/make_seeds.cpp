// Writes the fuzz targets' seed corpus: small valid inputs of every format each target reads, made
// here (no third-party file). Usage: lrvd_fuzz_seeds OUT_DIR (one folder per target under it).
// A program of its own: no header.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/mesh_writers.h"

namespace {

namespace fs = std::filesystem;

const std::vector<lrvd::Vec3> kTetraPoints = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::vector<std::array<int, 3>> kTetraFaces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

void put(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string binary_stl() {
  std::string bytes(80, ' ');
  auto put32 = [&](std::uint32_t v) { bytes.append(reinterpret_cast<const char*>(&v), 4); };  // little-endian host
  auto putf = [&](float v) { bytes.append(reinterpret_cast<const char*>(&v), 4); };
  put32(static_cast<std::uint32_t>(kTetraFaces.size()));
  for (const auto& f : kTetraFaces) {
    for (int k = 0; k < 3; ++k) putf(0);
    for (int v : f)
      for (int c = 0; c < 3; ++c) putf(static_cast<float>(kTetraPoints[v][c]));
    bytes += std::string(2, '\0');
  }
  return bytes;
}

std::string ascii_stl() {
  std::string text = "solid t\n";
  for (const auto& f : kTetraFaces) {
    text += "facet normal 0 0 0\nouter loop\n";
    for (int v : f)
      text += "vertex " + std::to_string(kTetraPoints[v].x) + " " + std::to_string(kTetraPoints[v].y) + " " +
              std::to_string(kTetraPoints[v].z) + "\n";
    text += "endloop\nendfacet\n";
  }
  return text + "endsolid t\n";
}

std::string ascii_ply(const char* coordinate, const char* index) {
  std::string text = std::string("ply\nformat ascii 1.0\nelement vertex 4\nproperty ") + coordinate + " x\nproperty " +
                     coordinate + " y\nproperty " + coordinate + " z\nelement face 4\nproperty list uchar " + index +
                     " vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  text += "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  for (const auto& f : kTetraFaces) text += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + " 200 10 10\n";
  return text;
}

// The compute entry's encoding (fuzz_entry.h) of a mesh with coordinates in units of 2^-2.
std::string compute_seed(int samples, const std::vector<std::array<int, 3>>& points,
                         const std::vector<std::array<int, 3>>& faces) {
  std::string bytes;
  bytes += static_cast<char>(samples - 1);
  bytes += static_cast<char>(7);
  bytes += static_cast<char>(points.size() - 4);
  bytes += static_cast<char>(faces.size() - 4);
  bytes += static_cast<char>(128 - 2);
  for (const auto& p : points)
    for (int c : p) {
      const auto v = static_cast<std::uint16_t>(static_cast<std::int16_t>(c));
      bytes += static_cast<char>(v & 0xff);
      bytes += static_cast<char>(v >> 8);
    }
  for (const auto& f : faces)
    for (int v : f) bytes += static_cast<char>(v);
  return bytes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  const fs::path out = argv[1];
  for (const char* target : {"mesh_file", "point_files", "compute"}) fs::create_directories(out / target);

  // mesh_file: the first byte chooses the extension (0 OFF, 1 OBJ, 2 PLY, 3 STL), --repair (4) and
  // read_polygon_soup (8).
  const fs::path scratch = out / "scratch";
  fs::create_directories(scratch);
  std::vector<std::pair<int, std::string>> meshes;
  for (const char* ext : {".off", ".obj", ".ply"}) {
    lrvd::write_mesh((scratch / (std::string("t") + ext)).string(), kTetraPoints, kTetraFaces);
    const int format = ext[1] == 'o' && ext[2] == 'f' ? 0 : ext[1] == 'o' ? 1 : 2;
    meshes.push_back({format, file_bytes(scratch / (std::string("t") + ext))});
  }
  fs::remove_all(scratch);
  meshes.push_back({0, "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"});  // a quad
  meshes.push_back({1, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"});
  meshes.push_back({2, ascii_ply("float", "int")});
  meshes.push_back({2, ascii_ply("double", "uchar")});
  meshes.push_back({2, ascii_ply("short", "ushort")});
  meshes.push_back({3, ascii_stl()});
  meshes.push_back({3, binary_stl()});
  int count = 0;
  for (const auto& [format, bytes] : meshes)
    for (int flags : {0, 4, 8}) put(out / "mesh_file" / ("seed_" + std::to_string(count++)), char(format | flags) + bytes);

  // point_files: bit 0 of the first byte, points (1) or weights (0).
  put(out / "point_files" / "points", "\x01" "1 0 0\n0 1 0\n0 0 1\n-1 0 0\n0 -1 0\n0 0 -1\n");
  put(out / "point_files" / "weighted_points", "\x01# x y z w\n1 0 0 0.1\n0 1 0 0.2\n0 0 1 0\n-1 0 0 0\n0 -1 0 0\n0 0 -1 1e-3\n");
  put(out / "point_files" / "weights", std::string("\x00", 1) + "0.1\n\n# comment\n0.2\n3e-2\n");

  // compute: a tetrahedron, an octahedron, a cube in triangles.
  put(out / "compute" / "tetrahedron", compute_seed(3, {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}}, kTetraFaces));
  put(out / "compute" / "octahedron",
      compute_seed(8, {{4, 0, 0}, {-4, 0, 0}, {0, 4, 0}, {0, -4, 0}, {0, 0, 4}, {0, 0, -4}},
                   {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}}));
  put(out / "compute" / "cube",
      compute_seed(16, {{0, 0, 0}, {0, 4, 0}, {4, 4, 0}, {4, 0, 0}, {0, 0, 4}, {4, 0, 4}, {4, 4, 4}, {0, 4, 4}},
                   {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}, {0, 3, 5}, {0, 5, 4}, {3, 2, 6}, {3, 6, 5}, {2, 1, 7},
                    {2, 7, 6}, {1, 0, 4}, {1, 4, 7}}));
  std::printf("seeds: %d mesh files, 3 point files, 3 compute meshes in %s\n", count, out.c_str());
  return 0;
}
