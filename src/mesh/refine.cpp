// Refinement by splitting long edges (paper §4.2): every edge longer than a bound is split at its
// midpoint, longest first, until none is left, so that each triangle can hold at most one sample.
#include <algorithm>
#include <cmath>
#include <queue>
#include <unordered_map>

#include <fmt/format.h>

#include "common/error.h"
#include "mesh/surface_mesh.h"

namespace lrvd {

namespace {

uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

struct LongEdge {
  double length;
  int a, b;
  bool operator<(const LongEdge& o) const { return length < o.length; }
};

}  // namespace

SurfaceMesh refine_long_edges(const SurfaceMesh& mesh, double max_length) {
  if (!(max_length > 0))
    throw InputError(fmt::format("refinement length must be positive (got {})", max_length));
  std::vector<Vec3> positions = mesh.positions();
  std::vector<Triangle> triangles = mesh.triangles();

  // Which triangles use each undirected edge (one or two).
  std::unordered_map<uint64_t, std::array<int, 2>> edge_triangles;
  auto attach = [&](int a, int b, int t) {
    auto [it, fresh] = edge_triangles.try_emplace(edge_key(a, b), std::array<int, 2>{t, -1});
    if (!fresh) it->second[1] = t;
  };
  auto replace = [&](int a, int b, int old_t, int new_t) {
    auto& slot = edge_triangles.at(edge_key(a, b));
    (slot[0] == old_t ? slot[0] : slot[1]) = new_t;
  };
  std::priority_queue<LongEdge> queue;
  auto push_if_long = [&](int a, int b) {
    const double len = distance(positions[a], positions[b]);
    if (len > max_length) queue.push({len, std::min(a, b), std::max(a, b)});
  };
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = triangles[t][e], b = triangles[t][(e + 1) % 3];
      attach(a, b, t);
      if (a < b || mesh.neighbor(t, e) < 0) push_if_long(a, b);
    }

  while (!queue.empty()) {
    const LongEdge edge = queue.top();
    queue.pop();
    auto found = edge_triangles.find(edge_key(edge.a, edge.b));
    if (found == edge_triangles.end()) continue;  // already split
    const std::array<int, 2> users = found->second;
    edge_triangles.erase(found);
    const int m = static_cast<int>(positions.size());
    positions.push_back(0.5 * (positions[edge.a] + positions[edge.b]));
    for (int t : users) {
      if (t < 0) continue;
      // Rotate so that the split edge is (u, v) = corners 0 -> 1 of t, w opposite.
      Triangle tri = triangles[t];
      int e = 0;
      while (!((tri[e] == edge.a || tri[e] == edge.b) && (tri[(e + 1) % 3] == edge.a || tri[(e + 1) % 3] == edge.b))) ++e;
      const int u = tri[e], v = tri[(e + 1) % 3], w = tri[(e + 2) % 3];
      const int t_new = static_cast<int>(triangles.size());
      triangles[t] = {u, m, w};
      triangles.push_back({m, v, w});
      replace(v, w, t, t_new);
      attach(u, m, t);
      attach(m, v, t_new);
      attach(m, w, t);
      attach(m, w, t_new);
      push_if_long(m, w);
    }
    push_if_long(edge.a, m);
    push_if_long(m, edge.b);
  }
  return SurfaceMesh(std::move(positions), std::move(triangles));
}

double suggested_refinement_length(const SurfaceMesh& mesh, int n) {
  if (mesh.triangle_count() >= 2 * n) return 0;
  // Equilateral triangles of side a have area sqrt(3)/4 a^2: 4n of them cover the area.
  return std::sqrt(4.0 * mesh.area() / (std::sqrt(3.0) * 4.0 * n));
}

}  // namespace lrvd
