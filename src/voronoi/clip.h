// Exact clipping of a mesh triangle by bisectors (paper §3.4): the polygon of one cell among a
// list of candidate cells, by Sutherland-Hodgman on symbolic vertices with exact side tests.
#pragma once

#include <vector>

#include "predicates/symbolic_vertex.h"

namespace lrvd {

class SurfaceMesh;

//! The part of triangle t closer to cell k than to every other cell of `others` (k itself is
//! skipped if listed). Result in `polygon` (counterclockwise, possibly empty); `scratch` is reused.
void clip_triangle(const SurfaceMesh& mesh, int t, int k, const int* others, int other_count,
                   const SymbolicContext& ctx, std::vector<SymbolicVertex>& polygon,
                   std::vector<SymbolicVertex>& scratch);

//! The edges of `triangle` (bit e: edge (corner e, corner e+1)) that vertex q lies on: two for a
//! mesh vertex at one of its corners, one for a type B vertex on one of its edges, none otherwise.
inline unsigned edge_mask(const SymbolicVertex& q, const std::array<int, 3>& triangle) {
  unsigned mask = 0;
  if (q.type == SymbolicVertex::Type::A) {
    for (int c = 0; c < 3; ++c)
      if (triangle[c] == q.v[0]) mask = (1u << c) | (1u << ((c + 2) % 3));
  } else if (q.type == SymbolicVertex::Type::B) {
    // Edge e joins corners e and e + 1: find the corners of the vertex's edge.
    int c0 = -1, c1 = -1;
    for (int c = 0; c < 3; ++c) {
      if (triangle[c] == q.v[0]) c0 = c;
      if (triangle[c] == q.v[1]) c1 = c;
    }
    if (c0 >= 0 && c1 >= 0) mask = 1u << ((c0 + 1) % 3 == c1 ? c0 : c1);
  }
  return mask;
}

//! Edges of `triangle` that a polygon reaches (`reach`: some vertex on the edge) and that it has a
//! side along (`along`: two consecutive vertices on the edge, a segment of positive length).
struct PolygonEdges {
  unsigned reach = 0, along = 0;
};
inline PolygonEdges polygon_edges(const SymbolicVertex* v, int count, const std::array<int, 3>& triangle) {
  PolygonEdges out;
  if (count == 0) return out;
  const unsigned first = edge_mask(v[0], triangle);
  unsigned previous = first;
  for (int k = 1; k <= count; ++k) {
    const unsigned current = k == count ? first : edge_mask(v[k], triangle);
    out.reach |= current;
    out.along |= previous & current;
    previous = current;
  }
  return out;
}

//! Clips an existing polygon of cell k in triangle t by bisector(k, l), in place.
void clip_by_bisector(const std::array<int, 3>& triangle, int k, int l, const SymbolicContext& ctx,
                      std::vector<SymbolicVertex>& polygon, std::vector<SymbolicVertex>& scratch);

}  // namespace lrvd
