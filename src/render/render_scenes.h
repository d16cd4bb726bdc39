// The scenes `lrvd render` draws: a mesh, a diagram's cells with their stray pieces hatched, and a
// mesh coloured by triangle quality or by the remesh checks its triangles fail.
#pragma once

#include <array>
#include <vector>

#include "predicates/vec3.h"
#include "render/render.h"

namespace lrvd {

class SurfaceMesh;
struct Diagram;
struct Samples;

//! A mesh in light grey; with `options.edges` its edges show.
RenderScene mesh_scene(const SurfaceMesh& mesh);
//! The same for any triangles (a soup, a non-manifold remesh).
RenderScene mesh_scene(const std::vector<Vec3>& positions, const std::vector<std::array<int, 3>>& triangles);

//! The colour of a triangle of quality Q (triangle_quality: 1 equilateral, 0 degenerate): dark
//! red at 0, red at 0.3, orange at 0.5, pale yellow at 0.7, light grey from 0.9 on.
Rgb quality_color(double q);
//! Colours every triangle of the scene by its quality; returns the worst Q (1 for no triangle).
double color_by_quality(RenderScene& scene);

//! What color_by_defects found, in triangles (one triangle may count under several kinds).
struct MeshDefectCounts {
  int degenerate = 0;    //!< repeated or collinear corners (exact): dark red
  int non_manifold = 0;  //!< on an edge of three or more triangles, or on the corners of another: red
  int crossing = 0;      //!< cutting through another triangle (exact, find_self_intersections): orange
  int boundary = 0;      //!< on an edge of one triangle: blue (a hole, or an open input's boundary)
  int unused_vertices = 0;  //!< vertices in no triangle, drawn as dots (RenderScene::points)
};
//! Colours the triangles where a remesh check would fail, the others light grey: degenerate ones,
//! those on non-manifold edges, those crossing another, and those on the boundary, in that order
//! of precedence; the vertices no triangle uses become the scene's points (dots).
MeshDefectCounts color_by_defects(RenderScene& scene);

//! The cells of a diagram, each in a colour its neighbours do not have, with dark lines between
//! cells and the samples as dots. Pieces of a cell that are not the one holding its sample (the
//! RVD's stray pieces; an LRVD has none) are hatched in the cell's colour.
struct DiagramScene {
  RenderScene scene;
  int cells_in_pieces = 0;   //!< cells with more than one connected piece
  int stray_polygons = 0;    //!< polygons hatched
};
DiagramScene diagram_scene(const Diagram& diagram, const SurfaceMesh& mesh, const Samples& samples);

}  // namespace lrvd
