// The geodesic unit sphere of the Fig. 9 benchmarks (bench_fig9, bench_verify): an icosahedron
// whose edges are cut into k segments, 20·k² triangles, vertices projected onto the sphere.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "mesh/surface_mesh.h"

namespace lrvd::bench {

//! The unit sphere as an icosahedron whose edges are cut into k segments, the 20·k² triangles'
//! vertices projected onto the sphere (a geodesic sphere of any resolution, not only 20·4^l).
inline SurfaceMesh geodesic_sphere(int k) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                         {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  const std::vector<Triangle> faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                                       {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  const std::vector<Vec3> corners = p;
  auto on_sphere = [](const Vec3& q) { return q / norm(q); };
  for (auto& q : p) q = on_sphere(q);

  // Interior vertices of the icosahedron edge (min, max), from min to max, shared by both faces.
  std::map<std::pair<int, int>, int> edge_first;
  auto edge_vertex = [&](int u, int v, int s) {  // s-th of the k-1 points from u towards v
    const int a = std::min(u, v), b = std::max(u, v);
    auto [it, inserted] = edge_first.emplace(std::make_pair(a, b), static_cast<int>(p.size()));
    if (inserted)
      for (int r = 1; r < k; ++r) p.push_back(on_sphere((corners[a] * double(k - r) + corners[b] * double(r)) / k));
    return it->second + (u == a ? s - 1 : k - s - 1);
  };

  std::vector<Triangle> triangles;
  triangles.reserve(20 * k * k);
  std::vector<int> grid((k + 1) * (k + 1));
  for (const Triangle& f : faces) {
    const Vec3 &A = corners[f[0]], &B = corners[f[1]], &C = corners[f[2]];
    // Point (i, j) of the face is (A (k-i-j) + B i + C j) / k.
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        int id;
        if (i == 0 && j == 0) id = f[0];
        else if (i == k) id = f[1];
        else if (j == k) id = f[2];
        else if (j == 0) id = edge_vertex(f[0], f[1], i);
        else if (i == 0) id = edge_vertex(f[0], f[2], j);
        else if (i + j == k) id = edge_vertex(f[1], f[2], j);
        else {
          id = static_cast<int>(p.size());
          p.push_back(on_sphere((A * double(k - i - j) + B * double(i) + C * double(j)) / k));
        }
        grid[i * (k + 1) + j] = id;
      }
    auto at = [&](int i, int j) { return grid[i * (k + 1) + j]; };
    for (int i = 0; i < k; ++i)
      for (int j = 0; i + j < k; ++j) {
        triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 2 <= k) triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  SurfaceMesh mesh(std::move(p), std::move(triangles));
  if (!mesh.is_closed() || mesh.euler_characteristic() != 2 || mesh.vertex_count() != 10 * k * k + 2)
    throw std::logic_error(fmt::format("geodesic_sphere({}) is not a closed sphere", k));
  return mesh;
}

//! Segments per icosahedron edge giving about `triangles` triangles.
inline int segments_for(int triangles) { return std::max(1, static_cast<int>(std::lround(std::sqrt(triangles / 20.0)))); }

}  // namespace lrvd::bench
