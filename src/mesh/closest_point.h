// ClosestPointIndex: closest point on a triangle mesh, through an Embree BVH (point queries).
// One index serves sample location, re-projection during CVT and distance metrics.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "predicates/vec3.h"

namespace lrvd {

class SurfaceMesh;

struct ClosestPoint {
  Vec3 point;         // closest point on the mesh
  int triangle = -1;  // triangle that holds it
  Vec3 barycentric;   // its barycentric coordinates in that triangle
  double distance = 0;
};

//! Closest point on a triangle of `t = (a, b, c)` to p, with barycentric coordinates.
ClosestPoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

//! A BVH over a set of triangles. The boxes are rounded outward to float, and distances are
//! computed in double on the original coordinates, so the answer is the closest triangle of the
//! double-precision mesh, not of a float copy.
class ClosestPointIndex {
 public:
  ClosestPointIndex(const std::vector<Vec3>& positions, const std::vector<std::array<int, 3>>& triangles);
  explicit ClosestPointIndex(const SurfaceMesh& mesh);
  ~ClosestPointIndex();
  ClosestPointIndex(const ClosestPointIndex&) = delete;
  ClosestPointIndex& operator=(const ClosestPointIndex&) = delete;

  //! Closest point of the whole mesh to p (thread-safe). `hint`, if not -1, is a triangle
  //! expected near the answer (the point's triangle before it moved a little): the search starts
  //! with its distance as the radius, which prunes most of the tree. The traversal visits the
  //! same nodes in the same order, only fewer, so the answer is the same, ties between triangles
  //! at one distance included (tested at mesh vertices).
  ClosestPoint query(const Vec3& p, int hint = -1) const;
  //! The closest point among the triangles t with group[t] == g (e.g. one connected component:
  //! `group` = SurfaceMesh::triangle_components()); triangles of other groups are never the
  //! answer, even when closer. A `hint` outside the group is not used.
  ClosestPoint query_within(const Vec3& p, const int* group, int g, int hint = -1) const;

  struct Impl;  // public name so the Embree callbacks can see it; its definition stays private

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace lrvd
