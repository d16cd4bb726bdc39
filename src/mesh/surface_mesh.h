// SurfaceMesh: an indexed, validated, manifold triangle mesh with the adjacency the diagrams walk
// (triangle-triangle across each edge, vertex-to-triangle lists, boundary loops, components).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/error.h"
#include "predicates/vec3.h"

namespace lrvd {

using Triangle = std::array<int, 3>;

//! The order of a refined mesh's triangles and vertices (mesh/refine.h).
enum class RefineOrder;

struct BoundingBox {
  Vec3 min, max;
  double diagonal() const;
  //! The largest absolute coordinate of the box.
  double reach() const;
  //! The unit in the last place of reach(): how finely doubles step anywhere in the box. Every
  //! coordinate in it is a multiple of this power of two.
  double coordinate_step() const;
};
//! The bounding box of a point set (not empty).
BoundingBox bounding_box(const std::vector<Vec3>& points);

//! An oriented 2-manifold triangle mesh, with or without boundary.
//! Edge e of triangle t joins corners e and (e+1)%3; neighbor(t, e) is the triangle across it.
//! \pre (checked by the constructor) finite coordinates, indices in range, no zero-area or
//!      duplicate triangles, every edge in at most two triangles with opposite directions,
//!      every vertex's triangles form one fan, no unreferenced vertices.
//! \throw InputError naming the first offending element when a precondition fails.
class SurfaceMesh {
 public:
  SurfaceMesh() = default;
  SurfaceMesh(std::vector<Vec3> positions, std::vector<Triangle> triangles);

  int vertex_count() const { return static_cast<int>(positions_.size()); }
  int triangle_count() const { return static_cast<int>(triangles_.size()); }
  const std::vector<Vec3>& positions() const { return positions_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  const Vec3& position(int v) const { return positions_[v]; }
  const Triangle& triangle(int t) const { return triangles_[t]; }

  //! Triangle across edge e of t, or -1 on the boundary.
  int neighbor(int t, int e) const { return neighbors_[t][e]; }
  //! Which edge of triangle `across` is the edge e of t (valid only when neighbor(t,e) >= 0).
  int neighbor_edge(int t, int e) const;
  //! The triangles a point of triangle t with barycentric coordinates `bary` lies on, appended to
  //! `out`: t, and where one coordinate is exactly 0 the triangle across that edge, where two are
  //! every other triangle around the vertex.
  void triangles_at(int t, const Vec3& bary, std::vector<int>& out) const;
  //! Triangles incident to vertex v.
  const int* vertex_triangles_begin(int v) const { return vt_triangles_.data() + vt_offsets_[v]; }
  const int* vertex_triangles_end(int v) const { return vt_triangles_.data() + vt_offsets_[v + 1]; }
  int vertex_triangle_count(int v) const { return vt_offsets_[v + 1] - vt_offsets_[v]; }
  //! Vertices joined to v by an edge, in increasing order.
  const int* vertex_neighbors_begin(int v) const { return vv_vertices_.data() + vv_offsets_[v]; }
  const int* vertex_neighbors_end(int v) const { return vv_vertices_.data() + vv_offsets_[v + 1]; }
  std::vector<int> vertex_neighbors(int v) const { return {vertex_neighbors_begin(v), vertex_neighbors_end(v)}; }

  //! Connected component of each triangle (0-based, by first triangle index) and their count.
  const std::vector<int>& triangle_components() const { return component_of_triangle_; }
  int component_count() const { return component_count_; }
  //! Component of a vertex (of any of its triangles).
  int vertex_component(int v) const { return component_of_triangle_[vt_triangles_[vt_offsets_[v]]]; }

  //! Boundary loops, each a closed list of vertices in the direction of their triangles' edges.
  const std::vector<std::vector<int>>& boundary_loops() const { return boundary_loops_; }
  bool is_closed() const { return boundary_loops_.empty(); }

  int edge_count() const { return edge_count_; }
  //! Euler characteristic V - E + F of the whole mesh / of each component.
  int euler_characteristic() const;
  std::vector<int> component_euler_characteristics() const;
  //! The fewest vertices a triangle mesh of the same topology can have, summed over the
  //! components: a closed component of Euler characteristic χ needs H(χ) = ⌈(7 + √(49 − 24χ))/2⌉
  //! (Heawood: 4 for a sphere, 7 for a torus); one with b boundary loops needs 3 on each loop (a
  //! vertex is on one loop at most) and H(χ + b) − b (a cone over each loop closes it), whichever is
  //! more: 3 for a disk, 6 for an annulus. A lower bound: genus 2 needs 10, not 9.
  int minimum_vertex_count() const;
  std::vector<int> minimum_vertex_counts() const;  //!< the same per component

  double triangle_area(int t) const;
  double area() const;
  Vec3 triangle_normal(int t) const;  // unit normal
  BoundingBox bounding_box() const;
  double max_edge_length() const;
  //! The length of boundary loop `loop` (an index into boundary_loops()): the sum of its edges.
  double boundary_loop_length(int loop) const;

 private:
  friend SurfaceMesh refine_long_edges(const SurfaceMesh&, double, std::vector<double>*, RefineOrder, double);
  friend SurfaceMesh refine_to_length_field(const SurfaceMesh&, std::vector<double>&, RefineOrder);
  friend SurfaceMesh spatially_ordered(const SurfaceMesh&, std::vector<int>*);
  //! The refinement of a valid mesh, whose adjacency the refinement knows: only the zero-area
  //! check is repeated (midpoints are rounded); the rest holds by construction. `components`:
  //! each triangle's component, numbered as finish_topology() would (by first triangle).
  SurfaceMesh(std::vector<Vec3> positions, std::vector<Triangle> triangles, std::vector<std::array<int, 3>> neighbors,
              int edge_count, std::vector<int> components, int component_count);

  void build_topology();            // all of the below, in order
  void build_vertex_triangles();    // vertex-to-triangle lists
  void link_and_check();            // duplicates, edges and neighbours, one fan per vertex
  void finish_topology();           // vertex-to-vertex lists, components, boundary loops
  void build_vertex_neighbors();    // vertex-to-vertex lists
  void build_components();          // components over triangle adjacency
  void build_boundary_loops();
  void check_triangle_areas() const;

  std::vector<Vec3> positions_;
  std::vector<Triangle> triangles_;
  std::vector<std::array<int, 3>> neighbors_;
  std::vector<int> vt_offsets_, vt_triangles_;
  std::vector<int> vv_offsets_, vv_vertices_;
  std::vector<int> component_of_triangle_;
  int component_count_ = 0;
  int edge_count_ = 0;
  std::vector<std::vector<int>> boundary_loops_;
};

//! Sizes (bounding-box diagonals) the remesher, the sampler and the quality metrics work with:
//! their areas, energies and squared distances are doubles, and stay far from overflow and
//! underflow over this range (remesh and MPS measured valid from 1e-28 to 1e42 on the elk).
constexpr double kSmallestModel = 1e-30, kLargestModel = 1e30;
//! \throw InputError, saying to scale the model, when its diagonal is outside
//! [kSmallestModel, kLargestModel]; `task` names what needs it ("remeshing").
void require_workable_size(const SurfaceMesh& mesh, const char* task);
//! The same for any point set (the vertices a remesh's triangles use), named `what` in the message
//! ("the remesh").
void require_workable_size(const std::vector<Vec3>& positions, const char* what, const char* task);

//! How far, in bounding-box diagonals of one surface, the vertices of another may lie from that
//! box for distances between the two (the Hausdorff distance of quality_metrics). The closest-point
//! index prunes with float boxes: from a point 2^24 diagonals away they all look equally far, and
//! each query visits every triangle (the elk against itself with one vertex drawn to 1e8, 3.7e5
//! diagonals: 0.4 s; to 1e10: over 16 s; to 1e24: 77 s).
constexpr double kFarthestMeasured = 1 << 20;
//! \throw InputError naming the first vertex of `triangles` (of `what`) farther than
//! kFarthestMeasured diagonals of `box` (the bounding box of `other`) from it; `task` names the work.
void require_within_reach(const BoundingBox& box, const std::vector<Vec3>& positions,
                          const std::vector<Triangle>& triangles, const char* what, const char* other,
                          const char* task);

//! The fewest steps of the doubles across a model (its bounding-box diagonal over the unit in the
//! last place of its largest coordinate) that sampling, the CVT and the metrics work with. Their
//! points are constructed in doubles: a unit cube at 1e15, where doubles step by 0.125, remeshed to
//! a "valid" mesh 25 % of its size away from it. At a million steps the constructions' rounding is
//! a millionth of the model; a model 1e-6 across at 1000 has 1e7 and remeshes as at the origin.
constexpr double kFewestCoordinateSteps = 1 << 20;
//! require_workable_size, and, for the work that constructs points on the model (sampling, the
//! CVT, the MPS, the metrics): \throw InputError, saying to move the model nearer the origin, when
//! the doubles step too coarsely across it (kFewestCoordinateSteps). A diagram of given points
//! needs only the first: its decisions are exact at any coordinates.
void require_workable_model(const SurfaceMesh& mesh, const char* task);

}  // namespace lrvd
