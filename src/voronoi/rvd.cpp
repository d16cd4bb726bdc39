// The exact restricted Voronoi (power) diagram, the baseline the LRVD is compared with: for each
// triangle, the cells meeting it are found by walking the Delaunay (regular) neighbour graph from
// the cell of one corner, and each is clipped by all its neighbours' bisectors exactly.
#include "voronoi/rvd.h"

#include <algorithm>
#include <chrono>
#include <map>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "common/timing.h"
#include "diagram/clip.h"
#include "mesh/surface_mesh.h"
#include "voronoi/lrvd.h"

namespace lrvd {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

// The most samples on one empty sphere that are all made neighbours (see neighbours_of).
constexpr std::size_t kMostCosphericalSamples = 32;

// Neighbours of each sample in the 3D Delaunay (or regular) triangulation, as sorted lists.
//
// Samples on one empty sphere (or power sphere) have several Delaunay triangulations, and CGAL
// builds one by its own tie rule, while the diagram's perturbation (the lower id is closer) may
// make neighbours of two samples that CGAL's triangulation does not join (the other diagonal of a
// cospherical cube's face, say). So the cells whose spheres are exactly one sphere are grouped
// (a cell and its neighbour across a facet are, when the neighbour's far vertex is on the cell's
// sphere: exact `side_of_sphere`), and every two samples of a group are neighbours. Samples all
// in one plane give a triangulation of dimension 2, whose triangles are grouped by their circles
// the same way (four samples on a circle round a mesh vertex lost a triangle's cell before).
// `on_sphere(cell, vertex)` is that exact test.
template <class Triangulation, class OnSphere>
std::vector<std::vector<int>> neighbours_of(const Triangulation& tr, int n, OnSphere on_sphere) {
  std::vector<std::vector<int>> adjacency(n);
  for (auto e = tr.finite_edges_begin(); e != tr.finite_edges_end(); ++e) {
    const int a = e->first->vertex(e->second)->info(), b = e->first->vertex(e->third)->info();
    adjacency[a].push_back(b);
    adjacency[b].push_back(a);
  }
  using Cell = typename Triangulation::Cell_handle;
  // The full-dimensional faces: tetrahedra, or triangles when every sample lies in one plane (the
  // facets (c, 3) of a triangulation of dimension 2, where a circle takes the sphere's part).
  const int dimension = tr.dimension(), corners = dimension + 1;
  std::vector<Cell> faces;
  if (dimension == 3)
    for (auto c = tr.all_cells_begin(); c != tr.all_cells_end(); ++c) faces.push_back(c);
  else if (dimension == 2)
    for (auto f = tr.all_facets_begin(); f != tr.all_facets_end(); ++f) faces.push_back(f->first);
  std::map<Cell, Cell> parent;
  auto find = [&](Cell c) {
    auto it = parent.find(c);
    while (it != parent.end() && it->second != c) {
      c = it->second;
      it = parent.find(c);
    }
    return c;
  };
  for (const Cell c : faces)
    for (int i = 0; i < corners; ++i) {
      const Cell other = c->neighbor(i);
      if (c < other && on_sphere(c, other->vertex(other->index(c)))) {
        const Cell a = find(c), b = find(other);
        parent.emplace(a, a);
        parent.emplace(b, b);
        if (a != b) parent[b] = a;
      }
    }
  std::map<Cell, std::vector<int>> groups;
  for (const auto& [cell, up] : parent) {
    std::vector<int>& members = groups[find(cell)];
    for (int i = 0; i < corners; ++i)
      if (!tr.is_infinite(cell->vertex(i))) members.push_back(cell->vertex(i)->info());
  }
  for (auto& [root, members] : groups) {
    std::sort(members.begin(), members.end());
    members.erase(std::unique(members.begin(), members.end()), members.end());
    // Samples all on one sphere (the vertices of a sphere mesh) would make every two neighbours
    // and every clipping as long as the samples: such groups keep CGAL's triangulation, and the
    // verification reports it if the diagram then breaks.
    if (members.size() > kMostCosphericalSamples) continue;
    for (int a : members)
      for (int b : members)
        if (a != b) adjacency[a].push_back(b);
  }
  for (auto& list : adjacency) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return adjacency;
}

std::vector<std::vector<int>> delaunay_neighbours(const std::vector<Site>& sites) {
  using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
  using Tds = CGAL::Triangulation_data_structure_3<Vb, CGAL::Delaunay_triangulation_cell_base_3<K>>;
  using Dt = CGAL::Delaunay_triangulation_3<K, Tds>;
  std::vector<std::pair<K::Point_3, int>> points;
  for (const Site& s : sites) points.emplace_back(K::Point_3(s.p.x, s.p.y, s.p.z), s.id);
  const Dt dt(points.begin(), points.end());
  const auto oriented_sphere = K().side_of_oriented_sphere_3_object();
  return neighbours_of(dt, static_cast<int>(sites.size()), [&](typename Dt::Cell_handle c, typename Dt::Vertex_handle v) {
    if (dt.is_infinite(v)) return false;
    if (dt.dimension() == 2) return dt.side_of_circle(c, 3, v->point()) == CGAL::ON_BOUNDARY;
    if (dt.is_infinite(c)) return dt.side_of_sphere(c, v->point()) == CGAL::ON_BOUNDARY;
    return oriented_sphere(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(), c->vertex(3)->point(),
                           v->point()) == CGAL::ON_ORIENTED_BOUNDARY;
  });
}

std::vector<std::vector<int>> regular_neighbours(const std::vector<Site>& sites) {
  using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K, CGAL::Regular_triangulation_vertex_base_3<K>>;
  using Tds = CGAL::Triangulation_data_structure_3<Vb, CGAL::Regular_triangulation_cell_base_3<K>>;
  using Rt = CGAL::Regular_triangulation_3<K, Tds>;
  std::vector<std::pair<K::Weighted_point_3, int>> points;
  for (const Site& s : sites) points.emplace_back(K::Weighted_point_3(K::Point_3(s.p.x, s.p.y, s.p.z), s.w), s.id);
  const Rt rt(points.begin(), points.end());
  return neighbours_of(rt, static_cast<int>(sites.size()), [&](typename Rt::Cell_handle c, typename Rt::Vertex_handle v) {
    if (rt.is_infinite(v)) return false;
    if (rt.dimension() == 2) return rt.side_of_power_circle(c, 3, v->point()) == CGAL::ON_BOUNDARY;
    return rt.side_of_power_sphere(c, v->point()) == CGAL::ON_BOUNDARY;
  });
}

}  // namespace

Diagram compute_rvd(const SurfaceMesh& mesh, const Samples& samples, bool weighted) {
  check_diagram_input(mesh, samples, weighted);
  const auto start = std::chrono::steady_clock::now();
  Diagram d;
  d.kind = weighted ? DiagramKind::Rpd : DiagramKind::Rvd;
  d.sample_count = samples.size();
  d.sites = make_sites(samples, weighted);
  const SymbolicContext ctx = d.context(mesh);
  const auto adjacency = weighted ? regular_neighbours(d.sites) : delaunay_neighbours(d.sites);

  // Walk from a cell to the exact owner of point q: a neighbour closer to q is always there
  // unless the current cell owns q (Voronoi and power cells are convex).
  auto owner = [&](int i, const SymbolicVertex& q) {
    for (bool moved = true; moved;) {
      moved = false;
      for (int j : adjacency[i])
        if (side(q, i, j, ctx) == Sign::Negative) {
          i = j;
          moved = true;
          break;
        }
    }
    return i;
  };

  std::vector<SymbolicVertex> polygon, scratch;
  std::vector<int> visited_stamp(samples.size(), -1), stack;
  std::vector<std::pair<int, std::vector<SymbolicVertex>>> pieces;
  int start_cell = samples.size() > 0 ? 0 : -1;
  d.triangle_offsets.assign(1, 0);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    // Hidden sites of a power diagram have no neighbours; start from a site that has some.
    if (adjacency[start_cell].empty() && samples.size() > 1)
      for (int i = 0; i < samples.size(); ++i)
        if (!adjacency[i].empty()) { start_cell = i; break; }
    const std::uint64_t ties = thread_perturbations();
    start_cell = owner(start_cell, SymbolicVertex::mesh_vertex(tri[0]));
    pieces.clear();
    stack.assign(1, start_cell);
    visited_stamp[start_cell] = t;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      clip_triangle(mesh, t, i, adjacency[i].data(), static_cast<int>(adjacency[i].size()), ctx, polygon, scratch);
      if (polygon.empty()) continue;
      for (const SymbolicVertex& q : polygon)
        for (int a = 0; a < q.num_labels(); ++a) {
          const int j = q.label[a];
          if (visited_stamp[j] != t) {
            visited_stamp[j] = t;
            stack.push_back(j);
          }
        }
      pieces.emplace_back(i, polygon);
    }
    std::sort(pieces.begin(), pieces.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    // After an exact tie, the sides and areas of the unperturbed geometry (as the LRVD's).
    const bool tied = thread_perturbations() != ties;
    for (const auto& [cell, verts] : pieces) {
      const int n = static_cast<int>(verts.size());
      d.polygons.push_back({t, cell, static_cast<int>(d.vertices.size()), n});
      d.vertices.insert(d.vertices.end(), verts.begin(), verts.end());
      d.polygon_along.push_back(static_cast<unsigned char>(
          tied ? along_in_the_limit(verts.data(), n, tri, ctx) | (zero_area_unperturbed(verts.data(), n, ctx) ? kZeroAreaInTheLimit : 0)
               : polygon_edges(verts.data(), n, tri).along));
    }
    d.triangle_offsets.push_back(static_cast<int>(d.polygons.size()));
    ++d.stats.clipped_triangles;
  }
  d.stats.time_s = seconds_since(start);
  return d;
}

}  // namespace lrvd
