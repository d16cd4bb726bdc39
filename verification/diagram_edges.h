// Properties decided along mesh edges: (2) each cell is one connected region, (6) both triangles
// beside a mesh edge split it at the same points with the same cells; part of verify_diagram.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "verification/diagram_checker.h"

namespace lrvd::verify_detail {

//! The edge checks' results for one chunk of triangles, each edge from its lower triangle.
struct EdgeChunk {
  std::int64_t checked = 0;                               //!< (6): the edges compared
  std::vector<std::pair<int, std::string>> failures;      //!< (6): 3 t + e and the offender
  std::vector<std::pair<int, int>> joins;                 //!< (2): the polygons an edge joins
  std::int64_t b_vertices = 0;                            //!< the distinct type B vertices of the edges
};

//! (2) and (6) on the edges of chunk c whose other triangle is in the chunk too (and its boundary
//! edges), right after the triangle pass made the chunk's sides; then only the sides along edges
//! to other chunks are kept.
void check_inner_edges(const DiagramInput& in, std::vector<TriangleChunk>& chunks, int c, EdgeChunk& out);

//! (2) and (6) on the edges between chunks, then every chunk's results in order and (2)'s
//! components. Returns the number of distinct type B vertices (each mesh edge's, from its two sides).
std::int64_t check_edges(const DiagramInput& in, const std::vector<TriangleChunk>& chunks, std::vector<EdgeChunk>& edges,
                         DiagramVerification& out);

}  // namespace lrvd::verify_detail
