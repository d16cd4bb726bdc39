// Building blocks of the stress meshes: closed surfaces whose connectivity is manifold and
// outward-oriented by construction (see stress_builders.h).
#include "mesh/stress_builders.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace lrvd::stress {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Two triangles of the quad a, b, c, d (counterclockwise seen from outside).
void add_quad(std::vector<Triangle>& triangles, int a, int b, int c, int d) {
  triangles.push_back({a, b, c});
  triangles.push_back({a, c, d});
}

}  // namespace

void append(MeshParts& into, const MeshParts& part) {
  const int offset = static_cast<int>(into.positions.size());
  into.positions.insert(into.positions.end(), part.positions.begin(), part.positions.end());
  for (const Triangle& t : part.triangles) into.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

MeshParts grid_union_boundary(const std::vector<double>& xs, const std::vector<double>& ys,
                              const std::vector<double>& zs, const std::function<bool(int, int, int)>& filled) {
  const std::array<const std::vector<double>*, 3> axes{&xs, &ys, &zs};
  const std::array<int, 3> cells{static_cast<int>(xs.size()) - 1, static_cast<int>(ys.size()) - 1,
                                 static_cast<int>(zs.size()) - 1};
  auto inside = [&](const std::array<int, 3>& g) {
    for (int a = 0; a < 3; ++a)
      if (g[a] < 0 || g[a] >= cells[a]) return false;
    return filled(g[0], g[1], g[2]);
  };
  MeshParts out;
  // Grid points become vertices in the order the faces first use them.
  std::vector<int> vertex_of(static_cast<size_t>(cells[0] + 1) * (cells[1] + 1) * (cells[2] + 1), -1);
  auto vertex = [&](const std::array<int, 3>& g) {
    int& v = vertex_of[(static_cast<size_t>(g[2]) * (cells[1] + 1) + g[1]) * (cells[0] + 1) + g[0]];
    if (v < 0) {
      v = static_cast<int>(out.positions.size());
      out.positions.push_back({(*axes[0])[g[0]], (*axes[1])[g[1]], (*axes[2])[g[2]]});
    }
    return v;
  };
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i) {
        const std::array<int, 3> cell{i, j, k};
        if (!inside(cell)) continue;
        for (int a = 0; a < 3; ++a)
          for (int side = 0; side < 2; ++side) {
            std::array<int, 3> across = cell;
            across[a] += side ? 1 : -1;
            if (inside(across)) continue;
            // Face on the plane g[a] = cell[a] + side; b, c follow a cyclically, so the corner order
            // (0,0), (1,0), (1,1), (0,1) in (b, c) has normal +a (e_b × e_c = e_a).
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            std::array<int, 3> g = cell;
            g[a] += side;
            std::array<int, 3> g10 = g, g11 = g, g01 = g;
            ++g10[b];
            ++g11[b];
            ++g11[c];
            ++g01[c];
            const int q00 = vertex(g), q10 = vertex(g10), q11 = vertex(g11), q01 = vertex(g01);
            if (side == 1)
              add_quad(out.triangles, q00, q10, q11, q01);
            else
              add_quad(out.triangles, q00, q01, q11, q10);
          }
      }
  return out;
}

MeshParts revolve_profile(const std::vector<std::array<double, 2>>& profile, int segments) {
  const int rings = static_cast<int>(profile.size()) - 2;  // profile points off the axis
  MeshParts out;
  out.positions.reserve(static_cast<size_t>(rings) * segments + 2);
  out.positions.push_back({0.0, 0.0, profile.front()[1]});
  std::vector<double> cosines(segments), sines(segments);
  for (int s = 0; s < segments; ++s) {
    const double angle = 2.0 * kPi * s / segments;
    cosines[s] = s == 0 ? 1.0 : std::cos(angle);
    sines[s] = s == 0 ? 0.0 : std::sin(angle);
  }
  for (int k = 1; k <= rings; ++k)
    for (int s = 0; s < segments; ++s)
      out.positions.push_back({profile[k][0] * cosines[s], profile[k][0] * sines[s], profile[k][1]});
  out.positions.push_back({0.0, 0.0, profile.back()[1]});
  const int top = rings * segments + 1;
  auto ring = [&](int k, int s) { return 1 + (k - 1) * segments + s % segments; };
  // Going around (s) then along the profile (k) is counterclockwise seen from outside.
  for (int s = 0; s < segments; ++s) out.triangles.push_back({0, ring(1, s + 1), ring(1, s)});
  for (int k = 1; k < rings; ++k)
    for (int s = 0; s < segments; ++s)
      add_quad(out.triangles, ring(k, s), ring(k, s + 1), ring(k + 1, s + 1), ring(k + 1, s));
  for (int s = 0; s < segments; ++s) out.triangles.push_back({ring(rings, s), ring(rings, s + 1), top});
  return out;
}

MeshParts unit_icosphere(int frequency) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  const std::array<Vec3, 12> corners{{{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                                      {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                                      {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}}};
  // Counterclockwise seen from outside.
  const std::array<std::array<int, 3>, 20> faces{{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                                  {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                  {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                                  {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}}};
  const int n = frequency;
  MeshParts out;
  // A lattice point is identified by its integer barycentric weights on the icosahedron's corners
  // (corner, weight) with weight > 0, sorted by corner: shared edges and corners map to one vertex.
  std::map<std::array<int, 6>, int> vertex_of;
  std::vector<int> local((n + 1) * (n + 1));
  for (const auto& face : faces) {
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        std::array<std::pair<int, int>, 3> w{{{face[0], n - i - j}, {face[1], i}, {face[2], j}}};
        std::sort(w.begin(), w.end());
        std::array<int, 6> key{-1, 0, -1, 0, -1, 0};
        Vec3 p{0, 0, 0};
        int used = 0;
        for (const auto& [corner, weight] : w) {
          if (weight == 0) continue;
          key[2 * used] = corner;
          key[2 * used + 1] = weight;
          ++used;
          p += static_cast<double>(weight) * corners[corner];
        }
        auto [it, fresh] = vertex_of.try_emplace(key, static_cast<int>(out.positions.size()));
        if (fresh) out.positions.push_back(p / norm(p));
        local[i * (n + 1) + j] = it->second;
      }
    // +i runs towards face[1], +j towards face[2]: (i,j), (i+1,j), (i,j+1) keeps the face's orientation.
    auto at = [&](int i, int j) { return local[i * (n + 1) + j]; };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        out.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j < n - 1) out.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  return out;
}

MeshParts closed_tube(const std::vector<Vec3>& centers, const std::vector<Vec3>& normals,
                      const std::vector<Vec3>& binormals, double radius, int ring_segments) {
  const int rings = static_cast<int>(centers.size());
  MeshParts out;
  out.positions.reserve(static_cast<size_t>(rings) * ring_segments);
  std::vector<double> cosines(ring_segments), sines(ring_segments);
  for (int s = 0; s < ring_segments; ++s) {
    const double angle = 2.0 * kPi * s / ring_segments;
    cosines[s] = s == 0 ? 1.0 : std::cos(angle);
    sines[s] = s == 0 ? 0.0 : std::sin(angle);
  }
  for (int i = 0; i < rings; ++i)
    for (int s = 0; s < ring_segments; ++s)
      out.positions.push_back(centers[i] + radius * (cosines[s] * normals[i] + sines[s] * binormals[i]));
  auto at = [&](int i, int s) { return (i % rings) * ring_segments + s % ring_segments; };
  // Around the ring (s) then along the curve (i) is counterclockwise seen from outside, because
  // tangent = normal × binormal. Split each quad along its shorter diagonal.
  for (int i = 0; i < rings; ++i)
    for (int s = 0; s < ring_segments; ++s) {
      const int a = at(i, s), b = at(i, s + 1), c = at(i + 1, s + 1), d = at(i + 1, s);
      const auto& p = out.positions;
      if (squared_distance(p[a], p[c]) <= squared_distance(p[b], p[d])) {
        add_quad(out.triangles, a, b, c, d);
      } else {
        out.triangles.push_back({a, b, d});
        out.triangles.push_back({b, c, d});
      }
    }
  return out;
}

MeshParts extrude_strip(const std::vector<std::array<double, 2>>& left, const std::vector<std::array<double, 2>>& right,
                        double z0, double z1, int layers) {
  const int n = static_cast<int>(right.size());
  const int loop_size = 2 * n;
  // The polygon, counterclockwise: along `right`, then back along `left`.
  std::vector<std::array<double, 2>> loop(right);
  loop.insert(loop.end(), left.rbegin(), left.rend());
  MeshParts out;
  out.positions.reserve(static_cast<size_t>(loop_size) * (layers + 1));
  for (int l = 0; l <= layers; ++l) {
    const double z = l == layers ? z1 : z0 + (z1 - z0) * (static_cast<double>(l) / layers);
    for (const auto& q : loop) out.positions.push_back({q[0], q[1], z});
  }
  auto at = [&](int q, int l) { return l * loop_size + q % loop_size; };
  // Walls: along a counterclockwise edge then up (+z) is counterclockwise seen from outside.
  for (int l = 0; l < layers; ++l)
    for (int q = 0; q < loop_size; ++q) add_quad(out.triangles, at(q, l), at(q + 1, l), at(q + 1, l + 1), at(q, l + 1));
  // Caps: quad right[i], right[i+1], left[i+1], left[i] is counterclockwise in the xy-plane.
  auto left_at = [&](int i) { return loop_size - 1 - i; };
  for (int i = 0; i + 1 < n; ++i) {
    add_quad(out.triangles, at(i, layers), at(i + 1, layers), at(left_at(i + 1), layers), at(left_at(i), layers));
    add_quad(out.triangles, at(i, 0), at(left_at(i), 0), at(left_at(i + 1), 0), at(i + 1, 0));
  }
  return out;
}

}  // namespace lrvd::stress
