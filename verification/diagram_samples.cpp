// (1) Each sample lies in its own cell's polygon in its triangle, exactly. Part of
// verify_diagram's triangle pass (diagram_triangle.cpp): the samples of a triangle are checked
// with the triangle's vertices at hand; verify_diagram lists the offenders by sample.
#include "verification/diagram_samples.h"

#include <cmath>

#include <fmt/format.h>

namespace lrvd::verify_detail {

void SampleChecks::check_samples(int t, const Triangle& tri, const Frame& f) {
  for (int s = in_.sample_first[t]; s < in_.sample_first[t + 1]; ++s) {
    const int i = in_.sample_order[s];
    std::string problem = sample_problem(i, t, tri, f);
    if (!problem.empty()) out_.sample_failures.emplace_back(i, std::move(problem));
  }
}

// x_i, at its barycentric coordinates taken as exact rationals, lies in the closed polygon of
// cell i in its triangle t. "" when it does, else the offender.
std::string SampleChecks::sample_problem(int i, int t, const Triangle& tri, const Frame& f) {
  const Vec3& b = in_.samples.barycentric[i];
  // Finite and not negative, and not all zero: their exact sum is then positive.
  const bool located = std::isfinite(b.x) && std::isfinite(b.y) && std::isfinite(b.z) && b.x >= 0 && b.y >= 0 &&
                       b.z >= 0 && (b.x > 0 || b.y > 0 || b.z > 0);
  if (!located) return fmt::format("sample {}: barycentric ({}, {}, {}) is outside its triangle {}", i, b.x, b.y, b.z, t);
  const ExactVertex point = ExactVertex::at_barycentric(tri, b, in_.context);
  bool has_polygon = false, inside = false;
  int holder = -1;
  // First the cell's own polygons where the diagram's order (by cell within a triangle) puts
  // them; when none holds the sample (or the order is broken), every polygon, as below.
  if (f.valid) {
    int from = begin_, to = end_;  // the first polygon of a cell >= i
    while (from < to) {
      const int mid = from + (to - from) / 2;
      if (d_.polygons[mid].cell < i) from = mid + 1; else to = mid;
    }
    for (int p = from; p < end_ && d_.polygons[p].cell == i && !inside; ++p)
      inside = usable(p) && contains_point(p, point, f);
  }
  for (int p = begin_; p < end_ && !inside; ++p) {
    if (!usable(p) || !f.valid) continue;
    const bool own = d_.polygons[p].cell == i;
    has_polygon = has_polygon || own;
    const bool contains = contains_point(p, point, f);
    if (contains && own) inside = true;
    if (contains && !own && holder < 0) holder = d_.polygons[p].cell;
  }
  out_.part.rational_points += point.has_rationals();
  if (inside) return {};
  if (!has_polygon) return fmt::format("sample {}: cell {} has no polygon in the sample's triangle {}", i, i, t);
  return fmt::format("sample {}: outside its cell's polygon in triangle {}{}", i, t,
                     holder >= 0 ? fmt::format(" (it lies in cell {}'s)", holder) : "");
}

// Exact point-in-closed-convex-polygon in the frame. A polygon of zero area (a degenerate
// input's limit) contains the points of its segment.
bool SampleChecks::contains_point(int p, const ExactVertex& x, const Frame& f) {
  const CellPolygon& poly = d_.polygons[p];
  points_.clear();
  for (int k = 0; k < poly.vertex_count; ++k) points_.push_back(&vertex(p, k));
  if (points_.size() < 3) return false;
  const bool flat = area(p) != Sign::Positive;  // known from the polygon checks
  for (size_t k = 0; k < points_.size(); ++k) {
    const Sign s = orient(*points_[k], *points_[(k + 1) % points_.size()], x, f);
    if (s == Sign::Negative || (flat && s != Sign::Zero)) return false;
  }
  if (!flat) return true;
  for (int axis : {f.u, f.v}) {
    bool below = false, above = false;  // some vertex <= x, some >= x along the axis
    for (const ExactVertex* v : points_) {
      below = below || coordinate(v->p(), axis) <= coordinate(x.p(), axis);
      above = above || coordinate(v->p(), axis) >= coordinate(x.p(), axis);
    }
    if (!below || !above) return false;
  }
  return true;
}

}  // namespace lrvd::verify_detail
