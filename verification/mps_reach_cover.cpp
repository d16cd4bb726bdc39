// ReachCover: maximality under the paper's rule read from a spot's side, decided exactly on
// polygons (mps_reach_cover.h).
#include "verification/mps_reach_cover.h"

#include <algorithm>
#include <cmath>

#include <CGAL/Gmpq.h>

namespace lrvd::verify_detail {

namespace {

using Q = CGAL::Gmpq;

long long cell_key(long long x, long long y, long long z) {
  return ((x & 0x1fffff) << 42) | ((y & 0x1fffff) << 21) | (z & 0x1fffff);
}

// Exact power distance |p - s|² - w with the sample's double position and weight.
Q power(const ExactPoint& p, const Vec3& s, double w) {
  const Q dx = p.x - Q(s.x), dy = p.y - Q(s.y), dz = p.z - Q(s.z);
  return dx * dx + dy * dy + dz * dz - Q(w);
}

// Keeps the part of the convex polygon where f <= 0 (f affine, given by its values).
template <class F>
std::vector<ExactPoint> clip(const std::vector<ExactPoint>& polygon, F&& f) {
  std::vector<ExactPoint> out;
  const size_t n = polygon.size();
  std::vector<Q> v(n);
  for (size_t k = 0; k < n; ++k) v[k] = f(polygon[k]);
  for (size_t k = 0; k < n; ++k) {
    const ExactPoint& a = polygon[k];
    const ExactPoint& b = polygon[(k + 1) % n];
    const Q &fa = v[k], &fb = v[(k + 1) % n];
    if (CGAL::sign(fa) != CGAL::POSITIVE) out.push_back(a);
    if ((CGAL::sign(fa) == CGAL::POSITIVE) != (CGAL::sign(fb) == CGAL::POSITIVE) && fa != 0 && fb != 0) {
      const Q u = fa / (fa - fb);
      out.push_back({a.x + u * (b.x - a.x), a.y + u * (b.y - a.y), a.z + u * (b.z - a.z)});
    }
  }
  return out;
}

}  // namespace

ReachCover::ReachCover(const SurfaceMesh& mesh, const Samples& samples, const std::vector<std::vector<int>>& sample_triangles)
    : mesh_(mesh), samples_(samples), sample_triangles_(sample_triangles) {
  for (double w : samples.weights) cell_ = std::max(cell_, std::sqrt(w));
  if (!(cell_ > 0)) return;
  for (int i = 0; i < samples.size(); ++i) {
    const Vec3& p = samples.positions[i];
    grid_[cell_key(std::llround(std::floor(p.x / cell_)), std::llround(std::floor(p.y / cell_)),
                   std::llround(std::floor(p.z / cell_)))]
        .push_back(i);
  }
}

bool ReachCover::chain(int t, const std::vector<ExactPoint>& polygon, const std::vector<Vec3>& approx, int s) {
  const double w = samples_.weights[s];
  const Q qw(w);
  const std::vector<int>& targets = sample_triangles_[s];
  auto target = [&](int u) { return std::find(targets.begin(), targets.end(), u) != targets.end(); };
  auto met = [&](int u) {
    const Triangle& tri = mesh_.triangle(u);
    const Vec3 &a = mesh_.position(tri[0]), &b = mesh_.position(tri[1]), &c = mesh_.position(tri[2]);
    // A triangle far from the corners (by far more than rounding) is not met: a filter that can
    // only refuse a chain, never make one.
    const Vec3 centre = (a + b + c) / 3.0;
    const double reach = std::sqrt(w) + std::sqrt(std::max({squared_distance(centre, a), squared_distance(centre, b),
                                                            squared_distance(centre, c)}));
    for (const Vec3& p : approx)
      if (squared_distance(p, centre) > reach * reach * (1 + 1e-6)) return false;
    for (const ExactPoint& p : polygon)
      if (!ball_meets_triangle(p, qw, a, b, c)) return false;
    return true;
  };
  if (target(t)) return true;
  std::vector<int> queue{t};
  for (size_t k = 0; k < queue.size(); ++k)
    for (int e = 0; e < 3; ++e) {
      const int n = mesh_.neighbor(queue[k], e);
      if (n < 0 || std::find(queue.begin(), queue.end(), n) != queue.end() || !met(n)) continue;
      if (target(n)) return true;
      queue.push_back(n);
    }
  return false;
}

bool ReachCover::covered_by(const std::vector<ExactPoint>& polygon, const std::vector<int>& sites) const {
  // Each site's power cell in the polygon must lie in its ball. A cell that shrinks to a segment
  // or a point has its points in the other cells' closures too: it is left to them.
  for (int a : sites) {
    std::vector<ExactPoint> cell = polygon;
    const Vec3& xa = samples_.positions[a];
    const double wa = samples_.weights[a];
    for (int b : sites) {
      if (b == a) continue;
      const Vec3& xb = samples_.positions[b];
      const double wb = samples_.weights[b];
      cell = clip(cell, [&](const ExactPoint& p) { return power(p, xa, wa) - power(p, xb, wb); });
      if (cell.size() < 3) break;
    }
    if (cell.size() < 3) continue;
    for (const ExactPoint& p : cell)
      if (CGAL::sign(power(p, xa, wa)) == CGAL::POSITIVE) return false;
  }
  return true;
}

bool ReachCover::covers(int t, const std::vector<ExactPoint>& polygon, int k, int depth, int budget) {
  return covers_part(t, polygon, k, depth, budget);
}

bool ReachCover::covers_part(int t, const std::vector<ExactPoint>& polygon, int k, int depth, int& budget) {
  if (polygon.size() < 3 || !(cell_ > 0) || --budget < 0) return false;
  std::vector<Vec3> approx;
  Vec3 lo = to_double(polygon[0]), hi = lo;
  for (const ExactPoint& p : polygon) {
    approx.push_back(to_double(p));
    const Vec3& a = approx.back();
    lo = {std::min(lo.x, a.x), std::min(lo.y, a.y), std::min(lo.z, a.z)};
    hi = {std::max(hi.x, a.x), std::max(hi.y, a.y), std::max(hi.z, a.z)};
  }
  std::vector<int> sites{k};
  if (covered_by(polygon, sites)) return true;
  // Candidates: centres within the largest radius of the polygon's box.
  for (long long x = std::llround(std::floor(lo.x / cell_)) - 1; x <= std::llround(std::floor(hi.x / cell_)) + 1; ++x)
    for (long long y = std::llround(std::floor(lo.y / cell_)) - 1; y <= std::llround(std::floor(hi.y / cell_)) + 1; ++y)
      for (long long z = std::llround(std::floor(lo.z / cell_)) - 1; z <= std::llround(std::floor(hi.z / cell_)) + 1; ++z) {
        const auto it = grid_.find(cell_key(x, y, z));
        if (it == grid_.end()) continue;
        for (int s : it->second) {
          if (s == k || std::find(sites.begin(), sites.end(), s) != sites.end()) continue;
          // A ball that holds no point of the polygon's box (by far more than rounding) covers nothing.
          const Vec3& c = samples_.positions[s];
          const Vec3 nearest{std::clamp(c.x, lo.x, hi.x), std::clamp(c.y, lo.y, hi.y), std::clamp(c.z, lo.z, hi.z)};
          if (squared_distance(nearest, c) > samples_.weights[s] * (1 + 1e-6)) continue;
          if (chain(t, polygon, approx, s)) sites.push_back(s);
        }
      }
  if (sites.size() > 1 && covered_by(polygon, sites)) return true;
  if (depth <= 0) return false;
  // Halves: across the diagonal from corner 0 to the middle one, or a triangle from its longest
  // side's midpoint to the opposite corner.
  const size_t n = polygon.size();
  std::vector<ExactPoint> first, second;
  if (n >= 4) {
    first.assign(polygon.begin(), polygon.begin() + static_cast<long>(n / 2) + 1);
    second.assign(polygon.begin() + static_cast<long>(n / 2), polygon.end());
    second.push_back(polygon[0]);
  } else {
    size_t e = 0;
    for (size_t k2 = 1; k2 < 3; ++k2)
      if (squared_distance(approx[k2], approx[(k2 + 1) % 3]) > squared_distance(approx[e], approx[(e + 1) % 3])) e = k2;
    const ExactPoint &a = polygon[e], &b = polygon[(e + 1) % 3], &c = polygon[(e + 2) % 3];
    const Q half(0.5);
    const ExactPoint m{(a.x + b.x) * half, (a.y + b.y) * half, (a.z + b.z) * half};
    first = {a, m, c};
    second = {m, b, c};
  }
  return covers_part(t, first, k, depth - 1, budget) && covers_part(t, second, k, depth - 1, budget);
}

}  // namespace lrvd::verify_detail
