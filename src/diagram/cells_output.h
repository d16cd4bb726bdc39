// Cells of a diagram as polygons for output: vertices shared where polygons meet, a cell label and
// a colour per face (neighbouring cells get different colours).
#pragma once

#include "diagram/diagram.h"
#include "io/mesh_writers.h"

namespace lrvd {

//! One face per cell polygon, vertices deduplicated by their symbolic identity.
PolygonMesh diagram_polygon_mesh(const Diagram& diagram, const SurfaceMesh& mesh);

//! Greedy colouring of the adjacency graph of `cell_count` cells (cells sharing one of `vertices`,
//! a diagram's boundary vertices, repeated or not): adjacent cells get different colour indices.
std::vector<int> color_cells(int cell_count, const std::vector<SymbolicVertex>& vertices);

//! A distinct, well separated RGB colour for each index.
std::array<unsigned char, 3> palette_color(int index);

}  // namespace lrvd
