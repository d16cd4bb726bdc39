// The reader's refusals of open seams (see mesh_seams.h): boundary corners that coincide or nearly
// coincide without being shared, and boundary corners on another face's boundary edge.
#include "io/mesh_seams.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <unordered_map>

#include "io/mesh_repair.h"
#include "mesh/weld.h"

namespace lrvd {

using namespace mesh_io_detail;

namespace {

// The largest --weld the refusal suggests, as a fraction of the bounding-box diagonal.
constexpr double kLargestSuggestedWeld = 1e-3;

// The --weld to suggest for a soup whose boundary corners nearly coincide, the closest pairs
// `found` apart (a fraction of the diagonal). The copies of one corner can lie further apart than
// the closest pairs, and a greedy weld without chains takes only those within the distance of the
// first copy, so the suggestion is where the seams stop closing: the smallest power of ten, from
// the one above `found`, at which welding the boundary vertices leaves as many boundary edges as
// welding at ten times it (at most kLargestSuggestedWeld).
double suggested_weld(const std::vector<Vec3>& positions, const std::vector<int>& boundary_vertices,
                      const std::vector<std::pair<int, int>>& boundary_edges, double diagonal, double found) {
  std::vector<Vec3> points;
  points.reserve(boundary_vertices.size());
  for (int v : boundary_vertices) points.push_back(positions[v]);
  std::vector<int> local(positions.size(), -1);
  for (std::size_t i = 0; i < boundary_vertices.size(); ++i) local[boundary_vertices[i]] = static_cast<int>(i);
  const auto open_edges_after_weld = [&](double fraction) {
    const std::vector<int> rep = weld_representatives(points, fraction * diagonal);
    std::map<std::pair<int, int>, int> uses;
    for (const auto& [a, b] : boundary_edges) {
      const int ra = rep[local[a]], rb = rep[local[b]];
      if (ra != rb) ++uses[{std::min(ra, rb), std::max(ra, rb)}];
    }
    return std::count_if(uses.begin(), uses.end(), [](const auto& u) { return u.second == 1; });
  };
  double weld = std::pow(10.0, std::floor(std::log10(found)) + 1);
  for (auto open = open_edges_after_weld(weld); weld < kLargestSuggestedWeld;) {
    const auto next = open_edges_after_weld(10 * weld);
    if (next == open) break;
    weld *= 10;
    open = next;
  }
  return weld;
}

// The soup's edges with the number of triangles on each, its boundary edges (one triangle) and the
// vertices on them, in index order.
struct SoupBoundary {
  std::unordered_map<uint64_t, int> edge_uses;
  std::vector<std::pair<int, int>> edges;
  std::vector<int> vertices;
  static uint64_t key(int a, int b) {
    return (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint32_t>(std::max(a, b));
  }
};

SoupBoundary soup_boundary(std::size_t vertex_count, const std::vector<Triangle>& triangles) {
  SoupBoundary boundary;
  std::unordered_map<uint64_t, int>& edge_uses = boundary.edge_uses;
  edge_uses.reserve(triangles.size() * 2);
  for (const Triangle& t : triangles)
    for (int e = 0; e < 3; ++e) ++edge_uses[SoupBoundary::key(t[e], t[(e + 1) % 3])];
  std::vector<char> on_boundary(vertex_count, 0);
  for (const Triangle& t : triangles)
    for (int e = 0; e < 3; ++e)
      if (edge_uses[SoupBoundary::key(t[e], t[(e + 1) % 3])] == 1) {
        on_boundary[t[e]] = on_boundary[t[(e + 1) % 3]] = 1;
        boundary.edges.push_back({t[e], t[(e + 1) % 3]});
      }
  for (int v = 0; v < static_cast<int>(vertex_count); ++v)
    if (on_boundary[v]) boundary.vertices.push_back(v);
  return boundary;
}

// The boundary vertices at the same point as another one: how many, and of the pairs, the one
// whose first vertex comes first in the file.
struct CoincidentTwins {
  int count = 0, first_a = -1, first_b = -1;
};

CoincidentTwins coincident_twins(const std::vector<Vec3>& positions, const std::vector<int>& boundary_vertices,
                                 const std::vector<int>& original) {
  CoincidentTwins twins;
  const auto less = [&](int a, int b) {
    const Vec3 &p = positions[a], &q = positions[b];
    return std::tie(p.x, p.y, p.z, a) < std::tie(q.x, q.y, q.z, b);
  };
  std::vector<int> sorted = boundary_vertices;
  std::sort(sorted.begin(), sorted.end(), less);
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const bool same_as_prev = i > 0 && positions[sorted[i]] == positions[sorted[i - 1]];
    const bool same_as_next = i + 1 < sorted.size() && positions[sorted[i]] == positions[sorted[i + 1]];
    if (same_as_prev || same_as_next) ++twins.count;
    if (same_as_next && (twins.first_a < 0 || original[sorted[i]] < twins.first_a))
      twins.first_a = original[sorted[i]], twins.first_b = original[sorted[i + 1]];
  }
  return twins;
}

// The boundary vertices within `tolerance` of another one that is not at the same point and shares
// no edge and no neighbour with it. Neighbours, for the pairs that belong together: an edge's ends,
// or two corners of one short boundary path (a disk whose outline has two short edges in a row is
// no soup).
NearTwins near_twins_on_boundary(const std::vector<Vec3>& positions, const SoupBoundary& boundary, double tolerance) {
  std::vector<std::vector<int>> neighbours(positions.size());
  for (const auto& [a, b] : boundary.edges) {
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  const auto joined = [&](int a, int b) {
    if (boundary.edge_uses.count(SoupBoundary::key(a, b))) return true;
    for (int c : neighbours[a])
      if (boundary.edge_uses.count(SoupBoundary::key(c, b))) return true;
    return false;
  };
  return find_near_twins(positions, boundary.vertices, tolerance, joined);
}

}  // namespace

void mesh_io_detail::refuse_triangle_soup(const std::string& path, const std::vector<Vec3>& positions,
                                          const std::vector<Triangle>& triangles, const std::vector<int>& original,
                                          bool repaired, double weld, const std::string& weld_damage) {
  const SoupBoundary boundary = soup_boundary(positions.size(), triangles);
  if (boundary.vertices.empty()) return;
  const CoincidentTwins coincident = repaired ? CoincidentTwins() : coincident_twins(positions, boundary.vertices, original);
  const double diagonal = bounding_box(positions).diagonal();
  // After a --weld W, the copies of one corner that the greedy weld left apart are less than 2 W
  // from each other when they all lay within 2 W: a W a little too small is caught too.
  const double near_fraction = std::max(kNearTwinFraction, 2 * weld);
  const NearTwins near = near_twins_on_boundary(positions, boundary, near_fraction * diagonal);
  const std::string weld_advice =
      near.count == 0 ? std::string()
                      : fmt::format(" --weld {:g}", suggested_weld(positions, boundary.vertices, boundary.edges, diagonal,
                                                                    near.max_distance / diagonal));
  if (coincident.count > 0)
    fail(path, fmt::format("looks like a triangle soup: vertices {} and {} coincide but are not shared ({} boundary "
                           "vertices have a twin{}); rerun with --repair{} to weld them",
                           coincident.first_a, coincident.first_b, coincident.count,
                           near.count > 0 ? fmt::format(", and {} a twin nearly at the same point", near.count) : "",
                           weld_advice));
  if (near.count == 0) return;
  const int a = repaired ? near.a : original[near.a], b = repaired ? near.b : original[near.b];
  // A weld that collapsed the file's own edges tore the surface: the seams it left are its doing.
  if (!weld_damage.empty())
    fail(path, fmt::format("{}, and left seams open: after --repair, vertices {} and {} are {:.3g} apart on separate "
                           "boundary edges ({} boundary vertices have such a twin)",
                           weld_damage, std::min(a, b), std::max(a, b), near.distance, near.count));
  fail(path, fmt::format("looks like a triangle soup or a seam whose corners nearly coincide: {}vertices {} and {} are "
                         "{:.3g} apart ({:.2g} of the bounding-box diagonal) on separate boundary edges ({} boundary "
                         "vertices have such a twin); rerun with --repair{} to weld them",
                         repaired ? "after --repair, " : "", std::min(a, b), std::max(a, b), near.distance,
                         near.distance / diagonal, near.count, weld_advice));
}

void mesh_io_detail::refuse_t_junctions(const std::string& path, const SurfaceMesh& mesh,
                                        const std::vector<int>& original, bool repaired) {
  const std::vector<Triangle>& triangles = mesh.triangles();  // every vertex used: the box is the mesh's
  const std::vector<TJunction> found =
      find_t_junctions(mesh.positions(), triangles, kNearTwinFraction * mesh.bounding_box().diagonal());
  if (found.empty()) return;
  const auto first = std::min_element(found.begin(), found.end(), [&](const TJunction& a, const TJunction& b) {
    return std::tie(a.triangle, a.vertex) < std::tie(b.triangle, b.vertex);
  });
  const Triangle& t = triangles[first->triangle];
  const auto number = [&](int v) { return repaired ? v : original[v]; };
  fail(path, fmt::format("{}has a crack: vertex {} lies on the boundary edge ({}, {}) of another face, which does not "
                         "use it (a T-junction; {} such corner{}){}",
                         repaired ? "is still invalid after --repair: it " : "", number(first->vertex),
                         number(t[first->edge]), number(t[(first->edge + 1) % 3]), found.size(),
                         found.size() == 1 ? "" : "s", repaired ? "" : "; rerun with --repair to split those edges"));
}

}  // namespace lrvd
