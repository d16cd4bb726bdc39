// Mean curvature from the cotangent Laplacian.
#include "mesh/curvature.h"

#include <algorithm>
#include <cmath>

namespace lrvd {

std::vector<double> mean_curvature(const SurfaceMesh& mesh) {
  const int nv = mesh.vertex_count();
  std::vector<Vec3> laplacian(nv, Vec3{});
  std::vector<double> area(nv, 0);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    const double a = mesh.triangle_area(t);
    for (int c = 0; c < 3; ++c) {
      const int i = tri[c], j = tri[(c + 1) % 3], k = tri[(c + 2) % 3];
      const Vec3 u = mesh.position(j) - mesh.position(i), v = mesh.position(k) - mesh.position(i);
      const double cot = dot(u, v) / std::max(norm(cross(u, v)), 1e-300);
      laplacian[j] += 0.5 * cot * (mesh.position(k) - mesh.position(j));
      laplacian[k] += 0.5 * cot * (mesh.position(j) - mesh.position(k));
      area[i] += a / 3;
    }
  }
  std::vector<char> boundary(nv, 0);
  for (const auto& loop : mesh.boundary_loops())
    for (int v : loop) boundary[v] = 1;
  std::vector<double> kappa(nv);
  for (int v = 0; v < nv; ++v) kappa[v] = boundary[v] ? 0.0 : norm(laplacian[v]) / (2 * std::max(area[v], 1e-300));
  return kappa;
}

std::vector<double> angle_deficits(const SurfaceMesh& mesh) {
  std::vector<double> deficit(mesh.vertex_count(), 2 * M_PI);
  for (const auto& loop : mesh.boundary_loops())
    for (int v : loop) deficit[v] = M_PI;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    for (int c = 0; c < 3; ++c) {
      const Vec3 u = mesh.position(tri[(c + 1) % 3]) - mesh.position(tri[c]);
      const Vec3 v = mesh.position(tri[(c + 2) % 3]) - mesh.position(tri[c]);
      deficit[tri[c]] -= std::atan2(norm(cross(u, v)), dot(u, v));
    }
  }
  return deficit;
}

}  // namespace lrvd
