// The vertices of one triangle at a time, for verify_diagram's triangle pass: each distinct symbolic
// vertex of its polygons made once, in the triangle's own copy, with its point and what the checks ask of it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "verification/diagram_checker.h"
#include "verification/triangle_enclosures.h"

namespace lrvd::verify_detail {

//! Equal to SymbolicVertex::mesh_vertex(q.v[0]), field by field.
inline bool is_mesh_vertex(const SymbolicVertex& q) {
  return q.type == SymbolicVertex::Type::A && q.v[1] == -1 && q.v[2] == -1 && q.label[0] == -1 && q.label[1] == -1 &&
         q.label[2] == -1;
}

//! A symbolic vertex whose indices are in range and whose labels are distinct.
bool well_formed(const SymbolicVertex& q, int vertex_count, int sample_count);

//! The triangle at hand and its own copy of its distinct vertices, which the checks of the triangle
//! pass read. They are stacked on it one class a file, in the order TriangleChecker
//! (diagram_triangle.h) runs them: PolygonChecks (4, 5), EquidistanceChecks (3), SampleChecks (1).
class TriangleVertices {
 protected:
  TriangleVertices(DiagramInput& in, TriangleChunk& out) : in_(in), d_(in.d), out_(out) {}

  void load_corners(const Triangle& tri);
  void load_vertices(const Triangle& tri);
  void load_whole(const Triangle& tri, int r);
  int local_index(const SymbolicVertex& q, const Triangle& tri);
  int add_local(const SymbolicVertex& q, const Triangle& tri);
  void make_points(const Triangle& tri);
  void load_frame(const Frame& f);

  int local_of(int p, int k) const { return of_[first_[p - begin_] + k]; }
  const ExactVertex& vertex(int p, int k) const { return local_[local_of(p, k)]; }
  const FrameVertex* frame_vertices(int p) const { return frame_.data() + first_[p - begin_]; }
  bool usable(int p) const { return usable_[p - begin_]; }
  Sign& area(int p) { return area_sign_[p - begin_]; }

  DiagramInput& in_;
  const Diagram& d_;
  TriangleChunk& out_;
  int begin_ = 0, end_ = 0;  // the triangle's polygons

  // The triangle's distinct vertices (its corners first), each with what the checks ask of it once.
  struct LocalVertex {
    std::uint64_t key = 0;     // corner_key / edge_key / irregular_key, when edges != 0
    std::uint8_t edges = 0;    // the triangle's edges it lies on by definition (FrameVertex::edges)
    std::uint8_t kind = 0;     // kMeshVertex, kTypeB, kTypeC (defined by this triangle), else other
    bool defined = false;      // a point of this triangle by definition (defined_on_triangle)
    std::int8_t inside = -1;   // exactly inside the triangle: 1, 0, or -1 not yet decided
    bool ends_side = false;    // type B: ends a usable polygon's side along its edge
  };
  static constexpr std::uint8_t kMeshVertex = 1, kTypeB = 2, kTypeC = 3;
  std::vector<SymbolicVertex> local_q_;
  std::vector<ExactVertex> local_;  // the points of local_q_ (and some left from earlier triangles)
  std::vector<LocalVertex> info_;
  TriangleEnclosures enclosures_;
  std::vector<int> lookup_;  // with many distinct vertices: an open-addressing table of local ids
  std::vector<int> of_;      // per polygon vertex of the triangle: its local id, -1 if malformed
  std::vector<int> first_;   // per polygon of the triangle: where its vertices start in of_ and frame_
  std::vector<FrameVertex> frame_;
  std::vector<char> usable_;
  std::vector<Sign> area_sign_;
  std::array<FrameVertex, 3> corner_frame_;
  std::array<const ExactVertex*, 3> corner_{};

  std::vector<const ExactVertex*> points_;  // a polygon's points, for the exact tests on it
};

}  // namespace lrvd::verify_detail
