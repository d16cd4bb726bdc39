// Diagram to polygon mesh for the cells PLY.
#include "voronoi/cells_output.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "mesh/surface_mesh.h"

namespace lrvd {

std::array<unsigned char, 3> palette_color(int index) {
  // Hues spread by the golden angle, alternating saturation/value bands.
  const double h = std::fmod(index * 0.618033988749895, 1.0) * 6.0;
  const double s = (index / 7) % 2 ? 0.45 : 0.7, v = (index / 3) % 2 ? 0.8 : 0.95;
  const int sector = static_cast<int>(h);
  const double f = h - sector, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r = v, g = t, b = p;
  switch (sector % 6) {
    case 1: r = q, g = v, b = p; break;
    case 2: r = p, g = v, b = t; break;
    case 3: r = p, g = q, b = v; break;
    case 4: r = t, g = p, b = v; break;
    case 5: r = v, g = p, b = q; break;
    default: break;
  }
  auto byte = [](double x) { return static_cast<unsigned char>(std::lround(255 * x)); };
  return {byte(r), byte(g), byte(b)};
}

std::vector<int> color_cells(const Diagram& diagram) {
  const int n = diagram.sample_count;
  std::vector<std::vector<int>> adjacent(n);
  for (const SymbolicVertex& q : diagram.vertices)
    for (int a = 0; a < q.num_labels(); ++a)
      for (int b = 0; b < q.num_labels(); ++b)
        if (a != b) adjacent[q.label[a]].push_back(q.label[b]);
  std::vector<int> color(n, -1);
  std::vector<char> used;
  for (int i = 0; i < n; ++i) {
    std::sort(adjacent[i].begin(), adjacent[i].end());
    adjacent[i].erase(std::unique(adjacent[i].begin(), adjacent[i].end()), adjacent[i].end());
    used.assign(adjacent[i].size() + 1, 0);
    for (int j : adjacent[i])
      if (color[j] >= 0 && color[j] < static_cast<int>(used.size())) used[color[j]] = 1;
    color[i] = static_cast<int>(std::find(used.begin(), used.end(), 0) - used.begin());
  }
  return color;
}

PolygonMesh diagram_polygon_mesh(const Diagram& diagram, const SurfaceMesh& mesh) {
  PolygonMesh out;
  const SymbolicContext ctx = diagram.context(mesh);
  std::unordered_map<SymbolicVertex, int, SymbolicVertexHash> index;
  const std::vector<int> colors = color_cells(diagram);
  for (const CellPolygon& poly : diagram.polygons) {
    std::vector<int> face;
    const SymbolicVertex* verts = diagram.polygon_vertices(poly);
    for (int a = 0; a < poly.vertex_count; ++a) {
      auto [it, fresh] = index.try_emplace(verts[a], static_cast<int>(out.positions.size()));
      if (fresh) out.positions.push_back(position(verts[a], ctx));
      face.push_back(it->second);
    }
    out.faces.push_back(std::move(face));
    out.face_cell.push_back(poly.cell);
    out.face_color.push_back(palette_color(colors[poly.cell]));
  }
  return out;
}

}  // namespace lrvd
