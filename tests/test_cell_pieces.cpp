// every_cell_in_one_piece: the quick answer the LRVD's connectivity restoration asks first agrees
// with counting the pieces by cell_components, on diagrams with and without cells in pieces.
#include <catch2/catch.hpp>

#include <string>
#include <utility>
#include <vector>

#include "diagram/clip.h"
#include "diagram/diagram.h"
#include "io/mesh_io.h"
#include "test_meshes.h"
#include "voronoi/lrvd.h"
#include "voronoi/rvd.h"

using namespace lrvd;

namespace {

// Per triangle, the cell of its only polygon when that polygon is the whole triangle (three
// corners, along every edge), else -1: what the LRVD builder knows as whole triangles.
std::vector<int> whole_cells(const Diagram& d, const SurfaceMesh& mesh) {
  std::vector<int> whole(mesh.triangle_count(), -1);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    if (d.triangle_offsets[t + 1] - d.triangle_offsets[t] != 1) continue;
    const int p = d.triangle_offsets[t];
    const CellPolygon& poly = d.polygons[p];
    const SymbolicVertex* v = d.polygon_vertices(poly);
    bool corners = poly.vertex_count == 3 && d.polygon_along[p] == 7;
    for (int c = 0; corners && c < 3; ++c) corners = v[c].type == SymbolicVertex::Type::A;
    if (corners) whole[t] = poly.cell;
  }
  return whole;
}

}  // namespace

TEST_CASE("Whether every cell is in one piece agrees with the pieces cell_components counts", "[lrvd][verification]") {
  const SurfaceMesh elk = read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/elk.off").mesh;
  const std::vector<std::pair<std::string, SurfaceMesh>> meshes = {
      {"icosphere(3)", test::icosphere(3)},
      {"nearby sheets", test::merge(test::grid(8, 8), test::grid(8, 8), {0, 0, 0.05})},
      {"elk", elk}};
  LrvdOptions fixpoint;  // without the restoration, some cells stay in pieces
  fixpoint.restore_connectivity = false;
  int in_pieces = 0, connected = 0;
  for (const auto& [name, mesh] : meshes)
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      const Samples samples = sample_uniform(mesh, 10 + 5 * static_cast<int>(seed), seed);
      for (const Diagram& d : {compute_lrvd(mesh, samples), compute_lrvd(mesh, samples, fixpoint), compute_rvd(mesh, samples)}) {
        INFO(name << " seed " << seed << " " << to_string(d.kind));
        bool one_piece = true;
        for (int c : cell_components(d, mesh, d.polygon_along).count) one_piece = one_piece && c <= 1;
        CHECK(every_cell_in_one_piece(d, mesh, d.polygon_along) == one_piece);
        CHECK(every_cell_in_one_piece(d, mesh, d.polygon_along, whole_cells(d, mesh)) == one_piece);
        (one_piece ? connected : in_pieces) += 1;
      }
    }
  CHECK(in_pieces > 0);
  CHECK(connected > 0);
}
