// Cells of a diagram as polygons for output: vertices shared where polygons meet, a cell label and
// a colour per face (neighbouring cells get different colours).
#pragma once

#include "mesh/mesh_io.h"
#include "voronoi/diagram.h"

namespace lrvd {

//! One face per cell polygon, vertices deduplicated by their symbolic identity.
PolygonMesh diagram_polygon_mesh(const Diagram& diagram, const SurfaceMesh& mesh);

//! Greedy colouring of the cell adjacency graph (cells sharing a boundary vertex): adjacent cells
//! get different colour indices.
std::vector<int> color_cells(const Diagram& diagram);

//! A distinct, well separated RGB colour for each index.
std::array<unsigned char, 3> palette_color(int index);

}  // namespace lrvd
