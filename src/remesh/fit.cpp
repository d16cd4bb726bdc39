// Quadric fitting of the remesh vertices under a quality floor (see fit.h).
#include "remesh/fit.h"

#include <algorithm>
#include <set>

#include <Eigen/Dense>

#include "metrics/quality.h"
#include "metrics/self_intersections.h"

namespace lrvd {

namespace {

// Area-weighted squared distance to the planes of the triangles under each cell, as A x = b.
struct CellQuadric {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
};

std::vector<CellQuadric> cell_quadrics(const Diagram& diagram, const SurfaceMesh& mesh) {
  std::vector<CellQuadric> quadric(diagram.sample_count);
  const SymbolicContext ctx = diagram.context(mesh);
  for (const CellPolygon& poly : diagram.polygons) {
    const SymbolicVertex* v = diagram.polygon_vertices(poly);
    const Vec3 origin = position(v[0], ctx);
    double area = 0;
    Vec3 previous = position(v[1], ctx) - origin;
    for (int k = 2; k < poly.vertex_count; ++k) {
      const Vec3 current = position(v[k], ctx) - origin;
      area += 0.5 * norm(cross(previous, current));
      previous = current;
    }
    if (!(area > 0)) continue;
    const Vec3 normal = mesh.triangle_normal(poly.triangle);
    const Eigen::Vector3d n(normal.x, normal.y, normal.z);
    const double offset = dot(normal, mesh.position(mesh.triangle(poly.triangle)[0]));
    quadric[poly.cell].a += area * n * n.transpose();
    quadric[poly.cell].b += area * offset * n;
  }
  return quadric;
}

// The minimiser of the quadric nearest to x0 within the directions the planes constrain.
Vec3 quadric_target(const CellQuadric& q, const Vec3& x0, double rank_threshold) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(q.a);
  const Eigen::Vector3d& lambda = eigen.eigenvalues();  // increasing
  if (!(lambda[2] > 0)) return x0;
  const Eigen::Vector3d start(x0.x, x0.y, x0.z);
  const Eigen::Vector3d residual = q.b - q.a * start;
  Eigen::Vector3d step = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k)
    if (lambda[k] > rank_threshold * lambda[2])
      step += eigen.eigenvectors().col(k).dot(residual) / lambda[k] * eigen.eigenvectors().col(k);
  return {x0.x + step[0], x0.y + step[1], x0.z + step[2]};
}

std::set<std::pair<int, int>> crossing_pairs(const DualMesh& dual) {
  const auto pairs = find_self_intersections(dual.positions, dual.triangles, proper_triangles(dual.positions, dual.triangles));
  return {pairs.begin(), pairs.end()};
}

}  // namespace

FitResult fit_to_surface(const Diagram& diagram, const SurfaceMesh& mesh, DualMesh& dual, const FitOptions& options) {
  FitResult result;
  const int n = static_cast<int>(dual.positions.size());
  const int nt = static_cast<int>(dual.triangles.size());
  if (n == 0 || nt == 0) return result;
  const std::vector<Vec3> original = dual.positions;

  // The floor: no triangle below the worst Q and the smallest angle the CVT gave (at most 30°), or
  // below its own value if it was worse than that already.
  std::vector<double> q_before(nt), angle_before(nt);
  std::vector<Vec3> normal_before(nt);
  double q_floor = 1, angle_floor = options.max_angle_floor;
  std::vector<std::vector<int>> incident(n);
  for (int t = 0; t < nt; ++t) {
    const Triangle& f = dual.triangles[t];
    const Vec3 &a = original[f[0]], &b = original[f[1]], &c = original[f[2]];
    q_before[t] = triangle_quality(a, b, c);
    angle_before[t] = triangle_min_angle(a, b, c);
    normal_before[t] = cross(b - a, c - a);
    q_floor = std::min(q_floor, q_before[t]);
    angle_floor = std::min(angle_floor, angle_before[t]);
    for (int v : f) incident[v].push_back(t);
  }
  auto acceptable = [&](int v) {
    for (int t : incident[v]) {
      const Triangle& f = dual.triangles[t];
      const Vec3 &a = dual.positions[f[0]], &b = dual.positions[f[1]], &c = dual.positions[f[2]];
      if (triangle_quality(a, b, c) < std::min(q_before[t], q_floor)) return false;
      if (triangle_min_angle(a, b, c) < std::min(angle_before[t], angle_floor)) return false;
      if (!(dot(cross(b - a, c - a), normal_before[t]) > 0)) return false;
    }
    return true;
  };

  const std::vector<CellQuadric> quadric = cell_quadrics(diagram, mesh);
  std::vector<Vec3> target(n);
  for (int v = 0; v < n; ++v) target[v] = quadric_target(quadric[v], original[v], options.rank_threshold);
  // The longest moves first (tips of the surface), each taken whole or in eighths.
  std::vector<int> order(n);
  for (int v = 0; v < n; ++v) order[v] = v;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return distance(target[a], original[a]) > distance(target[b], original[b]);
  });
  for (int pass = 0; pass < options.passes; ++pass)
    for (int v : order) {
      if (incident[v].empty()) continue;
      const Vec3 from = dual.positions[v];
      for (double step : {1.0, 0.875, 0.75, 0.625, 0.5, 0.375, 0.25, 0.125}) {
        dual.positions[v] = from + step * (target[v] - from);
        if (acceptable(v)) break;
        dual.positions[v] = from;
      }
    }

  // Moving vertices must not make triangles cross: put back both triangles of every new crossing.
  DualMesh unfitted;
  unfitted.positions = original;
  unfitted.triangles = dual.triangles;
  const std::set<std::pair<int, int>> before = crossing_pairs(unfitted);
  for (int round = 0; round < 8; ++round) {
    std::set<int> back;
    for (const auto& pair : crossing_pairs(dual))
      if (!before.count(pair))
        for (int t : {pair.first, pair.second})
          for (int v : dual.triangles[t])
            if (dual.positions[v] != original[v]) back.insert(v);
    if (back.empty()) break;
    for (int v : back) dual.positions[v] = original[v];
    result.reverted += static_cast<int>(back.size());
    if (round == 7) dual.positions = original;  // not settled: keep the CVT's vertices
  }
  for (int v = 0; v < n; ++v)
    if (dual.positions[v] != original[v]) {
      ++result.moved;
      result.max_displacement = std::max(result.max_displacement, distance(dual.positions[v], original[v]));
    }
  return result;
}

}  // namespace lrvd
