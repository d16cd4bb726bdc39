// (4) the polygons of a triangle are convex, counterclockwise, inside it and pairwise
// interior-disjoint, and (5) they cover it: checks of verify_diagram's triangle pass.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "verification/diagram_vertices.h"

namespace lrvd::verify_detail {

//! Above this many polygons (or cells) in a triangle, (3) and (4) compare only the pairs a
//! certified bound does not tell apart.
constexpr std::size_t kAllPairsUpTo = 16;

//! Whether the interval filters alone show the polygon (its n vertices in the frame) strictly convex
//! and counterclockwise; false leaves the decision to the exact test. \pre the rounding mode is upward.
bool strictly_convex(const FrameVertex* fv, int n, const Frame& f);

//! (4) and (5) on the triangle's vertices.
class PolygonChecks : protected TriangleVertices {
 protected:
  using TriangleVertices::TriangleVertices;

  std::string polygon_problem(int p, const Triangle& tri, const Frame& f);
  bool vertex_inside(int id, const FrameVertex& x, const Frame& f);
  std::string convexity_problem(int p, const Frame& f);
  bool bounded_by_triangle(const Triangle& tri);
  bool bounded_by_triangle_multisets(const Triangle& tri);
  void check_area_sum(int t, const Frame& f);
  void check_overlaps(int t, const Frame& f);
  bool separated(int p, int q, const Frame& f) const;

 private:
  struct DirectedEdge {
    int from, to;                // local ids, from < to
    int from_vertex, to_vertex;  // indices into Diagram::vertices
    int direction;               // +1 if a polygon runs from -> to, -1 if to -> from
    std::uint8_t edges;          // the triangle's edges both ends lie on by definition
  };
  std::vector<DirectedEdge> edges_;
  std::vector<std::array<int, 3>> along_bc_;
  // bounded_by_triangle: the sides' counts per pair of vertices and their flow along each edge;
  // with many vertices, the sides off the mesh edges by direction, the starts and ends along each.
  static constexpr std::size_t kCountsUpTo = 32;
  std::array<int, kCountsUpTo * kCountsUpTo> net_{};
  std::array<int, 3 * kCountsUpTo> flow_{};
  std::vector<std::size_t> touched_;
  std::vector<std::uint64_t> forward_, backward_;
  std::array<std::vector<int>, 3> from_, to_;
  // check_overlaps: the polygons to compare; above kAllPairsUpTo of them, their boxes in the frame.
  struct FrameBox {
    int polygon;
    double u_lo, u_hi, v_lo, v_hi;
    bool apart(const FrameBox& o) const { return u_hi < o.u_lo || o.u_hi < u_lo || v_hi < o.v_lo || o.v_hi < v_lo; }
  };
  std::vector<int> candidates_;
  std::vector<FrameBox> boxes_;
  std::vector<std::pair<int, int>> pairs_;
};

}  // namespace lrvd::verify_detail
