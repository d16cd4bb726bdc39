// Mesh IO: every refusal on a real malformed file with its message, --repair on real soups,
// exact round trips of the writers, CGAL's data-set meshes, and the Voronoi-cells PLY.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <set>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "common/error.h"
#include "io/mesh_io.h"
#include "io/mesh_writers.h"
#include "mesh/weld.h"

using namespace lrvd;
using Catch::Contains;

namespace {

std::string data(const std::string& name) { return std::string(LRVD_SOURCE_DIR) + "/tests/data/" + name; }

std::string scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(LRVD_BINARY_DIR) / "test_mesh_io";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

void write_file(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

template <class T>
void append(std::string& bytes, T value) {  // little-endian on the x86/arm hosts we build on
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

const float tetra_points[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const int tetra_faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

double signed_volume(const SurfaceMesh& mesh) {
  double six_volume = 0;
  for (const Triangle& t : mesh.triangles())
    six_volume += dot(mesh.position(t[0]), cross(mesh.position(t[1]), mesh.position(t[2])));
  return six_volume / 6;
}

}  // namespace

TEST_CASE("read_mesh refuses files it cannot open or does not know") {
  REQUIRE_THROWS_AS(read_mesh(data("no_such_mesh.off")), InputError);
  REQUIRE_THROWS_WITH(read_mesh(data("no_such_mesh.off")), Contains("no_such_mesh.off: no such file"));
  REQUIRE_THROWS_WITH(read_mesh(data("unknown.xyz")), Contains("unknown extension '.xyz'") && Contains(".off, .obj"));
  REQUIRE_THROWS_WITH(read_mesh(data("")), Contains("is a directory"));
  REQUIRE_THROWS_WITH(read_mesh(data("empty.off")), Contains("empty.off: is empty"));
  REQUIRE_THROWS_WITH(read_mesh(data("no_faces.off")), Contains("no_faces.off: has 3 vertices but no faces"));
}

TEST_CASE("read_mesh turns CGAL's refusal of a truncated or garbled file into the first offending line") {
  REQUIRE_THROWS_AS(read_mesh(data("truncated.off")), InputError);
  REQUIRE_THROWS_WITH(read_mesh(data("truncated.off")),
                      Contains("truncated.off: is truncated: the header declares 8 vertices and 6 faces, but the "
                               "file ends after 5 vertices"));
  REQUIRE_THROWS_WITH(read_mesh(data("not_a_number.off")), Contains("vertex 1 (line 4): 'O' is not a number"));

  // A truncated binary PLY: the header promises 4 faces, the body holds 3 and a half, fewer bytes
  // than 4 vertices and 4 triangles take.
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : tetra_points)
    for (float c : p) append(ply, c);
  for (const auto& f : tetra_faces) {
    append(ply, static_cast<unsigned char>(3));
    for (int v : f) append(ply, v);
  }
  const std::string truncated_ply = scratch("truncated.ply");
  write_file(truncated_ply, ply.substr(0, ply.size() - 7));
  REQUIRE_THROWS_WITH(read_mesh(truncated_ply),
                      Contains("is too short for its header: it declares 4 vertices and 4 faces, which take at least "
                               "100 bytes after its 169-byte header, but the file has only 262 bytes"));

  const std::string truncated_stl = scratch("truncated.stl");
  write_file(truncated_stl, read_file(data("tetrahedron.stl")).substr(0, 150));
  REQUIRE_THROWS_WITH(read_mesh(truncated_stl), Contains("is truncated: the ascii STL ends after 2 facets"));

  std::string binary_stl(80, ' ');
  append(binary_stl, std::uint32_t{4});
  binary_stl.append(4 * 50 - 20, '\0');
  write_file(scratch("truncated_binary.stl"), binary_stl);
  REQUIRE_THROWS_WITH(read_mesh(scratch("truncated_binary.stl")),
                      Contains("is truncated or malformed as binary STL: it has 264 bytes"));

  // Binary OFF: big-endian 32-bit counts, float coordinates, faces. CGAL reads faces without a
  // colour count; Geomview's layout has one after each face's indices, which CGAL misreads.
  for (bool colour_counts : {false, true}) {
    std::string off = "OFF BINARY\n";
    auto big_endian = [&off](std::uint32_t v) {
      for (int shift = 24; shift >= 0; shift -= 8) off.push_back(static_cast<char>(v >> shift & 0xff));
    };
    for (std::uint32_t count : {4u, 4u, 0u}) big_endian(count);
    const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const auto& corner : corners)
      for (float c : corner) {
        std::uint32_t bits;
        std::memcpy(&bits, &c, 4);
        big_endian(bits);
      }
    for (const auto& face : {std::array<std::uint32_t, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}) {
      big_endian(3);
      for (std::uint32_t v : face) big_endian(v);
      if (colour_counts) big_endian(0);
    }
    const std::string path = scratch(colour_counts ? "geomview_binary.off" : "binary.off");
    write_file(path, off);
    if (colour_counts)
      REQUIRE_THROWS_WITH(read_mesh(path), Contains("a colour count after each face's indices") && Contains("ASCII OFF"));
    else
      REQUIRE(read_mesh(path).mesh.triangle_count() == 4);
  }

  write_file(scratch("polyline.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("polyline.obj")), Contains("line 5: the OBJ statement 'l' is not supported"));
}

TEST_CASE("read_mesh refuses NaN and infinite coordinates") {
  REQUIRE_THROWS_AS(read_mesh(data("nan.off")), InputError);
  REQUIRE_THROWS_WITH(read_mesh(data("nan.off")),
                      Contains("nan.off: vertex 2 has a non-finite coordinate (0, nan, 0)"));
  REQUIRE_THROWS_WITH(read_mesh(data("inf.obj")),
                      Contains("inf.obj: vertex 2 has a non-finite coordinate (0, inf, 0)"));

  // Binary formats carry NaN through CGAL's reader; the check after reading catches it.
  std::string stl(80, '\0');
  append(stl, std::uint32_t{1});
  const float facet[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, std::nanf(""), 0};
  for (float c : facet) append(stl, c);
  append(stl, std::uint16_t{0});
  const std::string path = scratch("nan.stl");
  write_file(path, stl);
  REQUIRE_THROWS_WITH(read_mesh(path), Contains("nan.stl: facet 0 has a non-finite coordinate (0, nan, 0)"));

  std::string ascii_stl = read_file(data("tetrahedron.stl"));
  ascii_stl.replace(ascii_stl.find("vertex 0 0 1"), 12, "vertex 0 0 -inf");
  write_file(scratch("inf.stl"), ascii_stl);
  REQUIRE_THROWS_WITH(read_mesh(scratch("inf.stl")), Contains("facet 1 has a non-finite coordinate (0, 0, -inf)"));

  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (double c : {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, std::nan("")}) append(ply, c);
  append(ply, static_cast<unsigned char>(3));
  for (int v : {0, 1, 2}) append(ply, v);
  write_file(scratch("nan.ply"), ply);
  REQUIRE_THROWS_WITH(read_mesh(scratch("nan.ply")), Contains("vertex 2 has a non-finite coordinate (0, 1, nan)"));
}

TEST_CASE("read_mesh refuses face indices out of range") {
  REQUIRE_THROWS_AS(read_mesh(data("index_out_of_range.off")), InputError);
  REQUIRE_THROWS_WITH(read_mesh(data("index_out_of_range.off")),
                      Contains("index_out_of_range.off: face 2 has vertex index 9 out of range [0, 4)"));
  // CGAL's OBJ reader lets the index one past the end through; the check after reading does not,
  // and names the line with the file's own index.
  REQUIRE_THROWS_WITH(read_mesh(data("index_out_of_range.obj")),
                      Contains("face 3 (line 9) refers to vertex 5, but the file has 4 vertices"));
  // What CGAL misreads into short or wild faces: OBJ index 0 or a letter, an OFF whose header
  // declares fewer vertices than it has (a vertex line read as a face).
  const std::string tetra_obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n";
  write_file(scratch("index_zero.obj"), tetra_obj + "f 2 3 0\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("index_zero.obj")), Contains("face 3 (line 8): '0' is not a vertex index"));
  // Indices beyond 64 bits are shown as the file writes them, not clamped (nor, negative, taken
  // for a short face).
  for (const std::string index : {"99999999999999999999", "-99999999999999999999", "-9223372036854775808"}) {
    write_file(scratch("huge_index.obj"), tetra_obj + "f 2 3 " + index + "\n");
    REQUIRE_THROWS_WITH(read_mesh(scratch("huge_index.obj")),
                        Contains("face 3 (line 8) refers to vertex " + index + ", but the file has 4 vertices"));
  }
  write_file(scratch("huge_index.off"), "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n"
                                        "3 1 2 -99999999999999999999\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("huge_index.off")),
                      Contains("face 3 has vertex index -99999999999999999999 out of range [0, 4)"));
  // An ascii PLY index beyond CGAL's int: named with its line, not "the body does not match".
  const std::string ply_header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                                 "property double z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                 "end_header\n0 0 0\n1 0 0\n0 1 0\n";
  for (const std::string index : {"99999999999999999999", "3000000000"}) {
    write_file(scratch("huge_index.ply"), ply_header + "3 0 1 " + index + "\n");
    REQUIRE_THROWS_WITH(read_mesh(scratch("huge_index.ply")),
                        Contains("face 0 (line 13) has vertex index " + index + " out of range [0, 3)"));
  }
  write_file(scratch("letters.obj"), tetra_obj + "f a b c\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("letters.obj")), Contains("'a' is not a vertex index"));
  // What CGAL reads as something else and does not refuse: a fractional index, a word after a
  // face's indices.
  write_file(scratch("fraction.obj"), tetra_obj + "f 2 3 4.5\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("fraction.obj")), Contains("face 3 (line 8): '4.5' is not a vertex index"));
  write_file(scratch("trailing.obj"), tetra_obj + "f 2 3 4 junk\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("trailing.obj")), Contains("'junk' is not a vertex index"));
  write_file(scratch("fraction.off"), "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3.7\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("fraction.off")), Contains("face 3 (line 10): '3.7' is not a vertex index"));
  write_file(scratch("no_xyz.ply"),
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float a\nproperty float b\nproperty float z\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("no_xyz.ply")), Contains("its vertex element has no x, y properties (it has: a, b, z)"));
  write_file(scratch("header_short.off"), "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("header_short.off")),
                      Contains("face 0 (line 6) has 0 vertices") && Contains("header's vertex count, 3"));
}

TEST_CASE("read_mesh reports what SurfaceMesh refuses, with the file name and a --repair hint") {
  REQUIRE_THROWS_AS(read_mesh(data("nonmanifold_edge.off")), InputError);
  REQUIRE_THROWS_WITH(
      read_mesh(data("nonmanifold_edge.off")),
      Contains("nonmanifold_edge.off: mesh is not manifold: edge (0, 1) has 3") && Contains("; --repair may fix it"));
  REQUIRE_THROWS_WITH(read_mesh(data("nonmanifold_vertex.off")),
                      Contains("vertex 0 joins 2 separate fans") && Contains("--repair may fix it"));
  REQUIRE_THROWS_WITH(read_mesh(data("inconsistent_orientation.off")),
                      Contains("inconsistent orientation: triangles 0 and 1") && Contains("--repair may fix it"));
  REQUIRE_THROWS_WITH(read_mesh(data("zero_area.off")),
                      Contains("zero_area.off: triangle 1 (0, 2, 1) has zero area") && Contains("--repair may fix it"));
  REQUIRE_THROWS_WITH(read_mesh(data("duplicate_triangle.off")),
                      Contains("triangles 0 and 2 are duplicates") && Contains("--repair may fix it"));
}

TEST_CASE("an unwelded triangle soup is refused without --repair and welded into a closed mesh with it") {
  REQUIRE_THROWS_AS(read_mesh(data("soup.off")), InputError);
  REQUIRE_THROWS_WITH(read_mesh(data("soup.off")),
                      Contains("soup.off: looks like a triangle soup: vertices 0 and 10 coincide but are not shared") &&
                          Contains("rerun with --repair"));

  const LoadedMesh loaded = read_mesh(data("soup.off"), {true});
  REQUIRE(loaded.mesh.vertex_count() == 6);
  REQUIRE(loaded.mesh.triangle_count() == 8);
  REQUIRE(loaded.mesh.is_closed());
  REQUIRE(loaded.mesh.component_count() == 1);
  REQUIRE(loaded.mesh.euler_characteristic() == 2);
  REQUIRE(signed_volume(loaded.mesh) == Approx(4.0 / 3.0));
  REQUIRE(loaded.repair.merged_vertices == 18);
  REQUIRE(loaded.repair.reoriented_faces == 0);
  REQUIRE(loaded.repair.changed());
}

TEST_CASE("A crack where one side of a seam has corners the other lacks is refused, and --repair splits its edge") {
  // The unit cube with its front face split at two points of its bottom edge, which the bottom face
  // uses whole (a T-junction, common in CAD exports): on the edge, and a hair off it.
  for (const double lift : {0.0, 1e-8}) {
    INFO("lift " << lift);
    std::string off = "OFF\n10 14 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n";
    off += fmt::format("{} {} 0\n{} {} 0\n", 1.0 / 3, lift, 2.0 / 3, -lift);
    off += "3 0 2 3\n3 0 3 1\n3 4 5 7\n3 4 7 6\n3 2 6 7\n3 2 7 3\n3 0 4 6\n3 0 6 2\n3 1 3 7\n3 1 7 5\n"
           "3 0 8 4\n3 8 9 4\n3 9 1 5\n3 9 5 4\n";
    const std::string path = scratch("cube_cracked.off");
    write_file(path, off);
    REQUIRE_THROWS_WITH(read_mesh(path), Contains("cube_cracked.off: has a crack: vertex 8 lies on the boundary edge (1, 0) "
                                                  "of another face") &&
                                             Contains("2 such corners") && Contains("rerun with --repair"));
    const LoadedMesh loaded = read_mesh(path, {true});
    REQUIRE(loaded.repair.split_edges == 1);
    REQUIRE(loaded.repair.soup_changed());
    REQUIRE(loaded.mesh.vertex_count() == 10);
    REQUIRE(loaded.mesh.triangle_count() == 16);
    REQUIRE(loaded.mesh.is_closed());
    REQUIRE(loaded.mesh.euler_characteristic() == 2);
    REQUIRE(signed_volume(loaded.mesh) == Approx(1.0));
  }
}

TEST_CASE("Repair removes the wall two welded solids share, both copies, and keeps one copy of a lone double sheet") {
  // Boxes [0,1]^3 and [1,2]x[0,1]^2, each closed and oriented outwards, sharing the face x = 1 (its
  // two triangles listed once by each box, in opposite orientations).
  std::string off = "OFF\n12 24 0\n";
  for (int x = 0; x <= 2; ++x)
    for (int y = 0; y <= 1; ++y)
      for (int z = 0; z <= 1; ++z) off += fmt::format("{} {} {}\n", x, y, z);
  const auto at = [](int x, int y, int z) { return 4 * x + 2 * y + z; };
  for (int box = 0; box < 2; ++box) {
    const auto quad = [&](int a, int b, int c, int d) {
      off += fmt::format("3 {} {} {}\n3 {} {} {}\n", a, b, c, a, c, d);
    };
    const int x0 = box, x1 = box + 1;
    quad(at(x0, 0, 0), at(x0, 0, 1), at(x0, 1, 1), at(x0, 1, 0));  // x = x0, normal -x
    quad(at(x1, 0, 0), at(x1, 1, 0), at(x1, 1, 1), at(x1, 0, 1));  // x = x1, normal +x
    quad(at(x0, 0, 0), at(x1, 0, 0), at(x1, 0, 1), at(x0, 0, 1));  // y = 0, normal -y
    quad(at(x0, 1, 0), at(x0, 1, 1), at(x1, 1, 1), at(x1, 1, 0));  // y = 1, normal +y
    quad(at(x0, 0, 0), at(x0, 1, 0), at(x1, 1, 0), at(x1, 0, 0));  // z = 0, normal -z
    quad(at(x0, 0, 1), at(x1, 0, 1), at(x1, 1, 1), at(x0, 1, 1));  // z = 1, normal +z
  }
  const std::string path = scratch("two_boxes_shared_face.off");
  write_file(path, off);
  REQUIRE_THROWS_WITH(read_mesh(path), Contains("duplicates") && Contains("--repair may fix it"));
  const LoadedMesh loaded = read_mesh(path, {true});
  CHECK(loaded.repair.removed_internal_faces == 4);
  CHECK(loaded.repair.duplicated_nonmanifold_vertices == 0);
  REQUIRE(loaded.mesh.triangle_count() == 20);
  REQUIRE(loaded.mesh.is_closed());
  REQUIRE(loaded.mesh.component_count() == 1);
  REQUIRE(loaded.mesh.euler_characteristic() == 2);
  REQUIRE(signed_volume(loaded.mesh) == Approx(2.0));

  // A square listed twice, once each way, and nothing else: no solid on either side, one copy kept.
  const std::string sheet = scratch("double_sheet.off");
  write_file(sheet, "OFF\n4 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n3 0 2 1\n3 0 3 2\n");
  const LoadedMesh kept = read_mesh(sheet, {true});
  CHECK(kept.repair.removed_internal_faces == 0);
  CHECK(kept.repair.removed_duplicate_faces == 2);
  REQUIRE(kept.mesh.triangle_count() == 2);
}

TEST_CASE("T-junctions: corners on another face's boundary edge, away from its ends, split edge by edge") {
  // Triangle 0 has corner 3 on its edge 0 and corner 4 on its edge 1; they are corners of triangle 1.
  // Corner 5 lies a hair beyond the end of triangle 0's edge 2 (a near twin of corner 0, not a
  // junction), and corner 2 of triangle 0 is its own.
  const std::vector<Vec3> p = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0, 0}, {1, 1, 0}, {0, -1e-9, 0}, {2, 2, 1}};
  std::vector<Triangle> t = {{0, 1, 2}, {3, 4, 6}, {5, 6, 4}};
  std::vector<TJunction> found = find_t_junctions(p, t, 1e-6);
  REQUIRE(found.size() == 2);
  CHECK(found[0].vertex == 3);
  CHECK(found[0].triangle == 0);
  CHECK(found[0].edge == 0);
  CHECK(found[0].along == 0.5);
  CHECK(found[1].vertex == 4);
  CHECK(found[1].edge == 1);
  REQUIRE(split_at_t_junctions(t, found) == 1);  // edge 0 first; edge 1 is whole in one of its parts
  REQUIRE(t == std::vector<Triangle>{{0, 3, 2}, {3, 4, 6}, {5, 6, 4}, {3, 1, 2}});
  found = find_t_junctions(p, t, 1e-6);
  REQUIRE(found.size() == 1);
  CHECK(found[0].vertex == 4);
  CHECK(found[0].triangle == 3);
  REQUIRE(split_at_t_junctions(t, found) == 1);
  REQUIRE(t == std::vector<Triangle>{{0, 3, 2}, {3, 4, 6}, {5, 6, 4}, {1, 4, 3}, {4, 2, 3}});
  REQUIRE(find_t_junctions(p, t, 1e-6).empty());
}

TEST_CASE("a soup whose corners nearly coincide is refused naming --weld, and --weld welds it") {
  // soup_jittered.off: the octahedron soup with its corner copies 1e-10 to 2.3e-9 apart. The exact
  // twin test sees no seam; the near one does, and suggests a weld that takes every pair.
  REQUIRE_THROWS_WITH(read_mesh(data("soup_jittered.off")),
                      Contains("soup_jittered.off: looks like a triangle soup or a seam whose corners nearly "
                               "coincide: vertices 0 and 10 are 1e-09 apart") &&
                          Contains("(24 boundary vertices have such a twin); rerun with --repair --weld 1e-09"));
  // Exact welding alone leaves the seams open: said, not remeshed as 8 loose triangles.
  REQUIRE_THROWS_WITH(read_mesh(data("soup_jittered.off"), {true}),
                      Contains("after --repair, vertices") && Contains("--weld 1e-09"));
  for (const double weld : {1e-9, 1e-6}) {
    ReadOptions options;
    options.repair = true;
    options.weld = weld;
    const LoadedMesh loaded = read_mesh(data("soup_jittered.off"), options);
    REQUIRE(loaded.mesh.vertex_count() == 6);
    REQUIRE(loaded.mesh.triangle_count() == 8);
    REQUIRE(loaded.mesh.is_closed());
    REQUIRE(loaded.mesh.euler_characteristic() == 2);
    REQUIRE(loaded.repair.welded_vertices == 18);
    REQUIRE(loaded.repair.merged_vertices == 0);
    REQUIRE(signed_volume(loaded.mesh) == Approx(4.0 / 3.0));
  }
  // Too small a weld leaves some seams, and says so again.
  ReadOptions small;
  small.repair = true;
  small.weld = 1e-10;
  REQUIRE_THROWS_WITH(read_mesh(data("soup_jittered.off"), small), Contains("nearly coincide"));
}

TEST_CASE("The suggested --weld closes the seams also when a corner's copies lie further apart than the closest pairs") {
  // The octahedron soup with the k-th copy of each corner moved k * 0.9e-6 of the diagonal along x:
  // the closest pairs are 0.9e-6 apart, but a corner's copies span 2.7e-6 (or 1.8e-6), which a
  // weld of 1e-6 from the first copy does not reach. The suggestion is where the seams stop closing.
  const double step = 0.9e-6 * 2 * std::sqrt(3.0);  // the diagonal of [-1, 1]^3
  std::string off = "OFF\n24 8 0\n";
  const double corners[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  int copies[6] = {};
  for (const auto& face : faces)
    for (int c : face)
      off += fmt::format("{:.17g} {:.17g} {:.17g}\n", corners[c][0] + step * copies[c]++, corners[c][1], corners[c][2]);
  for (int f = 0; f < 8; ++f) off += fmt::format("3 {} {} {}\n", 3 * f, 3 * f + 1, 3 * f + 2);
  write_file(scratch("chain.off"), off);
  REQUIRE_THROWS_WITH(read_mesh(scratch("chain.off")), Contains("nearly coincide") && Contains("--weld 1e-05 to weld"));
  ReadOptions options;
  options.repair = true;
  options.weld = 1e-5;
  const LoadedMesh loaded = read_mesh(scratch("chain.off"), options);
  REQUIRE(loaded.mesh.vertex_count() == 6);
  REQUIRE(loaded.mesh.is_closed());
  // The smallest power of ten above the closest pairs leaves the soup open: refused again, after
  // the repair, with the same advice.
  options.weld = 1e-6;
  REQUIRE_THROWS_WITH(read_mesh(scratch("chain.off"), options), Contains("after --repair") && Contains("--weld 1e-05"));
}

TEST_CASE("A disk whose outline has two short edges in a row is no soup, and exact and near twins are named together") {
  // A fan of six triangles round the origin; corners 0, 1, 2 of its outline 1e-9 apart in a row.
  std::string fan = "OFF\n7 6 0\n0 0 0\n1 0 0\n1 1e-9 0\n1 2e-9 0\n-0.5 0.8 0\n-1 0 0\n0 -1 0\n";
  fan += "3 0 1 2\n3 0 2 3\n3 0 3 4\n3 0 4 5\n3 0 5 6\n3 0 6 1\n";
  write_file(scratch("fan_short_edges.off"), fan);
  const LoadedMesh disk = read_mesh(scratch("fan_short_edges.off"));
  REQUIRE(disk.mesh.triangle_count() == 6);
  REQUIRE(disk.mesh.boundary_loops().size() == 1);
  // The octahedron soup with one corner copy moved by 1e-9: exact twins and a near one, one advice.
  std::string soup = read_file(data("soup.off"));
  const std::string first = "\n1 0 0\n";
  soup.replace(soup.find(first), first.size(), "\n1.000000001 0 0\n");
  write_file(scratch("soup_one_near.off"), soup);
  REQUIRE_THROWS_WITH(read_mesh(scratch("soup_one_near.off")),
                      Contains("coincide but are not shared") && Contains("a twin nearly at the same point") &&
                          Contains("rerun with --repair --weld 1e-09 to weld them"));
}

TEST_CASE("A --weld above the file's shortest edge says it collapsed edges, and names that weld when the read fails") {
  // The octahedron with its edge from (1, 0, 0) to (0, 0, 1) split 0.001 from its first end: a
  // closed mesh whose shortest edge is 0.0014 long, 4.1e-4 of the diagonal.
  std::string off = "OFF\n7 10 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n0.999 0 0.001\n";
  off += "3 0 2 6\n3 6 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 6\n3 3 6 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";
  write_file(scratch("short_edge.off"), off);
  const double half_shortest = std::sqrt(2.0) * 0.001 / (2 * std::sqrt(12.0));
  ReadOptions options;
  options.repair = true;
  options.weld = 1e-3;
  const LoadedMesh welded = read_mesh(scratch("short_edge.off"), options);
  REQUIRE(welded.mesh.vertex_count() == 6);
  REQUIRE(welded.mesh.is_closed());
  REQUIRE(welded.repair.weld_collapsed_sides == 2);
  REQUIRE_THAT(welded.repair.notes.back(),
               Contains("--weld 0.001 collapsed 2 face sides of the file, up to 0.00141 long (below " +
                        fmt::format("{:.3g}", half_shortest)) &&
                   Contains("the surface lost those edges"));
  // Just below half the shortest edge, nothing collapses and nothing is said.
  options.weld = 0.99 * half_shortest;
  const LoadedMesh kept = read_mesh(scratch("short_edge.off"), options);
  REQUIRE(kept.mesh.vertex_count() == 7);
  REQUIRE(kept.repair.weld_collapsed_sides == 0);
  for (const std::string& note : kept.repair.notes) REQUIRE_THAT(note, !Contains("collapsed"));
  // A weld that tears CGAL's elk apart is named as the cause, not the file.
  options.weld = 0.015;
  REQUIRE_THROWS_WITH(read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/elk.off", options),
                      Contains("elk.off: --weld 0.015 collapsed") && Contains("and left seams open") &&
                          !Contains("rerun with"));
  // One so large that it takes nearly every face with the edges it collapses, leaving no seam:
  // 2 of the elk's 3290 faces were left, and the diagram of them "passed".
  options.weld = 0.5;
  REQUIRE_THROWS_WITH(read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/elk.off", options),
                      Contains("elk.off: has 2 of its 3290 faces left after --weld 0.5") &&
                          Contains("collapsed 9578 face sides"));
}

TEST_CASE("Welding takes points to the earliest representative within the tolerance, without chains") {
  const std::vector<Vec3> line = {{0, 0, 0}, {0.6, 0, 0}, {1.2, 0, 0}, {1.7, 0, 0}, {5, 0, 0}, {0, 0.99, 0}};
  // 1.2 is within 1 of 0.6 but not of 0, the representative that took 0.6: it starts its own.
  REQUIRE(weld_representatives(line, 1.0) == std::vector<int>{0, 0, 2, 2, 4, 0});
  REQUIRE(weld_representatives(line, 0.0) == std::vector<int>{0, 1, 2, 3, 4, 5});
  // A distance equal to the tolerance is not within it.
  REQUIRE(weld_representatives({{0, 0, 0}, {0.5, 0, 0}}, 0.5) == std::vector<int>{0, 1});

  // Near twins: not at the same point, not joined, among the candidates only.
  const std::vector<Vec3> points = {{0, 0, 0}, {0, 0, 0}, {0.1, 0, 0}, {0.15, 0, 0}, {3, 0, 0}, {3.05, 0, 0}};
  const auto never = [](int, int) { return false; };
  NearTwins twins = find_near_twins(points, {0, 1, 2, 3, 4, 5}, 0.2, never);
  REQUIRE(twins.count == 6);
  REQUIRE(twins.a == 0);
  REQUIRE(twins.b == 2);
  REQUIRE(twins.distance == Approx(0.1));
  REQUIRE(twins.max_distance == Approx(0.15));
  const auto edge_2_3 = [](int a, int b) { return std::min(a, b) == 2 && std::max(a, b) == 3; };
  twins = find_near_twins(points, {2, 3, 4}, 0.2, edge_2_3);
  REQUIRE(twins.count == 0);
  REQUIRE(twins.a == -1);
  REQUIRE(find_near_twins(points, {0, 1}, 0.2, never).count == 0);  // the same point is an exact twin
}

TEST_CASE("Repair orients, removes duplicates and degenerate faces, and cuts non-manifold configurations") {
  SECTION("one reversed face of a closed octahedron is the one reoriented") {
    const LoadedMesh loaded = read_mesh(data("inconsistent_orientation.off"), {true});
    REQUIRE(loaded.repair.reoriented_faces == 1);
    REQUIRE(loaded.mesh.is_closed());
    REQUIRE(loaded.mesh.euler_characteristic() == 2);
    REQUIRE(signed_volume(loaded.mesh) == Approx(4.0 / 3.0));
  }
  SECTION("a closed mesh oriented inwards is turned outwards") {
    const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const std::vector<Triangle> inwards = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    write_mesh(scratch("inwards.off"), p, inwards);
    REQUIRE(signed_volume(read_mesh(scratch("inwards.off")).mesh) < 0);  // valid as it is without repair
    const LoadedMesh loaded = read_mesh(scratch("inwards.off"), {true});
    REQUIRE(loaded.repair.reoriented_faces == 4);
    REQUIRE(signed_volume(loaded.mesh) == Approx(1.0 / 6.0));
  }
  SECTION("a duplicate triangle is removed") {
    const LoadedMesh loaded = read_mesh(data("duplicate_triangle.off"), {true});
    REQUIRE(loaded.repair.removed_duplicate_faces == 1);
    REQUIRE(loaded.mesh.triangle_count() == 2);
  }
  SECTION("a zero-area triangle is removed, and the vertex only it used") {
    const LoadedMesh loaded = read_mesh(data("zero_area.off"), {true});
    REQUIRE(loaded.repair.removed_degenerate_faces == 1);
    REQUIRE(loaded.repair.removed_unreferenced_vertices == 1);
    REQUIRE(loaded.mesh.triangle_count() == 1);
    REQUIRE(loaded.mesh.vertex_count() == 3);
  }
  SECTION("three triangles on one edge are cut apart") {
    // CGAL's orient_polygon_soup joins no two faces across an edge with 3 faces: each triangle
    // keeps its own copy of the edge's endpoints (2 x 2 copies).
    const LoadedMesh loaded = read_mesh(data("nonmanifold_edge.off"), {true});
    REQUIRE(loaded.repair.duplicated_nonmanifold_vertices == 4);
    REQUIRE(loaded.mesh.vertex_count() == 9);
    REQUIRE(loaded.mesh.component_count() == 3);
    REQUIRE(loaded.repair.notes.size() == 2);  // the copies, and the boundary loops left
  }
  SECTION("two cones sharing an apex get one apex each") {
    const LoadedMesh loaded = read_mesh(data("nonmanifold_vertex.off"), {true});
    REQUIRE(loaded.repair.duplicated_nonmanifold_vertices == 1);
    REQUIRE(loaded.mesh.vertex_count() == 8);
    REQUIRE(loaded.mesh.component_count() == 2);
  }
  SECTION("what repair cannot fix is still an error that says so") {
    REQUIRE_THROWS_WITH(read_mesh(data("nan.off"), {true}), Contains("non-finite coordinate"));
  }
}

TEST_CASE("fill_small_holes closes the holes up to a length and keeps the others") {
  // A 12 x 12 grid on the unit square without one of its quads (a hole of 4 edges, 4/12 around)
  // and without a row of four (10 edges, 10/12 around).
  std::vector<Vec3> p;
  std::vector<Triangle> t;
  const int n = 12;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) p.push_back({double(i) / n, double(j) / n, 0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (j == 2 && i == 2) continue;                      // the small hole
      if (j == 6 && i >= 6 && i < 10) continue;           // the large one
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      t.push_back({a, b, d});
      t.push_back({a, d, c});
    }
  const SurfaceMesh holed(p, t);
  REQUIRE(holed.boundary_loops().size() == 3);
  REQUIRE(holed.euler_characteristic() == -1);

  RepairReport report;
  const SurfaceMesh one = fill_small_holes(holed, 0.5, &report);
  REQUIRE(report.filled_holes == 1);
  REQUIRE(report.changed());
  REQUIRE(report.notes.size() == 1);
  REQUIRE(one.boundary_loops().size() == 2);
  REQUIRE(one.euler_characteristic() == 0);
  REQUIRE(one.triangle_count() == holed.triangle_count() + 2);  // 4 corners, no new vertex
  REQUIRE(one.vertex_count() == holed.vertex_count());
  for (int k = 0; k < holed.triangle_count(); ++k) REQUIRE(one.triangle(k) == holed.triangle(k));
  // The new triangles turn the way the mesh does (+z).
  for (int k = holed.triangle_count(); k < one.triangle_count(); ++k) REQUIRE(one.triangle_normal(k).z > 0);

  const SurfaceMesh both = fill_small_holes(holed, 1.0);
  REQUIRE(both.boundary_loops().size() == 1);
  REQUIRE(both.euler_characteristic() == 1);
  REQUIRE(both.triangle_count() == holed.triangle_count() + 2 + 8);
  REQUIRE(fill_small_holes(holed, 0.3).triangle_count() == holed.triangle_count());

  // A lone triangle beside it: its outline (3 around) is never filled, which would cover it twice.
  std::vector<Vec3> p2 = p;
  std::vector<Triangle> t2 = t;
  const int base = static_cast<int>(p2.size());
  for (const Vec3& q : {Vec3{2, 0, 0}, Vec3{2.5, 0, 0}, Vec3{2, 0.5, 0}}) p2.push_back(q);  // 1.71 around
  t2.push_back({base, base + 1, base + 2});
  RepairReport with_lone;
  const SurfaceMesh lone = fill_small_holes(SurfaceMesh(p2, t2), 2.0, &with_lone);
  REQUIRE(with_lone.filled_holes == 2);
  REQUIRE(lone.boundary_loops().size() == 2);  // the square's outline (4 around) and the triangle's
  REQUIRE(lone.triangle_count() == static_cast<int>(t2.size()) + 10);
  REQUIRE(with_lone.notes.size() == 2);
  REQUIRE_THAT(with_lone.notes[1], Contains("left 1 hole open: the whole outline of a component"));
  RepairReport nothing;
  REQUIRE(fill_small_holes(holed, 0.1, &nothing).triangle_count() == holed.triangle_count());
  REQUIRE(nothing.filled_holes == 0);
  REQUIRE_THAT(nothing.notes.at(0), Contains("no hole filled: the shortest of the 3 boundary loops is 0.333333 long"));

  // Through read_mesh: the length is a fraction of the bounding-box diagonal (sqrt 2 here). For a
  // fraction that large the outer boundary (4 around) is short enough too, but its patch would lie
  // over the sheet: it is left open.
  write_mesh(scratch("holed.off"), p, t);
  const LoadedMesh read = read_mesh(scratch("holed.off"), ReadOptions{false, 0.5 / std::sqrt(2.0)});
  REQUIRE(read.repair.filled_holes == 1);
  REQUIRE(read.mesh.boundary_loops().size() == 2);
  const LoadedMesh all = read_mesh(scratch("holed.off"), ReadOptions{false, 3.0});
  REQUIRE(all.repair.filled_holes == 2);
  REQUIRE(all.mesh.boundary_loops().size() == 1);
  REQUIRE_THAT(all.repair.notes.at(1), Contains("left 1 hole open: filling it would cut through the surface"));

  // A box without its lid: the lid's loop is filled and the box is closed.
  const std::vector<Vec3> box = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const std::vector<Triangle> sides = {{0, 2, 1}, {0, 3, 2}, {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
                                       {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  RepairReport lid;
  const SurfaceMesh closed = fill_small_holes(SurfaceMesh(box, sides), 4.5, &lid);
  REQUIRE(lid.filled_holes == 1);
  REQUIRE(closed.is_closed());
  REQUIRE(closed.euler_characteristic() == 2);
  REQUIRE(closed.triangle_count() == 12);
}

TEST_CASE("polygons are triangulated by exact ear clipping, also when non-convex") {
  const LoadedMesh cube = read_mesh(data("cube_quads.obj"));
  REQUIRE(cube.repair.triangulated_faces == 6);
  REQUIRE(cube.repair.removed_unreferenced_vertices == 1);  // dropped quietly, no error
  REQUIRE(cube.mesh.vertex_count() == 8);
  REQUIRE(cube.mesh.triangle_count() == 12);
  REQUIRE(cube.mesh.is_closed());
  REQUIRE(cube.mesh.euler_characteristic() == 2);
  REQUIRE(signed_volume(cube.mesh) == Approx(1.0));

  // A fan from the caps' first corner would leave the L: area and volume would be wrong.
  const LoadedMesh prism = read_mesh(data("l_prism.obj"));
  REQUIRE(prism.repair.triangulated_faces == 8);
  REQUIRE(prism.repair.notes.empty());
  REQUIRE(prism.mesh.triangle_count() == 20);
  REQUIRE(prism.mesh.is_closed());
  REQUIRE(prism.mesh.euler_characteristic() == 2);
  REQUIRE(prism.mesh.area() == Approx(14.0));
  REQUIRE(signed_volume(prism.mesh) == Approx(3.0));
}

TEST_CASE("PLY and STL, ascii and binary, are read") {
  const auto check_tetrahedron = [](const LoadedMesh& loaded) {
    REQUIRE(loaded.mesh.vertex_count() == 4);
    REQUIRE(loaded.mesh.triangle_count() == 4);
    REQUIRE(loaded.mesh.is_closed());
    REQUIRE(signed_volume(loaded.mesh) == Approx(1.0 / 6.0));
    REQUIRE_FALSE(loaded.repair.changed());
  };
  check_tetrahedron(read_mesh(data("tetrahedron.ply")));
  check_tetrahedron(read_mesh(data("tetrahedron.stl")));  // CGAL welds STL's repeated corners

  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : tetra_points)
    for (float c : p) append(ply, c);
  for (const auto& f : tetra_faces) {
    append(ply, static_cast<unsigned char>(3));
    for (int v : f) append(ply, v);
  }
  const std::string ply_path = scratch("tetrahedron_binary.PLY");  // extension case does not matter
  write_file(ply_path, ply);
  check_tetrahedron(read_mesh(ply_path));

  std::string stl(80, ' ');
  append(stl, std::uint32_t{4});
  for (const auto& f : tetra_faces) {
    for (int c = 0; c < 3; ++c) append(stl, 0.0f);
    for (int v : f)
      for (float c : tetra_points[v]) append(stl, c);
    append(stl, std::uint16_t{0});
  }
  const std::string stl_path = scratch("tetrahedron_binary.stl");
  write_file(stl_path, stl);
  check_tetrahedron(read_mesh(stl_path));
}

namespace {

// The tetrahedron as a PLY of the given format, with `faces` face records under a header that
// declares `declared_faces`, indices of `index_type` ("int", "uchar", ...), counts as uchar.
std::string tetrahedron_ply(const std::string& format, int declared_vertices, int declared_faces, int faces,
                            const std::string& index_type = "int") {
  std::string ply = fmt::format(
      "ply\nformat {} 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "element face {}\nproperty list uchar {} vertex_indices\nend_header\n",
      format, declared_vertices, declared_faces, index_type);
  const bool ascii = format == "ascii";
  for (const auto& p : tetra_points)
    if (ascii)
      ply += fmt::format("{} {} {}\n", p[0], p[1], p[2]);
    else
      for (float c : p) append(ply, c);
  for (int f = 0; f < faces; ++f) {
    if (ascii) {
      ply += fmt::format("3 {} {} {}\n", tetra_faces[f][0], tetra_faces[f][1], tetra_faces[f][2]);
      continue;
    }
    append(ply, static_cast<unsigned char>(3));
    for (int v : tetra_faces[f]) {
      if (index_type == "int") append(ply, v);
      if (index_type == "uchar" || index_type == "char") append(ply, static_cast<unsigned char>(v));
      if (index_type == "ushort" || index_type == "short") append(ply, static_cast<std::uint16_t>(v));
    }
  }
  return ply;
}

// The tetrahedron as binary STL: `facets` records under a header count of `declared`.
std::string tetrahedron_stl(std::uint32_t declared, int facets) {
  std::string stl(80, ' ');
  append(stl, declared);
  for (int f = 0; f < facets; ++f) {
    for (int c = 0; c < 3; ++c) append(stl, 0.0f);
    for (int v : tetra_faces[f % 4])
      for (float c : tetra_points[v]) append(stl, c);
    append(stl, std::uint16_t{0});
  }
  return stl;
}

}  // namespace

TEST_CASE("A header declaring more elements than the file's size can hold is refused at once, before allocating") {
  // CGAL's OFF reader sized its vectors from the header: this file took 50 s and 23 GB.
  write_file(scratch("declares_1e9_faces.off"), "OFF\n3 1000000000 0\n0 0 0\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("declares_1e9_faces.off")),
                      Contains("declares 3 vertices and 1000000000 faces") && Contains("its 25 bytes could not hold"));
  write_file(scratch("declares_1e9_vertices.off"), "OFF\n1000000000 1 0\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("declares_1e9_vertices.off")),
                      Contains("1000000000 vertices") && Contains("its 19 bytes could not hold"));
  // The header's counts on the keyword's line, nothing after: the size alone refuses it.
  std::string off = "OFF BINARY\n";
  for (std::uint32_t count : {4u, 1000000000u, 0u})
    for (int shift = 24; shift >= 0; shift -= 8) off.push_back(static_cast<char>(count >> shift & 0xff));
  write_file(scratch("declares_1e9_faces_binary.off"), off);
  REQUIRE_THROWS_WITH(read_mesh(scratch("declares_1e9_faces_binary.off")),
                      Contains("is too short for its header: it declares 4 vertices and 1000000000 faces") &&
                          Contains("the file has only 23 bytes"));
  // An OFF face declaring 2e9 vertices (CGAL allocated them before reading one).
  write_file(scratch("huge_face.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("huge_face.off")), Contains("face 0 (line 6) lists 3 of its 2000000000"));
  for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    const std::string path = scratch("declares_1e9_faces_" + format + ".ply");
    write_file(path, tetrahedron_ply(format, 4, 1000000000, 4));
    REQUIRE_THROWS_WITH(read_mesh(path), Contains("is too short for its header: it declares 4 vertices and "
                                                  "1000000000 faces") &&
                                             Contains(fmt::format("the file has only {} bytes",
                                                                  std::filesystem::file_size(path))));
  }
  // A PLY list declaring more entries than the rest of the file holds (CGAL resized its buffer to it).
  write_file(scratch("huge_list.ply"),
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
             "element face 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
             "2000000000 0 1 2\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("huge_list.ply")),
                      Contains("face 0's vertex_indices list declares 2000000000 entries, more than the 7 bytes left"));
  std::string stl = tetrahedron_stl(1000000000, 4);
  write_file(scratch("declares_1e9_facets.stl"), stl);
  REQUIRE_THROWS_WITH(read_mesh(scratch("declares_1e9_facets.stl")),
                      Contains("it has 284 bytes, not the 84 + 50 x 1000000000 = 50000000084 its header's count of "
                               "1000000000 facets takes"));
}

TEST_CASE("PLY and binary STL files holding more elements than their header declares are refused") {
  write_file(scratch("more_faces_ascii.ply"), tetrahedron_ply("ascii", 4, 3, 4));
  REQUIRE_THROWS_WITH(read_mesh(scratch("more_faces_ascii.ply")),
                      Contains("has more than its 3 declared faces: line 17 ('3 1 2 3') follows them"));
  write_file(scratch("more_faces_binary.ply"), tetrahedron_ply("binary_little_endian", 4, 3, 4));
  REQUIRE_THROWS_WITH(read_mesh(scratch("more_faces_binary.ply")),
                      Contains("has more than its 3 declared faces: 13 bytes follow them, room for another"));
  // Trailing whitespace (ascii) and a few bytes too short for a face (binary) are no more faces.
  write_file(scratch("trailing_space.ply"), tetrahedron_ply("ascii", 4, 4, 4) + "\n  \n");
  REQUIRE(read_mesh(scratch("trailing_space.ply")).mesh.triangle_count() == 4);
  write_file(scratch("trailing_bytes.ply"), tetrahedron_ply("binary_little_endian", 4, 4, 4) + std::string(12, '\0'));
  REQUIRE(read_mesh(scratch("trailing_bytes.ply")).mesh.triangle_count() == 4);

  write_file(scratch("count_2_has_4.stl"), tetrahedron_stl(2, 4));
  REQUIRE_THROWS_WITH(read_mesh(scratch("count_2_has_4.stl")),
                      Contains("is a binary STL whose header declares 2 facets (84 + 50 x 2 = 184 bytes), but it has "
                               "284 bytes, room for 2 more facets"));
  // Padding shorter than a facet is let through, as some writers add it.
  write_file(scratch("padded.stl"), tetrahedron_stl(4, 4) + std::string(49, '\0'));
  REQUIRE(read_mesh(scratch("padded.stl")).mesh.triangle_count() == 4);
  std::string padded_nan = tetrahedron_stl(4, 4) + std::string(10, '\0');
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&padded_nan[84 + 12], &nan, 4);  // facet 0's first corner's x
  write_file(scratch("padded_nan.stl"), padded_nan);
  REQUIRE_THROWS_WITH(read_mesh(scratch("padded_nan.stl")), Contains("facet 0 has a non-finite coordinate"));
}

TEST_CASE("Messages for an OFF on one line, a too short STL and PLY indices of every integer type") {
  // CGAL takes the counts across lines but each vertex and face from a line of its own.
  write_file(scratch("one_line.off"),
             "OFF 4 4 0 0 0 0 1 0 0 0 1 0 0 0 1 3 0 2 1 3 0 1 3 3 0 3 2 3 1 2 3\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("one_line.off")),
                      Contains("has several vertices or faces on one line (line 1 holds 28 numbers)") &&
                          Contains("put each vertex and face on a line of its own"));
  write_file(scratch("counts_on_keyword_line.off"), "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  REQUIRE(read_mesh(scratch("counts_on_keyword_line.off")).mesh.triangle_count() == 1);
  write_file(scratch("counts_across_lines.off"), "OFF\n3\n1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  REQUIRE(read_mesh(scratch("counts_across_lines.off")).mesh.triangle_count() == 1);
  write_file(scratch("vertex_on_counts_line.off"), "OFF\n3 1 0 0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  REQUIRE(read_mesh(scratch("vertex_on_counts_line.off")).mesh.triangle_count() == 1);

  write_file(scratch("short.stl"), "abc");
  REQUIRE_THROWS_WITH(read_mesh(scratch("short.stl")),
                      Contains("is too short to be an STL file (3 bytes): it holds neither a binary STL's 84-byte "
                               "header nor an ascii STL's 'solid'"));

  for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"})
    for (const std::string type : {"char", "uchar", "short", "ushort", "int"}) {
      if (format == "binary_big_endian" && type != "uchar") continue;  // big-endian shorts are not written here
      const std::string path = scratch("indices_" + type + "_" + format + ".ply");
      write_file(path, tetrahedron_ply(format, 4, 4, 4, type));
      if (format == "binary_big_endian") {  // the float coordinates must be big-endian too
        std::string bytes = read_file(path);
        const std::size_t body = bytes.find("end_header\n") + 11;
        for (std::size_t at = body; at < body + 48; at += 4) std::reverse(bytes.begin() + at, bytes.begin() + at + 4);
        write_file(path, bytes);
      }
      const LoadedMesh loaded = read_mesh(path);
      CAPTURE(path);
      REQUIRE(loaded.mesh.vertex_count() == 4);
      REQUIRE(loaded.mesh.triangle_count() == 4);
      REQUIRE(signed_volume(loaded.mesh) == Approx(1.0 / 6.0));
    }
}

TEST_CASE("written meshes read back with identical positions and triangles") {
  // Doubles that %.6g or float storage would not keep.
  std::vector<Vec3> positions = {{1.0 / 3, 0.1, -0.0},
                                 {-1, 1e-300, 2.0 / 7},
                                 {0.2, 1, 1e20 / 3},
                                 {0, -1, 0.30000000000000004},
                                 {0, 0, 1},
                                 {0, 0, -1}};
  const std::vector<Triangle> triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                           {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const char* name : {"round_trip.off", "round_trip.obj", "round_trip.ply"}) {
    const std::string path = scratch(name);
    write_mesh(path, positions, triangles);
    const LoadedMesh back = read_mesh(path);
    INFO(name);
    REQUIRE(back.mesh.triangles() == triangles);
    REQUIRE(back.mesh.vertex_count() == static_cast<int>(positions.size()));
    for (std::size_t v = 0; v < positions.size(); ++v)
      for (int c = 0; c < 3; ++c) {
        const double got = back.mesh.position(static_cast<int>(v))[c], want = positions[v][c];
        REQUIRE(std::memcmp(&got, &want, sizeof(double)) == 0);  // bit for bit: -0.0 stays -0.0
      }
    write_mesh(path, back.mesh);  // the SurfaceMesh overload writes the same file
    REQUIRE(read_mesh(path).mesh.positions() == back.mesh.positions());
  }
}

TEST_CASE("write_mesh refuses unknown extensions and unwritable paths") {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  REQUIRE_THROWS_AS(write_mesh(scratch("mesh.stl"), p, {{0, 1, 2}}), InputError);
  REQUIRE_THROWS_WITH(write_mesh(scratch("mesh.stl"), p, {{0, 1, 2}}), Contains("extension '.stl'"));
  REQUIRE_THROWS_WITH(write_mesh(scratch("no_such_dir/mesh.off"), p, {{0, 1, 2}}),
                      Contains("cannot be opened for writing"));
}

TEST_CASE("write_mesh refuses a vertex that is not a point, and writes nothing") {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, std::nan(""), 0}, {0, 1, 0}};
  const std::string path = scratch("nan_vertex.off");
  std::filesystem::remove(path);
  REQUIRE_THROWS_AS(write_mesh(path, p, {{0, 1, 2}}), std::invalid_argument);
  REQUIRE_THROWS_WITH(write_mesh(path, p, {{0, 1, 2}}), Contains("vertex 1"));
  REQUIRE_FALSE(std::filesystem::exists(path));
  const std::vector<Vec3> far = {{0, 0, 0}, {1, 0, 0}, {0, std::numeric_limits<double>::infinity(), 0}};
  REQUIRE_THROWS_WITH(write_mesh(path, far, {{0, 1, 2}}), Contains("vertex 2"));
}

TEST_CASE("CGAL's elk and knot load as closed manifolds of the right genus") {
  const std::string dir = LRVD_CGAL_DATA_DIR;
  const LoadedMesh elk = read_mesh(dir + "/elk.off");
  REQUIRE(elk.mesh.vertex_count() == 1645);
  REQUIRE(elk.mesh.triangle_count() == 3290);
  REQUIRE(elk.mesh.is_closed());
  REQUIRE(elk.mesh.component_count() == 1);
  REQUIRE(elk.mesh.euler_characteristic() == 0);  // the elk is a torus: body and legs close a handle
  REQUIRE_FALSE(elk.repair.changed());

  const LoadedMesh knot = read_mesh(dir + "/knot.off");
  REQUIRE(knot.mesh.vertex_count() == 2080);
  REQUIRE(knot.mesh.triangle_count() == 4160);
  REQUIRE(knot.mesh.is_closed());
  REQUIRE(knot.mesh.component_count() == 1);
  REQUIRE(knot.mesh.euler_characteristic() == 0);  // a knotted tube: genus 1
}

TEST_CASE("write_cells_ply writes polygons with a cell label and a colour per face") {
  PolygonMesh cells;
  cells.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}, {0.5, 1.5, 0}};
  cells.faces = {{0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 6}};
  cells.face_cell = {7, 8, 7};
  cells.face_color = {{{255, 0, 0}}, {{0, 255, 0}}, {{255, 0, 0}}};
  const std::string path = scratch("cells.ply");
  write_cells_ply(path, cells);

  // The header declares the cell property; the binary body holds the labels and colours.
  const std::string bytes = read_file(path);
  const std::size_t body = bytes.find("end_header\n") + 11;
  const std::string header = bytes.substr(0, body);
  REQUIRE_THAT(header, Contains("element face 3") && Contains("property int cell") && Contains("property uchar red"));
  std::size_t at = body + cells.positions.size() * 3 * sizeof(double);
  for (std::size_t f = 0; f < cells.faces.size(); ++f) {
    REQUIRE(static_cast<std::size_t>(static_cast<unsigned char>(bytes[at])) == cells.faces[f].size());
    at += 1 + 4 * cells.faces[f].size();
    int cell;
    std::memcpy(&cell, bytes.data() + at, 4);
    REQUIRE(cell == cells.face_cell[f]);
    REQUIRE(static_cast<unsigned char>(bytes[at + 4]) == cells.face_color[f][0]);
    at += 4 + 3;
  }
  REQUIRE(at == bytes.size());

  // CGAL reads it back (ignoring the extra properties): 2 quads + 1 triangle.
  const LoadedMesh back = read_mesh(path);
  REQUIRE(back.repair.triangulated_faces == 2);
  REQUIRE(back.mesh.triangle_count() == 5);
  REQUIRE(back.mesh.positions() == cells.positions);

  cells.face_cell.pop_back();
  REQUIRE_THROWS_AS(write_cells_ply(path, cells), std::invalid_argument);
}

TEST_CASE("A polygon face that crosses itself or visits a vertex twice is refused, and fanned with --repair") {
  // A quad crossed into a bow tie covers its area twice when triangulated, and a pentagon that
  // returns to its first vertex gave a unit square an area of 1.5: both were read without a word.
  const std::string bowtie = scratch("bowtie.off"), twice = scratch("vertex_twice.off");
  write_file(bowtie, "OFF\n4 1 0\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n4 0 1 2 3\n");
  write_file(twice, "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n5 0 1 2 0 3\n");
  REQUIRE_THROWS_WITH(read_mesh(bowtie), Contains("bowtie.off: face 0 (4 vertices) is self-intersecting or degenerate") &&
                                             Contains("--repair"));
  REQUIRE_THROWS_WITH(read_mesh(twice), Contains("vertex_twice.off: face 0 (5 vertices) visits vertex 0 twice"));
  ReadOptions repair;
  repair.repair = true;
  const LoadedMesh fanned = read_mesh(bowtie, repair);
  CHECK(fanned.mesh.triangle_count() >= 2);
  bool noted = false;
  for (const std::string& note : fanned.repair.notes) noted = noted || note.find("it was fanned") != std::string::npos;
  CHECK(noted);
  // A simple quad, convex or not, is still read: two triangles of its area.
  write_file(scratch("dart.off"), "OFF\n4 1 0\n0 0 0\n2 0 0\n1 0.5 0\n1 2 0\n4 0 1 2 3\n");
  const LoadedMesh dart = read_mesh(scratch("dart.off"));
  CHECK(dart.mesh.triangle_count() == 2);
  CHECK(dart.mesh.area() == Approx(1.25));  // the shoelace area of the dart
}

TEST_CASE("A --weld that joins every corner leaves no faces and names the weld not the file") {
  // A tetrahedron 1 across welded at 10: every corner goes to the first, every face collapses.
  std::string tetra = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  write_file(scratch("weld_all.off"), tetra);
  ReadOptions options;
  options.repair = true;
  options.weld = 10;
  REQUIRE_THROWS_WITH(read_mesh(scratch("weld_all.off"), options),
                      Contains("weld_all.off: has no faces left after --weld 10 joined their corners: --weld 10 "
                               "collapsed 12 face sides of the file"));
  // A weld that joins only corners of separate faces collapses no face side, but can still flatten
  // every face: (0 0.0007 0) and (2 0.0007 0) go to (0 0 0) and (2 0 0), (1 0.001 0) to (1 0 0).
  write_file(scratch("weld_flat.off"), "OFF\n6 2 0\n1 0 0\n0 0 0\n2 0 0\n1 0.001 0\n0 0.0007 0\n2 0.0007 0\n"
                                       "3 1 2 3\n3 0 4 5\n");
  options.weld = 1e-3;
  REQUIRE_THROWS_WITH(read_mesh(scratch("weld_flat.off"), options),
                      Contains("weld_flat.off: has no faces left after --weld 0.001 joined their corners: use a "
                               "smaller value"));
  // Without --weld, faces all degenerate in the file: --repair says it removed them.
  write_file(scratch("flat_only.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n");
  REQUIRE_THROWS_WITH(read_mesh(scratch("flat_only.off"), {true}),
                      Contains("flat_only.off: has no faces left after --repair removed the degenerate ones"));
  // The same file with a --weld that joins no corner: the file's faces, not the weld, are named.
  options.weld = 1e-6;
  REQUIRE_THROWS_WITH(read_mesh(scratch("flat_only.off"), options),
                      Contains("flat_only.off: has no faces left after --repair removed the degenerate ones") &&
                          !Contains("--weld"));
}

TEST_CASE("Filling holes of a closed mesh fills nothing and notes that it is closed") {
  std::string tetra = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  write_file(scratch("closed_fill.off"), tetra);
  const LoadedMesh loaded = read_mesh(scratch("closed_fill.off"), ReadOptions{false, 0.5});
  REQUIRE(loaded.mesh.triangle_count() == 4);
  REQUIRE(loaded.repair.filled_holes == 0);
  REQUIRE(loaded.repair.notes == std::vector<std::string>{"no hole to fill: the mesh is closed"});
}

TEST_CASE("Filling holes of an open mesh too large to measure is refused naming the file") {
  // A square sheet 2e30 across with a hole: read as it is, refused by the hole filling.
  std::string off = "OFF\n16 16 0\n";
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) off += fmt::format("{} {} 0\n", i * 1e30 / 1.5, j * 1e30 / 1.5);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      if (i == 1 && j == 1) continue;
      const int a = j * 4 + i, b = a + 1, c = a + 4, d = c + 1;
      off += fmt::format("3 {} {} {}\n3 {} {} {}\n", a, b, d, a, d, c);
    }
  write_file(scratch("huge_sheet.off"), off);
  REQUIRE(read_mesh(scratch("huge_sheet.off")).mesh.boundary_loops().size() == 2);
  REQUIRE_THROWS_WITH(read_mesh(scratch("huge_sheet.off"), ReadOptions{false, 0.5}),
                      Contains("huge_sheet.off: ") && Contains("hole filling works with sizes from 1e-30 to 1e+30"));
}

TEST_CASE("fill_small_holes leaves open a hole every triangulation of which repeats an edge") {
  // The 7-vertex torus (faces i i+1 i+3 and i i+3 i+2 mod 7), every pair of vertices an edge,
  // without the six triangles round vertex 0, which becomes a vertex inside triangle 1 2 4 instead.
  // The hexagon 1..6 left open has all its chords as edges already: no triangulation is valid.
  std::vector<Vec3> p(7);
  for (int k = 1; k <= 6; ++k) p[k] = {double(k), double(k * k), double(k * k * k)};
  p[0] = (p[1] + p[2] + p[4]) / 3.0;
  const std::vector<Triangle> t = {{1, 2, 0}, {2, 4, 0}, {4, 1, 0}, {2, 3, 5}, {3, 4, 6},
                                   {5, 6, 1}, {1, 4, 3}, {2, 5, 4}, {3, 6, 5}, {6, 2, 1}};
  const SurfaceMesh holed(p, t);
  REQUIRE(holed.boundary_loops().size() == 1);
  REQUIRE(holed.boundary_loops()[0].size() == 6);
  RepairReport report;
  const SurfaceMesh same = fill_small_holes(holed, 1e6, &report);
  REQUIRE(same.triangle_count() == holed.triangle_count());
  REQUIRE(report.filled_holes == 0);
  REQUIRE(report.notes == std::vector<std::string>{"left 1 hole open: CGAL found no valid triangulation of it"});
}

TEST_CASE("fill_small_holes leaves open two holes whose patches cut each other but not the surface") {
  // Two open square pyramids sharing the points (-1, 0, 0) and (1, 0, 0) of their rims: one's rim in
  // z = 0 (apex below), the other's in y = 0 (apex at +y). Each rim is a rhombus whose short
  // diagonal crosses the long one at the origin: both patches hold the segment between the shared
  // points, and each meets the other pyramid at those points only.
  const std::vector<Vec3> p = {{-1, 0, 0}, {0, 0.5, 0}, {1, 0, 0}, {0, -0.5, 0}, {0, 0, -2},
                               {-1, 0, 0}, {0, 0, 0.5}, {1, 0, 0}, {0, 0, -0.5}, {0, 2, 0}};
  const std::vector<Triangle> t = {{1, 0, 4}, {2, 1, 4}, {3, 2, 4}, {0, 3, 4},
                                   {6, 5, 9}, {7, 6, 9}, {8, 7, 9}, {5, 8, 9}};
  const SurfaceMesh pyramids(p, t);
  REQUIRE(pyramids.boundary_loops().size() == 2);
  // Each alone is filled.
  for (int k = 0; k < 2; ++k) {
    const std::vector<Vec3> one(p.begin() + 5 * k, p.begin() + 5 * k + 5);
    std::vector<Triangle> sides(t.begin() + 4 * k, t.begin() + 4 * k + 4);
    for (Triangle& s : sides)
      for (int& v : s) v -= 5 * k;
    REQUIRE(fill_small_holes(SurfaceMesh(one, sides), 100).is_closed());
  }
  RepairReport report;
  const SurfaceMesh same = fill_small_holes(pyramids, 100, &report);
  REQUIRE(same.triangle_count() == 8);
  REQUIRE(report.filled_holes == 0);
  REQUIRE(report.notes == std::vector<std::string>{"left 2 holes open: filling them would cut through the surface or "
                                                   "make a degenerate triangle"});
}

TEST_CASE("The repair keeps one copy of a face that splitting a T-junction makes again") {
  // Beside the octahedron, triangle 7 8 10 with corner 9 of triangle 7 9 10 at the middle of its
  // edge 7 8: splitting that T-junction makes 7 9 10 a second time. The repair once refused its own
  // result then ("is still invalid after --repair: triangles ... are duplicates"); one copy stays.
  std::string off = "OFF\n11 12 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n0.999 0 0.001\n";
  off += "10 0 0\n12 0 0\n11 0 0\n11 1 0\n";
  off += "3 0 2 6\n3 6 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 6\n3 3 6 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";
  off += "3 7 8 10\n3 7 9 10\n";
  const std::string path = scratch("split_duplicate.off");
  write_file(path, off);
  const LoadedMesh loaded = read_mesh(path, {true});
  CHECK(loaded.repair.split_edges == 1);
  CHECK(loaded.repair.removed_duplicate_faces == 1);
  const SurfaceMesh& mesh = loaded.mesh;
  REQUIRE(mesh.triangle_count() == 12);  // the octahedron's 10 and the halves 7 9 10, 9 8 10
  auto count = [&](std::set<std::array<double, 3>> corners) {
    int n = 0;
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      std::set<std::array<double, 3>> at;
      for (int v : mesh.triangle(t)) at.insert({mesh.position(v).x, mesh.position(v).y, mesh.position(v).z});
      n += at == corners;
    }
    return n;
  };
  CHECK(count({{10, 0, 0}, {11, 0, 0}, {11, 1, 0}}) == 1);
  CHECK(count({{11, 0, 0}, {12, 0, 0}, {11, 1, 0}}) == 1);
  CHECK(count({{10, 0, 0}, {12, 0, 0}, {11, 1, 0}}) == 0);  // the unsplit triangle is gone
}
