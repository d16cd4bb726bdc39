// SurfaceMesh construction: validation of the manifold preconditions and the adjacency build.
#include "mesh/surface_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>
#include <unordered_map>

#include <fmt/format.h>

#include "common/error.h"
#include "predicates/predicates.h"

namespace lrvd {

namespace {

int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// Whether the triangles edge-connected to `start` can be oriented consistently: a union-find with
// parity (whether a triangle must be reversed relative to its root) over the edges that exactly
// two triangles share. For the message on an inconsistent orientation: a Möbius-like strip has
// none.
bool orientable_around(const std::vector<Triangle>& triangles, int start) {
  std::unordered_map<std::uint64_t, std::vector<std::pair<int, bool>>> users;  // edge -> (triangle, a < b)
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = triangles[t][e], b = triangles[t][(e + 1) % 3];
      users[(static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint32_t>(std::max(a, b))]
          .push_back({t, a < b});
    }
  std::vector<int> parent(triangles.size());
  std::vector<char> flip(triangles.size(), 0);  // relative to the parent
  std::iota(parent.begin(), parent.end(), 0);
  std::function<std::pair<int, char>(int)> find = [&](int x) -> std::pair<int, char> {
    if (parent[x] == x) return {x, 0};
    const auto [root, parity] = find(parent[x]);
    parent[x] = root;
    flip[x] ^= parity;
    return {root, flip[x]};
  };
  std::vector<std::pair<int, int>> conflicts;  // roots that met with the wrong parity
  for (const auto& [edge, list] : users) {
    if (list.size() != 2) continue;
    // Consistent when the two traverse the edge in opposite directions: the same flip for both.
    const char must_differ = list[0].second == list[1].second;
    const auto [ra, pa] = find(list[0].first);
    const auto [rb, pb] = find(list[1].first);
    if (ra == rb) {
      if ((pa ^ pb) != must_differ) conflicts.push_back({ra, 0});
      continue;
    }
    parent[ra] = rb;
    flip[ra] = static_cast<char>(pa ^ pb ^ must_differ);
  }
  const int root = find(start).first;
  for (const auto& [r, unused] : conflicts)
    if (find(r).first == root) return false;
  return true;
}

// The steps of SurfaceMesh::link_and_check.

// Of vertices a and b, the one in fewer triangles.
int least_used(const SurfaceMesh& mesh, int a, int b) {
  return mesh.vertex_triangle_count(a) <= mesh.vertex_triangle_count(b) ? a : b;
}

void check_no_duplicate_triangles(const SurfaceMesh& mesh) {
  const int nt = mesh.triangle_count();
  const std::vector<Triangle>& triangles = mesh.triangles();
  // Duplicate triangles: same vertex set, in any order; the earlier one is among the triangles
  // around the corner with the fewest triangles (a fan's hub would make this quadratic), before
  // this one.
  auto sorted_corners = [&](int t) {
    std::array<int, 3> corners = triangles[t];
    std::sort(corners.begin(), corners.end());
    return corners;
  };
  for (int t = 0; t < nt; ++t) {
    const std::array<int, 3> corners = sorted_corners(t);
    const int pivot = least_used(mesh, least_used(mesh, corners[0], corners[1]), corners[2]);
    for (const int* u = mesh.vertex_triangles_begin(pivot); *u < t; ++u)
      if (sorted_corners(*u) == corners)
        throw InputError(fmt::format("triangles {} and {} are duplicates (vertices {}, {}, {})", *u, t, corners[0],
                                     corners[1], corners[2]));
  }
}

// The neighbours of the mesh's triangles across their edges; returns the number of edges.
int link_edges(const SurfaceMesh& mesh, std::vector<std::array<int, 3>>& neighbors) {
  const int nt = mesh.triangle_count();
  const std::vector<Triangle>& triangles = mesh.triangles();
  // Edges: at most two triangles each, in opposite directions. The triangles of edge (a, b) are
  // those around a or b (whichever has fewer) that hold both, in increasing order; each (t, e) is
  // checked when t is reached, so the first offending triangle is named, as a single pass over the
  // triangles would.
  neighbors.assign(nt, {-1, -1, -1});
  int edge_count = 0;
  auto edge_index = [&](int t, int a, int b) {  // the edge of t from a to b, or -1
    for (int e = 0; e < 3; ++e)
      if (triangles[t][e] == a && triangles[t][(e + 1) % 3] == b) return e;
    return -1;
  };
  for (int t = 0; t < nt; ++t) {
    for (int e = 0; e < 3; ++e) {
      const int a = triangles[t][e], b = triangles[t][(e + 1) % 3];
      int users[3] = {-1, -1, -1}, count = 0;
      const int pivot = least_used(mesh, a, b), other = pivot == a ? b : a;
      for (const int* u = mesh.vertex_triangles_begin(pivot); u != mesh.vertex_triangles_end(pivot) && count < 3; ++u) {
        const Triangle& tri = triangles[*u];
        if (tri[0] == other || tri[1] == other || tri[2] == other) users[count++] = *u;
      }
      if (users[0] == t) {
        ++edge_count;
        continue;
      }
      if (count >= 3 && users[2] == t)
        throw InputError(fmt::format("mesh is not manifold: edge ({}, {}) has 3 or more triangles ({}, {}, {})",
                                     std::min(a, b), std::max(a, b), users[0], users[1], t));
      if (users[1] != t) continue;  // a fourth user or later: the third one has thrown already
      const int t0 = users[0];
      if (edge_index(t0, a, b) >= 0)
        throw InputError(fmt::format(
            "inconsistent orientation: triangles {} and {} both traverse edge ({}, {}) in the same direction{}", t0,
            t, a, b,
            orientable_around(triangles, t) ? ""
                                             : ", and no orientation of their surface agrees on every edge (it is "
                                               "one-sided, like a Möbius strip: a repair cuts it open)"));
      neighbors[t][e] = t0;
      neighbors[t0][edge_index(t0, b, a)] = t;
    }
  }
  return edge_count;
}

void check_one_fan_per_vertex(const SurfaceMesh& mesh, const std::vector<std::array<int, 3>>& neighbors) {
  const int nv = mesh.vertex_count();
  const std::vector<Triangle>& triangles = mesh.triangles();
  // Manifold vertices: the triangles around v form a single fan (edge-connected through v). With
  // every edge manifold and consistently oriented, the triangles around v chain across their
  // edges at v; a walk both ways from the first one meets all of them iff they form one fan.
  // Only a failing vertex is looked at again, to count its fans for the message.
  auto corner_of = [&](int t, int v) { return triangles[t][0] == v ? 0 : triangles[t][1] == v ? 1 : 2; };
  auto fan_size = [&](int v) {
    const int start = *mesh.vertex_triangles_begin(v), count = mesh.vertex_triangle_count(v);
    int seen = 1;
    // Forward: across edge (v, next); stops back at the start (a closed fan) or at the boundary.
    int t = neighbors[start][corner_of(start, v)];
    for (; t >= 0 && t != start && seen <= count; t = neighbors[t][corner_of(t, v)]) ++seen;
    if (t == start) return seen;
    // Backward: across edge (previous, v), from the start to the other end of the open fan.
    for (t = neighbors[start][(corner_of(start, v) + 2) % 3]; t >= 0 && seen <= count;
         t = neighbors[t][(corner_of(t, v) + 2) % 3])
      ++seen;
    return seen;
  };
  {
    std::vector<int> parent;
    for (int v = 0; v < nv; ++v) {
      const int count = mesh.vertex_triangle_count(v);
      if (fan_size(v) == count) continue;
      const int* begin = mesh.vertex_triangles_begin(v);
      parent.resize(count);
      std::iota(parent.begin(), parent.end(), 0);
      int groups = count;
      for (int a = 0; a < count; ++a) {
        const int t = begin[a];
        for (int e = 0; e < 3; ++e) {
          const Triangle& tri = triangles[t];
          if (tri[e] != v && tri[(e + 1) % 3] != v) continue;
          const int across = neighbors[t][e];
          if (across < 0) continue;
          const int b = static_cast<int>(std::lower_bound(begin, begin + count, across) - begin);  // sorted list
          const int ra = find_root(parent, a), rb = find_root(parent, b);
          if (ra != rb) { parent[ra] = rb; --groups; }
        }
      }
      throw InputError(fmt::format("mesh is not manifold: vertex {} joins {} separate fans of triangles", v, groups));
    }
  }
}

}  // namespace

double BoundingBox::diagonal() const { return distance(min, max); }
double BoundingBox::reach() const {
  return std::max({std::abs(min.x), std::abs(min.y), std::abs(min.z), std::abs(max.x), std::abs(max.y), std::abs(max.z)});
}
double BoundingBox::coordinate_step() const { return std::ldexp(1.0, std::ilogb(reach()) - 52); }

SurfaceMesh::SurfaceMesh(std::vector<Vec3> positions, std::vector<Triangle> triangles)
    : positions_(std::move(positions)), triangles_(std::move(triangles)) {
  if (positions_.empty() || triangles_.empty()) throw InputError("mesh is empty: it has no triangles");
  for (int v = 0; v < vertex_count(); ++v) {
    const Vec3& p = positions_[v];
    if (!is_finite(p))
      throw InputError(fmt::format("vertex {} has a non-finite coordinate ({}, {}, {})", v, p.x, p.y, p.z));
  }
  std::vector<char> referenced(positions_.size(), 0);
  for (int t = 0; t < triangle_count(); ++t) {
    const Triangle& tri = triangles_[t];
    for (int c = 0; c < 3; ++c) {
      if (tri[c] < 0 || tri[c] >= vertex_count())
        throw InputError(fmt::format("triangle {} has vertex index {} out of range [0, {})", t, tri[c],
                                     vertex_count()));
      referenced[tri[c]] = 1;
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      throw InputError(fmt::format("triangle {} is degenerate: it repeats a vertex ({}, {}, {})", t, tri[0],
                                   tri[1], tri[2]));
  }
  check_triangle_areas();
  for (int v = 0; v < vertex_count(); ++v)
    if (!referenced[v]) throw InputError(fmt::format("vertex {} is not used by any triangle", v));
  build_topology();
}

SurfaceMesh::SurfaceMesh(std::vector<Vec3> positions, std::vector<Triangle> triangles,
                         std::vector<std::array<int, 3>> neighbors, int edge_count, std::vector<int> components,
                         int component_count)
    : positions_(std::move(positions)),
      triangles_(std::move(triangles)),
      neighbors_(std::move(neighbors)),
      component_of_triangle_(std::move(components)),
      component_count_(component_count),
      edge_count_(edge_count) {
  check_triangle_areas();
  build_vertex_triangles();
  build_vertex_neighbors();
  build_boundary_loops();
}

void SurfaceMesh::check_triangle_areas() const {
  for (int t = 0; t < triangle_count(); ++t) {
    const Triangle& tri = triangles_[t];
    if (predicates::collinear(positions_[tri[0]], positions_[tri[1]], positions_[tri[2]]))
      throw InputError(fmt::format("triangle {} ({}, {}, {}) has zero area", t, tri[0], tri[1], tri[2]));
  }
}

void SurfaceMesh::build_topology() {
  build_vertex_triangles();
  link_and_check();
  finish_topology();
}

void SurfaceMesh::triangles_at(int t, const Vec3& bary, std::vector<int>& out) const {
  out.push_back(t);
  const int zeros = (bary.x == 0) + (bary.y == 0) + (bary.z == 0);
  if (zeros == 2) {
    const int v = triangles_[t][bary.x != 0 ? 0 : (bary.y != 0 ? 1 : 2)];
    for (const int* s = vertex_triangles_begin(v); s != vertex_triangles_end(v); ++s)
      if (*s != t) out.push_back(*s);
  } else if (zeros == 1) {
    // Edge e joins corners e and e + 1: the one without corner k is k + 1.
    const int k = bary.x == 0 ? 0 : (bary.y == 0 ? 1 : 2);
    const int across = neighbor(t, (k + 1) % 3);
    if (across >= 0) out.push_back(across);
  }
}

void SurfaceMesh::build_vertex_triangles() {
  const int nt = triangle_count(), nv = vertex_count();

  // Vertex-to-triangle lists (CSR), each in increasing triangle order.
  vt_offsets_.assign(nv + 1, 0);
  for (const Triangle& tri : triangles_)
    for (int v : tri) ++vt_offsets_[v + 1];
  std::partial_sum(vt_offsets_.begin(), vt_offsets_.end(), vt_offsets_.begin());
  vt_triangles_.resize(vt_offsets_[nv]);
  {
    std::vector<int> fill(vt_offsets_.begin(), vt_offsets_.end() - 1);
    for (int t = 0; t < nt; ++t)
      for (int v : triangles_[t]) vt_triangles_[fill[v]++] = t;
  }
}

void SurfaceMesh::link_and_check() {
  check_no_duplicate_triangles(*this);
  edge_count_ = link_edges(*this, neighbors_);
  check_one_fan_per_vertex(*this, neighbors_);
}

void SurfaceMesh::finish_topology() {
  build_vertex_neighbors();
  build_components();
  build_boundary_loops();
}

void SurfaceMesh::build_vertex_neighbors() {
  const int nv = vertex_count();
  auto corner_of = [&](int t, int v) { return triangles_[t][0] == v ? 0 : triangles_[t][1] == v ? 1 : 2; };
  // Vertex-to-vertex lists (CSR), sorted. Around a manifold vertex v each neighbour u follows v in
  // the one triangle holding edge (v, u), or, on the boundary, precedes it in the one holding (u, v).
  // The relation is symmetric: going through the vertices u in increasing order and appending u to
  // the list of each of its neighbours (each edge once, by the same rule seen from u) leaves every
  // list sorted, without a sort.
  auto for_each_neighbor = [&](int u, auto&& f) {
    for (const int* t = vertex_triangles_begin(u); t != vertex_triangles_end(u); ++t) {
      const int c = corner_of(*t, u);
      f(triangles_[*t][(c + 1) % 3]);
      if (neighbors_[*t][(c + 2) % 3] < 0) f(triangles_[*t][(c + 2) % 3]);
    }
  };
  // The same entries counted per triangle: w gets u for each edge u -> w, and x gets y for each
  // boundary edge x -> y.
  vv_offsets_.assign(nv + 1, 0);
  for (int t = 0; t < triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      ++vv_offsets_[triangles_[t][(e + 1) % 3] + 1];
      if (neighbors_[t][e] < 0) ++vv_offsets_[triangles_[t][e] + 1];
    }
  std::partial_sum(vv_offsets_.begin(), vv_offsets_.end(), vv_offsets_.begin());
  vv_vertices_.assign(vv_offsets_[nv], 0);
  std::vector<int> fill(vv_offsets_.begin(), vv_offsets_.end() - 1);
  for (int u = 0; u < nv; ++u) for_each_neighbor(u, [&](int w) { vv_vertices_[fill[w]++] = u; });
}

void SurfaceMesh::build_components() {
  const int nt = triangle_count();
  // Connected components over triangle adjacency.
  component_of_triangle_.assign(nt, -1);
  component_count_ = 0;
  std::vector<int> stack;
  for (int seed = 0; seed < nt; ++seed) {
    if (component_of_triangle_[seed] >= 0) continue;
    const int c = component_count_++;
    component_of_triangle_[seed] = c;
    stack.push_back(seed);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int e = 0; e < 3; ++e) {
        const int n = neighbors_[t][e];
        if (n >= 0 && component_of_triangle_[n] < 0) {
          component_of_triangle_[n] = c;
          stack.push_back(n);
        }
      }
    }
  }
}

void SurfaceMesh::build_boundary_loops() {
  const int nt = triangle_count();
  // Boundary loops: each boundary vertex of a manifold mesh has one outgoing boundary edge.
  boundary_loops_.clear();
  std::unordered_map<int, int> next_on_boundary;
  for (int t = 0; t < nt; ++t)
    for (int e = 0; e < 3; ++e)
      if (neighbors_[t][e] < 0) next_on_boundary[triangles_[t][e]] = triangles_[t][(e + 1) % 3];
  std::vector<int> starts;
  for (const auto& kv : next_on_boundary) starts.push_back(kv.first);
  std::sort(starts.begin(), starts.end());
  std::unordered_map<int, char> visited;
  for (int start : starts) {
    if (visited.count(start)) continue;
    std::vector<int> loop;
    for (int v = start; !visited.count(v); v = next_on_boundary.at(v)) {
      visited[v] = 1;
      loop.push_back(v);
    }
    boundary_loops_.push_back(std::move(loop));
  }
}

int SurfaceMesh::neighbor_edge(int t, int e) const {
  const int across = neighbors_[t][e];
  const int a = triangles_[t][e];
  for (int f = 0; f < 3; ++f)
    if (triangles_[across][(f + 1) % 3] == a) return f;
  return -1;
}

int SurfaceMesh::euler_characteristic() const { return vertex_count() - edge_count_ + triangle_count(); }

std::vector<int> SurfaceMesh::component_euler_characteristics() const {
  std::vector<int> chi(component_count_, 0);
  for (int v = 0; v < vertex_count(); ++v) ++chi[vertex_component(v)];
  for (int t = 0; t < triangle_count(); ++t) {
    const int c = component_of_triangle_[t];
    ++chi[c];
    for (int e = 0; e < 3; ++e)  // count each edge once: from its lower triangle, or alone on the boundary
      if (neighbors_[t][e] < 0 || neighbors_[t][e] > t) --chi[c];
  }
  return chi;
}

std::vector<int> SurfaceMesh::minimum_vertex_counts() const {
  std::vector<int> loops(component_count_, 0);
  for (const std::vector<int>& loop : boundary_loops_) ++loops[vertex_component(loop.front())];
  const std::vector<int> chi = component_euler_characteristics();
  auto heawood = [](int euler) { return static_cast<int>(std::ceil((7 + std::sqrt(49.0 - 24.0 * euler)) / 2 - 1e-9)); };
  std::vector<int> fewest(component_count_);
  for (int c = 0; c < component_count_; ++c)
    fewest[c] = loops[c] == 0 ? heawood(chi[c]) : std::max(3 * loops[c], heawood(chi[c] + loops[c]) - loops[c]);
  return fewest;
}

int SurfaceMesh::minimum_vertex_count() const {
  const std::vector<int> fewest = minimum_vertex_counts();
  return std::accumulate(fewest.begin(), fewest.end(), 0);
}

double SurfaceMesh::triangle_area(int t) const {
  const Triangle& tri = triangles_[t];
  const Vec3& a = positions_[tri[0]];
  return 0.5 * norm(cross(positions_[tri[1]] - a, positions_[tri[2]] - a));
}

double SurfaceMesh::area() const {
  double sum = 0;
  for (int t = 0; t < triangle_count(); ++t) sum += triangle_area(t);
  return sum;
}

Vec3 SurfaceMesh::triangle_normal(int t) const {
  const Triangle& tri = triangles_[t];
  return lrvd::triangle_normal(positions_[tri[0]], positions_[tri[1]], positions_[tri[2]]);
}

BoundingBox bounding_box(const std::vector<Vec3>& points) {
  if (points.empty()) throw std::invalid_argument("bounding_box: no points");
  BoundingBox box{points.front(), points.front()};
  for (const Vec3& p : points)
    for (int c = 0; c < 3; ++c) {
      box.min[c] = std::min(box.min[c], p[c]);
      box.max[c] = std::max(box.max[c], p[c]);
    }
  return box;
}

BoundingBox SurfaceMesh::bounding_box() const {
  if (positions_.empty()) throw InputError("the mesh is empty: it has no bounding box");
  return lrvd::bounding_box(positions_);
}

double SurfaceMesh::boundary_loop_length(int loop) const {
  const std::vector<int>& v = boundary_loops_[loop];
  double length = 0;
  for (size_t k = 0; k < v.size(); ++k) length += distance(positions_[v[k]], positions_[v[(k + 1) % v.size()]]);
  return length;
}

double SurfaceMesh::max_edge_length() const {
  double longest = 0;
  for (const Triangle& tri : triangles_)
    for (int e = 0; e < 3; ++e)
      longest = std::max(longest, distance(positions_[tri[e]], positions_[tri[(e + 1) % 3]]));
  return longest;
}

namespace {

void require_workable_size(const BoundingBox& box, const char* what, const char* task) {
  // std::hypot, not BoundingBox::diagonal(): squaring the extents would overflow or vanish outside the range.
  const Vec3 extent = box.max - box.min;
  const double diagonal = std::hypot(extent.x, extent.y, extent.z);
  if (!std::isfinite(diagonal))  // extents past the largest double: box.max - box.min overflowed
    throw InputError(fmt::format("{} spans more than the doubles hold (coordinates from {:.3g} to {:.3g}); {} works "
                                 "with sizes from {:g} to {:g}: scale the model first",
                                 what, std::min({box.min.x, box.min.y, box.min.z}), std::max({box.max.x, box.max.y, box.max.z}),
                                 task, kSmallestModel, kLargestModel));
  if (!(diagonal >= kSmallestModel && diagonal <= kLargestModel))
    throw InputError(fmt::format("{} is {:.3g} across (bounding-box diagonal); {} works with sizes from {:g} to "
                                 "{:g}: scale the model first",
                                 what, diagonal, task, kSmallestModel, kLargestModel));
}

void require_fine_coordinates(const BoundingBox& box, const char* what, const char* task) {
  const Vec3 extent = box.max - box.min;
  const double diagonal = std::hypot(extent.x, extent.y, extent.z);
  const double reach = box.reach();
  if (!(diagonal > 0) || !std::isfinite(reach)) return;  // require_workable_size's to refuse
  const double step = box.coordinate_step();
  if (diagonal / step >= kFewestCoordinateSteps) return;
  const Vec3 centre = 0.5 * box.min + 0.5 * box.max;
  throw InputError(fmt::format("{} is {:.3g} across but lies at coordinates up to {:.3g}, where doubles step by {:.3g}: "
                               "{} needs at least {:.0f} steps across it; move the model nearer the origin (its "
                               "centre is at {:.6g} {:.6g} {:.6g})",
                               what, diagonal, reach, step, task, kFewestCoordinateSteps, centre.x, centre.y, centre.z));
}

void require_triangles(const SurfaceMesh& mesh, const char* task) {
  // A default-constructed mesh: the constructor refuses an empty one, this catches the other way.
  if (mesh.triangle_count() == 0) throw InputError(fmt::format("the mesh is empty: {} needs triangles", task));
}

}  // namespace

void require_workable_size(const std::vector<Vec3>& positions, const char* what, const char* task) {
  if (!positions.empty()) require_workable_size(bounding_box(positions), what, task);
}

void require_workable_size(const SurfaceMesh& mesh, const char* task) {
  require_triangles(mesh, task);
  require_workable_size(mesh.bounding_box(), "the model", task);
}

void require_within_reach(const BoundingBox& box, const std::vector<Vec3>& positions,
                          const std::vector<Triangle>& triangles, const char* what, const char* other,
                          const char* task) {
  const double reach = kFarthestMeasured * box.diagonal();
  for (const Triangle& t : triangles)
    for (int v : t) {
      const Vec3& p = positions[v];
      const Vec3 outside{std::max({box.min.x - p.x, p.x - box.max.x, 0.0}), std::max({box.min.y - p.y, p.y - box.max.y, 0.0}),
                         std::max({box.min.z - p.z, p.z - box.max.z, 0.0})};
      const double away = std::hypot(outside.x, outside.y, outside.z);
      if (away > reach)
        throw InputError(fmt::format("vertex {} of {} at ({:.6g}, {:.6g}, {:.6g}) is {:.3g} bounding-box diagonals of "
                                     "{} away from it, farther than {} reaches ({:.3g}): is it an outlier, or are the "
                                     "two in different frames?",
                                     v, what, p.x, p.y, p.z, away / box.diagonal(), other, task, kFarthestMeasured));
    }
}

void require_workable_model(const SurfaceMesh& mesh, const char* task) {
  require_triangles(mesh, task);
  const BoundingBox box = mesh.bounding_box();
  require_workable_size(box, "the model", task);
  require_fine_coordinates(box, "the model", task);
}

}  // namespace lrvd
