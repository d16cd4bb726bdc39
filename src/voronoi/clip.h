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

//! Clips an existing polygon of cell k in triangle t by bisector(k, l), in place.
void clip_by_bisector(const std::array<int, 3>& triangle, int k, int l, const SymbolicContext& ctx,
                      std::vector<SymbolicVertex>& polygon, std::vector<SymbolicVertex>& scratch);

}  // namespace lrvd
