// The disks of maximal Poisson-disk sampling as the triangles know them (paper §4.2, second change):
// per-triangle lists of the disks that cover or reach each triangle, grown by region, and the exact point-in-disk test.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "common/huge_pages.h"
#include "mesh/surface_mesh.h"
#include "predicates/vec3.h"
#include "samples/samples.h"

namespace lrvd::mps_detail {

//! Two triangles "face alike" when the cosine of the angle between their normals exceeds this.
constexpr double kFacingCosine = 0.0;

//! inside_disk decided with rational arithmetic (its slow path).
bool inside_disk_exact(const Vec3& p, const Vec3& c, double w);

//! |p - c|² < w, decided exactly: doubles when the rounding error cannot change the answer,
//! rational arithmetic otherwise. Inline: the double test decides almost every call.
inline bool inside_disk(const Vec3& p, const Vec3& c, double w) {
  const double d = squared_distance(p, c);
  // fl(d) is within 5u·d of |p - c|² (three rounded differences, squares and sums, u = 2^-53),
  // and the subtraction below adds at most u·|d - w|: a margin of 1e-15·(d + w) decides, unless
  // d is so small that the squares may have underflowed.
  if (d >= 1e-250) {
    const double margin = 1e-15 * (d + w);
    if (d - w > margin) return false;
    if (w - d > margin) return true;
  } else if (w > 1e-240) {
    return true;  // |p - c|² is below 1e-249 however the squares rounded (a centre on a mesh vertex: 0)
  }
  return inside_disk_exact(p, c, w);
}

//! The disks of the samples and, per triangle, which of them reach it. The *local region* of a
//! ball B(x, r) around a point of triangle t: the triangles that the ball meets, edge-connected to
//! t through such triangles — the paper's region growing ("until the disk does not intersect with
//! a neighboring triangle"). With the facing cut (MpsConflict::CloseAcrossTurns) only triangles facing the
//! same way as t (normals at less than 90°) count. The disk of sample i is B(x_i, r_i) on the
//! triangles of its local region.
//! Each triangle lists the disks that cover it fully and those that reach it only partly, and the
//! sample centres it holds.
class DiskIndex {
 public:
  //! facing_cut: regions grow only through triangles facing like the centre's (MpsConflict::CloseAcrossTurns).
  explicit DiskIndex(const SurfaceMesh& mesh, bool facing_cut = false);
  //! Regions stop where the surface turns by 90° or more (MpsConflict::CloseAcrossTurns).
  bool facing_cut() const { return facing_cut_; }

  int size() const { return static_cast<int>(disk_records_.size()); }
  const Vec3& center(int i) const { return disk_records_[i].center; }
  double weight(int i) const { return disk_records_[i].weight; }
  int triangle(int i) const { return triangles_[i]; }
  const Vec3& barycentric(int i) const { return barycentric_[i]; }

  //! Some disk covers triangle t entirely (a dart there is rejected without a distance test).
  bool fully_covered(int t) const { return covered_head_[t] >= 0; }
  //! p, a point of triangle t, lies in the disk of a sample that reaches t.
  bool in_some_disk(const Vec3& p, int t) const;

  //! The local region of the ball (p, w) around a point of triangle t. Valid until the next call.
  const std::vector<int>& grow(const Vec3& p, int t, double w);
  //! Without the facing cut: the union of the local regions of (p, w) around each of the `count`
  //! triangles `from` (those p lies on), in one growth from all of them. Valid until the next call.
  const std::vector<int>& grow(const Vec3& p, const int* from, int count, double w);
  //! Every triangle the ball (p, w) meets, edge-connected to t through such triangles whichever
  //! way they face. Valid until the next call.
  const std::vector<int>& met(const Vec3& p, int t, double w);
  //! Triangles s and t face the same way (normals at less than 90°).
  bool faces_like(int s, int t) const { return faces(s, normals_[t]); }
  //! Unit normal of triangle t (mesh.triangle_normal(t)).
  const Vec3& normal(int t) const { return normals_[t]; }
  //! Bounding sphere of triangle t: its centroid and the distance from there to its farthest corner.
  Vec3 triangle_center(int t) const;
  double triangle_radius(int t) const;
  //! Area of each triangle (mesh.triangle_area(t): the normal's cross product gives both).
  const std::vector<double>& triangle_areas() const { return areas_; }
  //! Whether `target` is in the local region of (p, w) around t (leaves grow()'s result alone,
  //! not met()'s).
  bool reaches(const Vec3& p, int t, double w, int target);
  //! Whether `target` is in the local region of sample i's ball at weight w, grown from every
  //! triangle the sample lies on (SurfaceMesh::triangles_at).
  bool sample_reaches(int i, double w, int target);
  //! The weight at which the local region of the ball about p, grown from the triangles `from`
  //! (those p lies on), starts to reach one of `to`: the least, over chains of edge-adjacent
  //! triangles from `from` to `to`, of the largest squared distance from p to a triangle of the
  //! chain (the region at weight w holds the triangles closer than √w, so it reaches `to` iff w is
  //! above this). `cap` when no chain stays below cap. In doubles: a candidate for an exact test.
  double reach_threshold(const Vec3& p, const std::vector<int>& from, const std::vector<int>& to, double cap);

  //! Adds a sample whose local region is `region` (from grow(p, t, w)) and returns its index.
  int insert(const Vec3& p, int t, const Vec3& barycentric, double w, const std::vector<int>& region);

  //! f(sample) for every disk that reaches t (covering ones first).
  template <class F>
  void for_each_disk(int t, F&& f) const {
    for (int k = covered_head_[t]; k >= 0; k = links_[k].next) f(links_[k].item);
    for (int k = partial_head_[t]; k >= 0; k = links_[k].next) f(links_[k].item);
  }
  //! f(sample) for every sample whose centre lies in t: a centre exactly on an edge or a corner
  //! lies in every triangle there (SurfaceMesh::triangles_at).
  template <class F>
  void for_each_center(int t, F&& f) const {
    for (int k = center_head_[t]; k >= 0; k = center_links_[k].next) f(center_links_[k].item);
  }

  Samples samples() const;

 private:
  struct Link {
    int item, next;
  };
  //! What region growing reads of a triangle, in half a cache line (the growth is bound by memory
  //! reads): the unit normal and a bounding sphere in floats, and the last growth that visited it.
  //! The sphere is the float centroid's with its radius rounded up, so it holds the triangle and
  //! rejects only what the double one would; a facing test too close to call in floats reads the
  //! double normal (faces()).
  struct alignas(32) TriangleInfo {
    float normal[3];
    float center[3];
    float radius;
    std::uint32_t stamp = 0;
  };
  //! dot(normal of triangle s, facing) > kFacingCosine, decided as the double normals decide it.
  bool faces(int s, const Vec3& facing) const {
    const TriangleInfo& info = triangles_info_[s];
    // Each float component is within 2^-24 (relative) of the double one; for unit vectors the
    // dot product then differs by less than 1e-6 from the double one.
    const double d = info.normal[0] * facing.x + info.normal[1] * facing.y + info.normal[2] * facing.z - kFacingCosine;
    if (d > 1e-6) return true;
    if (d < -1e-6) return false;
    return dot(normals_[s], facing) > kFacingCosine;
  }
  template <class F>
  bool search(const Vec3& p, const int* from, int count, double w, bool region, F&& f);
  //! The ball (p, w), r = √w, meets triangle t (triangle_squared_distance < w), balls far from t's
  //! bounding sphere rejected at once.
  bool meets(int t, const Vec3& p, double w, double r) const;
  const SurfaceMesh& mesh_;
  bool facing_cut_;
  //! A disk's centre and weight together: the disk tests read both.
  struct Disk {
    Vec3 center;
    double weight;
  };
  std::vector<Disk> disk_records_;
  std::vector<Vec3> barycentric_;
  std::vector<int> triangles_;
  std::vector<Link> center_links_;
  std::vector<int> covered_head_, partial_head_, center_head_;  // per triangle
  HugePageVector<Link> links_;
  std::uint32_t stamp_value_ = 0;  // of the current growth (TriangleInfo::stamp)
  std::vector<std::uint32_t> vertex_stamp_;  // per vertex: last insertion that tested it
  std::vector<char> vertex_inside_;          // per vertex: inside that insertion's ball
  std::uint32_t vertex_stamp_value_ = 0;
  std::vector<int> region_, queue_, seeds_;
  std::vector<double> threshold_key_;  // per triangle, reach_threshold(): the best key found (this stamp)
  std::vector<std::pair<double, int>> threshold_heap_;  // reach_threshold(): (key, triangle), least on top
  HugePageVector<TriangleInfo> triangles_info_;  // per triangle
  HugePageVector<Vec3> normals_;                 // per triangle, unit, in doubles
  std::vector<double> areas_;                 // per triangle
};

//! Whether a chain of edge-adjacent triangles leads from t to one of `targets` through triangles
//! that the ball of weight w about every one of the `count` points meets (exactly). For points of
//! a convex polygon in t, the ball about any point of the polygon then meets them too (the
//! distance to a triangle is convex): the region of that ball reaches the target from t.
bool reach_chain(const SurfaceMesh& mesh, int t, const Vec3* points, int count, double w, const std::vector<int>& targets);

//! Squared distance from p to triangle t of the mesh.
double triangle_squared_distance(const SurfaceMesh& mesh, int t, const Vec3& p);

//! Barycentric coordinates of p (a point of the plane of triangle t) in t, clamped to the triangle.
Vec3 barycentric_in_triangle(const SurfaceMesh& mesh, int t, const Vec3& p);

}  // namespace lrvd::mps_detail
