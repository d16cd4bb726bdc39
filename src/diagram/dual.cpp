// Dual triangulation of a diagram with orientation read from the polygons' counterclockwise order.
#include "diagram/dual.h"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "common/error.h"

namespace lrvd {

DualMesh compute_dual(const Diagram& diagram, const SurfaceMesh& mesh, const Samples& samples) {
  if (const std::string error = diagram_layout_error(diagram, mesh); !error.empty())
    throw InputError("compute_dual: the diagram does not fit the mesh: " + error);
  if (samples.size() != diagram.sample_count)
    throw InputError(fmt::format("compute_dual: the diagram has {} cells but {} samples are given", diagram.sample_count,
                                 samples.size()));
  DualMesh dual;
  dual.positions = samples.positions;
  std::map<Triangle, int> seen;  // rotated so the smallest index comes first -> triangle index
  for (const CellPolygon& poly : diagram.polygons) {
    const SymbolicVertex* verts = diagram.polygon_vertices(poly);
    const int a = poly.cell;
    for (int k = 0; k < poly.vertex_count; ++k) {
      const SymbolicVertex& q = verts[k];
      // Each type (c) vertex is met by the polygons of its three cells: emit it from the smallest.
      if (q.type != SymbolicVertex::Type::C || q.label[0] != a) continue;
      // Around q, counterclockwise: cell a, then the cell across a's incoming edge (prev -> q).
      const SymbolicVertex& prev = verts[(k + poly.vertex_count - 1) % poly.vertex_count];
      int x = -1;
      for (int l : q.label)
        if (l != a && prev.has_label(l)) x = l;
      if (x < 0) continue;  // cannot happen in a valid diagram; the remesh check reports the gap
      const int y = q.label[0] + q.label[1] + q.label[2] - a - x;
      const Triangle tri = {a, x, y};
      const auto [it, fresh] = seen.emplace(tri, static_cast<int>(dual.triangles.size()));
      if (!fresh) {
        ++dual.merged_duplicates;
        dual.merged_into.push_back(it->second);
        continue;
      }
      dual.triangles.push_back(tri);
    }
  }
  return dual;
}

}  // namespace lrvd
