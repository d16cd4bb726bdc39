// Sutherland-Hodgman clipping on symbolic vertices. The symbolic perturbation guarantees no vertex
// lies on a clipping bisector, so each vertex is strictly kept or strictly dropped.
#include "voronoi/clip.h"

#include <stdexcept>

#include "mesh/surface_mesh.h"

namespace lrvd {

void clip_by_bisector(const std::array<int, 3>& triangle, int k, int l, const SymbolicContext& ctx,
                      std::vector<SymbolicVertex>& polygon, std::vector<SymbolicVertex>& scratch) {
  const size_t n = polygon.size();
  if (n == 0) return;
  scratch.clear();
  const Sign first = side(polygon[0], k, l, ctx);
  if (first == Sign::Zero) throw std::logic_error("clip: a polygon vertex already lies on the clipping bisector");
  Sign su = first;
  for (size_t a = 0; a < n; ++a) {
    const SymbolicVertex& u = polygon[a];
    const SymbolicVertex& w = polygon[(a + 1) % n];
    const Sign sw = a + 1 == n ? first : side(w, k, l, ctx);
    if (sw == Sign::Zero) throw std::logic_error("clip: a polygon vertex already lies on the clipping bisector");
    if (su == Sign::Positive) scratch.push_back(u);
    if (su != sw) scratch.push_back(intersect(u, w, k, l, triangle));
    su = sw;
  }
  polygon.swap(scratch);
}

void clip_triangle(const SurfaceMesh& mesh, int t, int k, const int* others, int other_count,
                   const SymbolicContext& ctx, std::vector<SymbolicVertex>& polygon,
                   std::vector<SymbolicVertex>& scratch) {
  const Triangle& tri = mesh.triangle(t);
  polygon.clear();
  for (int c = 0; c < 3; ++c) polygon.push_back(SymbolicVertex::mesh_vertex(tri[c]));
  for (int a = 0; a < other_count && !polygon.empty(); ++a)
    if (others[a] != k) clip_by_bisector(tri, k, others[a], ctx, polygon, scratch);
}

}  // namespace lrvd
