// Diagram to polygon mesh for the cells PLY.
#include "diagram/cells_output.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/error.h"
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

std::vector<int> color_cells(int cell_count, const std::vector<SymbolicVertex>& vertices) {
  const int n = cell_count;
  // Each cell's neighbours, one list after another (offsets first, then the lists).
  std::vector<int> offset(n + 1, 0);
  auto for_each_pair = [&](auto&& visit) {
    for (const SymbolicVertex& q : vertices)
      for (int a = 0; a < q.num_labels(); ++a)
        for (int b = 0; b < q.num_labels(); ++b)
          if (a != b) visit(q.label[a], q.label[b]);
  };
  for_each_pair([&](int i, int) { ++offset[i + 1]; });
  for (int i = 0; i < n; ++i) offset[i + 1] += offset[i];
  std::vector<int> adjacent(offset[n]);
  std::vector<int> fill(offset.begin(), offset.end() - 1);
  for_each_pair([&](int i, int j) { adjacent[fill[i]++] = j; });
  std::vector<int> color(n, -1);
  std::vector<char> used;
  for (int i = 0; i < n; ++i) {
    const auto begin = adjacent.begin() + offset[i], end = adjacent.begin() + offset[i + 1];
    std::sort(begin, end);
    const auto last = std::unique(begin, end);
    used.assign(static_cast<std::size_t>(last - begin) + 1, 0);
    for (auto it = begin; it != last; ++it)
      if (color[*it] >= 0 && color[*it] < static_cast<int>(used.size())) used[color[*it]] = 1;
    color[i] = static_cast<int>(std::find(used.begin(), used.end(), 0) - used.begin());
  }
  return color;
}

PolygonMesh diagram_polygon_mesh(const Diagram& diagram, const SurfaceMesh& mesh) {
  if (const std::string error = diagram_layout_error(diagram, mesh); !error.empty())
    throw InputError("diagram_polygon_mesh: the diagram does not fit the mesh: " + error);
  PolygonMesh out;
  const SymbolicContext ctx = diagram.context(mesh);
  SymbolicVertexIndex index;
  index.reserve(diagram.vertices.size() / 2);  // most vertices are in two or more polygons
  const std::size_t np = diagram.polygons.size();
  out.faces.resize(np);
  out.face_cell.resize(np);
  for (std::size_t p = 0; p < np; ++p) {
    const CellPolygon& poly = diagram.polygons[p];
    const SymbolicVertex* verts = diagram.polygon_vertices(poly);
    std::vector<int>& face = out.faces[p];
    face.resize(poly.vertex_count);
    for (int a = 0; a < poly.vertex_count; ++a) face[a] = index.insert(verts[a]);
    out.face_cell[p] = poly.cell;
  }
  const std::vector<int> colors = color_cells(diagram.sample_count, index.vertices());
  std::vector<std::array<unsigned char, 3>> palette;  // colours are small numbers: each made once
  for (int c : colors)
    while (static_cast<int>(palette.size()) <= c) palette.push_back(palette_color(static_cast<int>(palette.size())));
  out.face_color.resize(np);
  for (std::size_t p = 0; p < np; ++p) out.face_color[p] = palette[colors[out.face_cell[p]]];
  out.positions.resize(index.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, index.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) out.positions[k] = position(index[static_cast<int>(k)], ctx);
  });
  return out;
}

}  // namespace lrvd
