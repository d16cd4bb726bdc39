// Refinement by splitting long edges (paper §4.2): every edge longer than a bound (one length, or a
// length field over the vertices) split at its midpoint, longest first; the Morton renumbering of a mesh.
#pragma once

#include <string>
#include <vector>

#include "common/error.h"
#include "mesh/surface_mesh.h"

namespace lrvd {

//! The most triangles a refinement may be expected to give, margin included. A diagram costs about
//! 0.6-0.75 KB a triangle to compute and 1.4 KB a triangle with its exact verification (the elk at
//! 500,000 samples, refined to 1.9M triangles: 1.4 GB without the verification, 2.7 GB with it), so
//! this keeps a verified diagram under about 9 GB; more is refused instead of exhausting memory.
constexpr double kMaxRefinedTriangles = 6e6;

//! A refinement refused because it would pass its triangle limit (refine_long_edges).
class RefinementLimitError : public InputError {
 public:
  using InputError::InputError;
};

//! The order of a refined mesh's triangles and vertices (refine_long_edges, refine_to_length_field).
//! Each input triangle's pieces are consecutive either way.
enum class RefineOrder {
  Input,    //!< in the input triangles' order; the input's vertices keep their indices
  Spatial,  //!< along a Morton curve through the input triangles' centroids; every vertex numbered
            //!< in the order the triangles first use it (passes over the mesh stay local in memory)
};

//! Splits every edge longer than max_length (both triangles beside it, 1-to-2 splits at the
//! midpoint, longest edges first) until no edge is longer (paper §4.2). The surface is unchanged.
//! \pre max_length > 0.
//! `vertex_values`, when given, holds one value per vertex of `mesh` and is extended to the new
//! vertices, each taking the mean of its edge's end points: a field linear over each input
//! triangle is carried over exactly (up to rounding), since every edge split lies in one of them.
//! \throw RefinementLimitError when the result would have more than `max_triangles` triangles
//! (checked as it splits: triangles far longer than wide split into many more pieces than the
//! area tells, see expected_refined_triangle_count).
SurfaceMesh refine_long_edges(const SurfaceMesh& mesh, double max_length, std::vector<double>* vertex_values = nullptr,
                              RefineOrder order = RefineOrder::Input, double max_triangles = kMaxRefinedTriangles);

//! The same splitting with a length per vertex: every edge longer than the smaller of its ends'
//! lengths is split. `vertex_lengths` (one per vertex of `mesh`, all positive) is carried to the
//! new vertices as refine_long_edges carries its values. A field linear over each input triangle
//! is smallest at an edge's ends, so each edge of the result is no longer than the field anywhere
//! along it. Used by the adaptive MPS with its radius field.
//! \throw InputError when a length is not positive; RefinementLimitError past kMaxRefinedTriangles
//! triangles, as refine_long_edges.
SurfaceMesh refine_to_length_field(const SurfaceMesh& mesh, std::vector<double>& vertex_lengths,
                                   RefineOrder order = RefineOrder::Input);

//! The same surface renumbered: its triangles along a Morton curve through their centroids, its
//! vertices in the order those triangles first use them, each triangle's corners in their order (so
//! a point's barycentric coordinates carry over). `new_triangle[t]`, when asked for, is the new
//! index of triangle t. Passes over the mesh then stay local in memory: an LRVD of 1000 samples on
//! dragon_100k, stored in no spatial order, takes 0.04–0.07 s instead of 0.10 s.
SurfaceMesh spatially_ordered(const SurfaceMesh& mesh, std::vector<int>* new_triangle = nullptr);

//! The edge length to refine to so that n samples do not crowd the triangles (about four
//! triangles a sample), or 0 when the mesh already has at least two triangles a sample.
double suggested_refinement_length(const SurfaceMesh& mesh, int n);

//! About how many triangles refine_long_edges(mesh, max_length) gives, without refining: to refuse
//! a refinement that would not fit in memory. The count was 0.59-1.11 times this on the stress
//! meshes and CGAL's at 1,000-200,000 samples' lengths, and up to kRefinedTriangleMargin times it
//! where every edge is just longer than max_length (an octahedron at 100 samples: 1.25).
double expected_refined_triangle_count(const SurfaceMesh& mesh, double max_length);
//! How far the count can exceed that estimate: when every edge is just longer than max_length,
//! every triangle splits into quarters of about equilateral shape and side max_length / 2, of area
//! max_length^2 / 9.24 against the estimate's max_length^2 / 6.5.
constexpr double kRefinedTriangleMargin = 9.24 / 6.5;

//! The most triangles the automatic refinement (to suggested_refinement_length) may make when
//! `expected` are expected: 8 times the margin over the estimate, at least 100,000. Triangles far
//! longer than wide split into far more pieces than their area tells (an octahedron with one
//! vertex drawn to 1e6: 2.1 million triangles for an estimate of 88).
double auto_refinement_limit(double expected);

//! Of the triangles with an edge longer than `max_length`, the one longest for its width, in words
//! with its corner opposite its shortest edge ("triangle 0 (vertices 0, 2, 5) is 1e+06 long and
//! 1.41 wide; its corner 0 is at (-1e+06, 0, 0), far from the others"); "" when none is longer.
std::string thinnest_long_triangle(const SurfaceMesh& mesh, double max_length);

}  // namespace lrvd
