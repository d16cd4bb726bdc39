// Small meshes built in code for the tests: octahedron, grid sheets, spheres, merging, shuffling.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "mesh/surface_mesh.h"

namespace lrvd::test {

inline SurfaceMesh octahedron() {
  return SurfaceMesh({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                     {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
}

//! Unit square [0,1]^2 in the z = 0 plane, nx * ny quads split in two.
inline SurfaceMesh grid(int nx, int ny) {
  std::vector<Vec3> p;
  std::vector<Triangle> t;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) p.push_back({double(i) / nx, double(j) / ny, 0});
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      t.push_back({a, b, d});
      t.push_back({a, d, c});
    }
  return SurfaceMesh(p, t);
}

//! Two unit squares in the z = 0 plane joined by a neck `width` wide (centred on y = 1/2) and
//! `length` long, on a grid of `per_unit` quads a unit split in two; width and length are whole
//! numbers of quads.
inline SurfaceMesh neck_sheet(int per_unit, double width, double length) {
  const double h = 1.0 / per_unit;
  const int nx = static_cast<int>(std::lround((2 + length) * per_unit)), ny = per_unit;
  std::map<std::pair<int, int>, int> index;
  std::vector<Vec3> p;
  std::vector<Triangle> t;
  auto vertex = [&](int i, int j) {
    const auto [it, added] = index.try_emplace({i, j}, static_cast<int>(p.size()));
    if (added) p.push_back({i * h, j * h, 0});
    return it->second;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = (i + 0.5) * h, y = (j + 0.5) * h;
      if (x > 1 && x < 1 + length && std::abs(y - 0.5) > width / 2) continue;
      const int a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i, j + 1), d = vertex(i + 1, j + 1);
      t.push_back({a, b, d});
      t.push_back({a, d, c});
    }
  return SurfaceMesh(p, t);
}

//! The unit square in the z = 0 plane (`per_unit` quads a side, each split in two) with a handle
//! on top: a square tube one quad wide that rises from the quad at (i, j), runs `span` quads along
//! x at a height of two quads and comes down into the quad at (i + span, j). Genus 1, one boundary
//! loop.
inline SurfaceMesh sheet_with_handle(int per_unit, int i, int j, int span) {
  const double h = 1.0 / per_unit;
  std::vector<Vec3> p;
  std::vector<Triangle> t;
  for (int y = 0; y <= per_unit; ++y)
    for (int x = 0; x <= per_unit; ++x) p.push_back({x * h, y * h, 0});
  auto grid_vertex = [&](int x, int y) { return y * (per_unit + 1) + x; };
  for (int y = 0; y < per_unit; ++y)
    for (int x = 0; x < per_unit; ++x) {
      if (y == j && (x == i || x == i + span)) continue;  // the tube's two ends
      const int a = grid_vertex(x, y), b = a + 1, c = a + per_unit + 1, d = c + 1;
      t.push_back({a, b, d});
      t.push_back({a, d, c});
    }
  // Rings of four vertices, in the order (low x or top, low y), (high x or bottom, low y), then
  // the same two at high y: up from the first quad, two mitred corners, down into the second.
  const double x0 = i * h, x1 = (i + span) * h, y0 = j * h, y1 = y0 + h, z1 = 2 * h;
  auto add = [&](const Vec3& q) {
    p.push_back(q);
    return static_cast<int>(p.size()) - 1;
  };
  std::vector<std::array<int, 4>> rings;
  rings.push_back({grid_vertex(i, j), grid_vertex(i + 1, j), grid_vertex(i + 1, j + 1), grid_vertex(i, j + 1)});
  rings.push_back({add({x0, y0, h}), add({x0 + h, y0, h}), add({x0 + h, y1, h}), add({x0, y1, h})});
  rings.push_back({add({x0, y0, z1 + h}), add({x0 + h, y0, z1}), add({x0 + h, y1, z1}), add({x0, y1, z1 + h})});
  rings.push_back({add({x1 + h, y0, z1 + h}), add({x1, y0, z1}), add({x1, y1, z1}), add({x1 + h, y1, z1 + h})});
  rings.push_back({add({x1 + h, y0, h}), add({x1, y0, h}), add({x1, y1, h}), add({x1 + h, y1, h})});
  rings.push_back({grid_vertex(i + span + 1, j), grid_vertex(i + span, j), grid_vertex(i + span, j + 1),
                   grid_vertex(i + span + 1, j + 1)});
  for (size_t k = 0; k + 1 < rings.size(); ++k)
    for (int a = 0; a < 4; ++a) {
      const int b = (a + 1) % 4;
      t.push_back({rings[k][a], rings[k + 1][b], rings[k + 1][a]});
      t.push_back({rings[k][a], rings[k][b], rings[k + 1][b]});
    }
  return SurfaceMesh(p, t);
}

//! Icosphere of radius 1: `levels` 1-to-4 subdivisions of an icosahedron, vertices on the sphere.
inline SurfaceMesh icosphere(int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                         {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<Triangle> t = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                             {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                             {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& q : p) q = q / norm(q);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      Vec3 m = p[a] + p[b];
      p.push_back(m / norm(m));
      return mid[key] = static_cast<int>(p.size()) - 1;
    };
    std::vector<Triangle> next;
    for (const auto& f : t) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    t.swap(next);
  }
  return SurfaceMesh(p, t);
}

//! Torus round the z axis, radii R (to the tube's centre) and r (the tube's), of nu x nv quads
//! split into two triangles each.
inline SurfaceMesh torus(double R, double r, int nu, int nv) {
  std::vector<Vec3> p;
  std::vector<Triangle> t;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, w = 2 * M_PI * j / nv;
      p.push_back({(R + r * std::cos(w)) * std::cos(u), (R + r * std::cos(w)) * std::sin(u), r * std::sin(w)});
    }
  auto at = [&](int i, int j) { return (i % nu) * nv + j % nv; };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      t.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      t.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return SurfaceMesh(p, t);
}

//! Disjoint union of two meshes, the second shifted by `offset`.
inline SurfaceMesh merge(const SurfaceMesh& a, const SurfaceMesh& b, const Vec3& offset) {
  std::vector<Vec3> p = a.positions();
  std::vector<Triangle> t = a.triangles();
  const int base = a.vertex_count();
  for (const Vec3& q : b.positions()) p.push_back(q + offset);
  for (Triangle f : b.triangles()) t.push_back({f[0] + base, f[1] + base, f[2] + base});
  return SurfaceMesh(p, t);
}

//! The same surface with its triangles in a random order (`seed`): an order that says nothing of
//! where a triangle is.
inline SurfaceMesh shuffled(const SurfaceMesh& mesh, unsigned seed) {
  std::vector<Triangle> t = mesh.triangles();
  std::mt19937 random(seed);
  std::shuffle(t.begin(), t.end(), random);
  return SurfaceMesh(mesh.positions(), t);
}

}  // namespace lrvd::test
