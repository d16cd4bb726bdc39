// The disks of maximal Poisson-disk sampling as the triangles know them (paper §4.2, second
// change): region growing from a dart's triangle instead of a 3D grid, per-triangle lists of the
// disks that cover or reach each triangle, and the exact point-in-disk test.
#include "mps/mps_disks.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "mesh/closest_point.h"
#include "predicates/ball_triangle.h"
#include "predicates/exact.h"

namespace lrvd::mps_detail {

bool inside_disk_exact(const Vec3& p, const Vec3& c, double w) {
  return CGAL::sign(exact_power_distance(to_exact(p), Site{c, w, 0})) == CGAL::NEGATIVE;
}

double triangle_squared_distance(const SurfaceMesh& mesh, int t, const Vec3& p) {
  const Triangle& tri = mesh.triangle(t);
  const ClosestPoint c = closest_point_on_triangle(p, mesh.position(tri[0]), mesh.position(tri[1]), mesh.position(tri[2]));
  return squared_distance(p, c.point);
}

Vec3 barycentric_in_triangle(const SurfaceMesh& mesh, int t, const Vec3& p) {
  const Triangle& tri = mesh.triangle(t);
  const Vec3 a = mesh.position(tri[0]);
  const Vec3 v0 = mesh.position(tri[1]) - a, v1 = mesh.position(tri[2]) - a, v2 = p - a;
  const double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1), d20 = dot(v2, v0), d21 = dot(v2, v1);
  const double det = d00 * d11 - d01 * d01;
  double u = (d11 * d20 - d01 * d21) / det, v = (d00 * d21 - d01 * d20) / det;
  // A sliver whose Gram determinant cancels to zero or below (a needle 1e-9 wide, split): its
  // closest point's coordinates, which a degenerate triangle has too (an audit: NaN coordinates
  // gave a NaN radius, which reached the exact disk test as SIGFPE).
  if (!(det > 0) || !std::isfinite(u) || !std::isfinite(v))
    return closest_point_on_triangle(p, a, mesh.position(tri[1]), mesh.position(tri[2])).barycentric;
  u = std::clamp(u, 0.0, 1.0);
  v = std::clamp(v, 0.0, 1.0);
  if (u + v > 1) {
    const double s = u + v;
    u /= s;
    v /= s;
  }
  return {1 - u - v, u, v};
}

bool reach_chain(const SurfaceMesh& mesh, int t, const Vec3* points, int count, double w, const std::vector<int>& targets) {
  auto target = [&](int u) { return std::find(targets.begin(), targets.end(), u) != targets.end(); };
  auto met = [&](int u) {
    const Triangle& tri = mesh.triangle(u);
    for (int k = 0; k < count; ++k)
      if (!ball_meets_triangle(points[k], w, mesh.position(tri[0]), mesh.position(tri[1]), mesh.position(tri[2])))
        return false;
    return true;
  };
  if (target(t)) return true;
  std::vector<int> queue{t};
  for (size_t k = 0; k < queue.size(); ++k)
    for (int e = 0; e < 3; ++e) {
      const int n = mesh.neighbor(queue[k], e);
      if (n < 0 || std::find(queue.begin(), queue.end(), n) != queue.end() || !met(n)) continue;
      if (target(n)) return true;
      queue.push_back(n);
    }
  return false;
}

DiskIndex::DiskIndex(const SurfaceMesh& mesh, bool facing_cut)
    : mesh_(mesh),
      facing_cut_(facing_cut),
      covered_head_(mesh.triangle_count(), -1),
      partial_head_(mesh.triangle_count(), -1),
      center_head_(mesh.triangle_count(), -1),
      vertex_stamp_(mesh.vertex_count(), 0),
      vertex_inside_(mesh.vertex_count(), 0),
      triangles_info_(mesh.triangle_count()),
      normals_(mesh.triangle_count()),
      areas_(mesh.triangle_count()) {
  // A finished sampling lists each triangle in about 3-5 disks (edges split to twice the radius:
  // 4.2-5.2 on the Table 3 models at r = 0.005 and adaptive r_min = 0.004, 2.9-4.2 at r = 0.02):
  // reserved at once, as growing the list would copy it into fresh memory. Room never used is
  // never touched.
  links_.reserve(6 * static_cast<size_t>(mesh.triangle_count()));
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    const Vec3 &a = mesh.position(tri[0]), &b = mesh.position(tri[1]), &d = mesh.position(tri[2]);
    // As mesh.triangle_normal(t) and mesh.triangle_area(t) compute them, from one cross product.
    const Vec3 n = cross(b - a, d - a);
    const double length = norm(n);
    areas_[t] = 0.5 * length;
    normals_[t] = n / length;
    TriangleInfo& info = triangles_info_[t];
    const Vec3 c = triangle_center(t);
    for (int k = 0; k < 3; ++k) {
      info.normal[k] = static_cast<float>(normals_[t][k]);
      info.center[k] = static_cast<float>(c[k]);
    }
    // The radius about the float centre, rounded up: the sphere holds the triangle. A centre out of
    // float range gives an infinite radius: a sphere that rejects nothing.
    const Vec3 cf{info.center[0], info.center[1], info.center[2]};
    const double radius = std::sqrt(std::max({squared_distance(cf, a), squared_distance(cf, b), squared_distance(cf, d)}));
    info.radius = static_cast<float>(radius);
    if (info.radius < radius) info.radius = std::nextafter(info.radius, std::numeric_limits<float>::infinity());
    if (!std::isfinite(radius)) info.radius = std::numeric_limits<float>::infinity();
  }
}

Vec3 DiskIndex::triangle_center(int t) const {
  const Triangle& tri = mesh_.triangle(t);
  return (mesh_.position(tri[0]) + mesh_.position(tri[1]) + mesh_.position(tri[2])) / 3.0;
}

double DiskIndex::triangle_radius(int t) const {
  const Triangle& tri = mesh_.triangle(t);
  const Vec3 c = triangle_center(t);
  return std::sqrt(std::max({squared_distance(c, mesh_.position(tri[0])), squared_distance(c, mesh_.position(tri[1])),
                             squared_distance(c, mesh_.position(tri[2]))}));
}

inline bool DiskIndex::meets(int t, const Vec3& p, double w, double r) const {
  // Far outside the triangle's bounding sphere (with room for rounding): no closest point needed.
  const TriangleInfo& info = triangles_info_[t];
  const double reach = r + info.radius;
  if (squared_distance(p, Vec3{info.center[0], info.center[1], info.center[2]}) > reach * reach * (1 + 1e-9)) return false;
  // The ball meets t: a corner inside decides at once (most calls), else the exact test.
  const Triangle& tri = mesh_.triangle(t);
  for (int c = 0; c < 3; ++c)
    if (inside_disk(mesh_.position(tri[c]), p, w)) return true;
  return ball_meets_triangle(p, w, mesh_.position(tri[0]), mesh_.position(tri[1]), mesh_.position(tri[2]));
}

bool DiskIndex::in_some_disk(const Vec3& p, int t) const {
  if (covered_head_[t] >= 0) return true;
  for (int k = partial_head_[t]; k >= 0; k = links_[k].next) {
    const int j = links_[k].item;
    if (inside_disk(p, disk_records_[j].center, disk_records_[j].weight)) return true;
  }
  return false;
}

template <class F>
bool DiskIndex::search(const Vec3& p, const int* from, int count, double w, bool region, F&& f) {
  if (++stamp_value_ == 0) {  // wrapped: forget every old visit
    for (TriangleInfo& info : triangles_info_) info.stamp = 0;
    stamp_value_ = 1;
  }
  // Breadth-first over the triangles the ball meets, from those p lies on. With the facing cut, a
  // region (region: true) grows only through those facing like the first, and f sees only those;
  // the paper's rule (no cut) and met() take every one.
  const bool cut = facing_cut_;
  queue_.clear();
  for (int k = 0; k < count; ++k) {
    const int t = from[k];
    if (triangles_info_[t].stamp == stamp_value_) continue;
    triangles_info_[t].stamp = stamp_value_;
    queue_.push_back(t);
    if (f(t)) return true;
  }
  const Vec3 facing = normals_[from[0]];
  const double r = std::sqrt(w);
  for (size_t k = 0; k < queue_.size(); ++k) {
    const int s = queue_[k];
    for (int e = 0; e < 3; ++e) {
      const int n = mesh_.neighbor(s, e);
      if (n < 0) continue;
      TriangleInfo& info = triangles_info_[n];
      if (info.stamp == stamp_value_) continue;
      info.stamp = stamp_value_;
      const bool counted = !cut || faces(n, facing);
      if ((region && !counted) || !meets(n, p, w, r)) continue;
      queue_.push_back(n);
      if (counted && f(n)) return true;
    }
  }
  return false;
}

const std::vector<int>& DiskIndex::grow(const Vec3& p, int t, double w) { return grow(p, &t, 1, w); }

const std::vector<int>& DiskIndex::grow(const Vec3& p, const int* from, int count, double w) {
  region_.clear();
  search(p, from, count, w, true, [&](int n) {
    region_.push_back(n);
    return false;
  });
  return region_;
}

const std::vector<int>& DiskIndex::met(const Vec3& p, int t, double w) {
  search(p, &t, 1, w, false, [](int) { return false; });
  return queue_;
}

bool DiskIndex::reaches(const Vec3& p, int t, double w, int target) {
  return search(p, &t, 1, w, true, [&](int n) { return n == target; });
}

bool DiskIndex::sample_reaches(int i, double w, int target) {
  seeds_.clear();
  mesh_.triangles_at(triangles_[i], barycentric_[i], seeds_);
  for (int s : seeds_)
    if (reaches(center(i), s, w, target)) return true;
  return false;
}

double DiskIndex::reach_threshold(const Vec3& p, const std::vector<int>& from, const std::vector<int>& to, double cap) {
  // Dijkstra on the bottleneck: a triangle's key is the least, over chains from `from`, of the
  // largest squared distance on the chain; the first target taken from the heap has the answer.
  if (++stamp_value_ == 0) {
    for (TriangleInfo& info : triangles_info_) info.stamp = 0;
    stamp_value_ = 1;
  }
  threshold_key_.resize(triangles_info_.size());
  // A binary heap in a kept vector (std::priority_queue's operations, without its allocation).
  std::vector<std::pair<double, int>>& heap = threshold_heap_;
  const std::greater<std::pair<double, int>> later;
  heap.clear();
  auto offer = [&](int t, double key) {
    TriangleInfo& info = triangles_info_[t];
    if (info.stamp == stamp_value_ && threshold_key_[t] <= key) return;
    info.stamp = stamp_value_;
    threshold_key_[t] = key;
    heap.emplace_back(key, t);
    std::push_heap(heap.begin(), heap.end(), later);
  };
  for (int t : from) offer(t, 0);  // p lies on them: every region holds them
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const auto [key, t] = heap.back();
    heap.pop_back();
    if (key > threshold_key_[t]) continue;
    if (std::find(to.begin(), to.end(), t) != to.end()) return key;
    for (int e = 0; e < 3; ++e) {
      const int n = mesh_.neighbor(t, e);
      if (n < 0) continue;
      const double next = std::max(key, triangle_squared_distance(mesh_, n, p));
      if (next < cap) offer(n, next);
    }
  }
  return cap;
}

int DiskIndex::insert(const Vec3& p, int t, const Vec3& barycentric, double w, const std::vector<int>& region) {
  const int i = size();
  disk_records_.push_back({p, w});
  barycentric_.push_back(barycentric);
  triangles_.push_back(t);
  seeds_.clear();
  mesh_.triangles_at(t, barycentric, seeds_);
  for (int s : seeds_) {
    center_links_.push_back({i, center_head_[s]});
    center_head_[s] = static_cast<int>(center_links_.size()) - 1;
  }
  if (++vertex_stamp_value_ == 0) {  // wrapped: forget every old test
    std::fill(vertex_stamp_.begin(), vertex_stamp_.end(), 0);
    vertex_stamp_value_ = 1;
  }
  for (int s : region) {
    const Triangle& tri = mesh_.triangle(s);
    bool covers = true;  // the ball is convex: it holds the triangle iff it holds its corners
    for (int c = 0; c < 3 && covers; ++c) {
      const int v = tri[c];  // each corner tested once: the region's triangles share them
      if (vertex_stamp_[v] != vertex_stamp_value_) {
        vertex_stamp_[v] = vertex_stamp_value_;
        vertex_inside_[v] = inside_disk(mesh_.position(v), p, w);
      }
      covers = vertex_inside_[v];
    }
    int& head = covers ? covered_head_[s] : partial_head_[s];
    links_.push_back({i, head});
    head = static_cast<int>(links_.size()) - 1;
  }
  return i;
}

Samples DiskIndex::samples() const {
  Samples s;
  s.positions.reserve(disk_records_.size());
  s.weights.reserve(disk_records_.size());
  for (const Disk& d : disk_records_) {
    s.positions.push_back(d.center);
    s.weights.push_back(d.weight);
  }
  s.triangles = triangles_;
  s.barycentric = barycentric_;
  return s;
}

}  // namespace lrvd::mps_detail
