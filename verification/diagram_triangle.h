// verify_diagram's pass over the triangles: each triangle's vertices, then its checks in order, the
// polygon sides along its edges listed for the edge pass, and its share of the distinct vertices.
#pragma once

#include <array>
#include <vector>

#include "verification/diagram_samples.h"

namespace lrvd::verify_detail {

//! The checks of one triangle at a time, on its own copy of its distinct vertices: (4) and (5),
//! (3) for every polygon vertex, (1) for the samples located on it; lists the polygon sides along
//! its edges for the edge pass.
class TriangleChecker : private SampleChecks {
 public:
  TriangleChecker(DiagramInput& in, TriangleChunk& out) : SampleChecks(in, out) {}
  void check_triangles(int begin, int end);

 private:
  void check_triangle(int t);
  int whole_rotation(const Triangle& tri) const;
  bool check_whole(const Frame& f);
  void list_whole_sides(const Triangle& tri, int r);
  void check_polygons(int t, const Triangle& tri, const Frame& f);
  void check_structure(int t, const Frame& f);
  void report_unusable(int t, int p);
  void list_sides(const Triangle& tri);
  void count_vertices();

  std::vector<std::array<int, 5>> along_;  // list_sides: the polygon sides along the triangle's edges
};

}  // namespace lrvd::verify_detail
