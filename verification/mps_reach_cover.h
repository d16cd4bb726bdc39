// Maximality under the paper's conflict rule read from a spot's side (internal to verification/):
// a spot x of triangle t is covered when a sample s lies within r_s of it and the region of the
// ball B(x, r_s) — grown from t over every edge-adjacent triangle it meets — reaches s's triangle
// (a dart at x would be refused). Decided on polygons with a certificate: every corner of the
// polygon's pieces in balls of samples whose chains hold at every corner (docs/algorithms/mps.md).
#pragma once

#include <unordered_map>
#include <vector>

#include "mesh/surface_mesh.h"
#include "predicates/exact.h"
#include "samples/samples.h"

namespace lrvd::verify_detail {

class ReachCover {
 public:
  //! sample_triangles[i]: the triangles sample i lies on (one, or all of those at its edge or corner).
  ReachCover(const SurfaceMesh& mesh, const Samples& samples, const std::vector<std::vector<int>>& sample_triangles);

  //! Whether every point of the convex polygon P (exact corners, in triangle t) lies in the ball
  //! of sample k, or in the ball of a sample s whose chain holds on P: a chain of edge-adjacent
  //! triangles from t to one of s's whose every triangle is met by the ball B(c, r_s) about every
  //! corner c of P (so about every point of P: the distance to a triangle is convex). Decided
  //! exactly on the power diagram of k and those samples restricted to P, and where that does not
  //! suffice, on the halves of P, and theirs, up to `depth` halvings deep and `budget` polygons
  //! in all. Only the halves that are not decided are halved again, so the polygons gather where
  //! two coverings barely overlap (by 10^-7 r on a thin box's rim); false is "not shown covered".
  bool covers(int t, const std::vector<ExactPoint>& polygon, int k, int depth, int budget);

 private:
  bool covers_part(int t, const std::vector<ExactPoint>& polygon, int k, int depth, int& budget);
  bool chain(int t, const std::vector<ExactPoint>& polygon, const std::vector<Vec3>& approx, int s);
  bool covered_by(const std::vector<ExactPoint>& polygon, const std::vector<int>& sites) const;

  const SurfaceMesh& mesh_;
  const Samples& samples_;
  const std::vector<std::vector<int>>& sample_triangles_;
  double cell_ = 0;  // of the grid of centres: the largest radius
  std::unordered_map<long long, std::vector<int>> grid_;
};

}  // namespace lrvd::verify_detail
