// CVT remeshing with repair of the dual by moving samples into under-sampled thin parts.
#include "remesh/remesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>

#include <fmt/format.h>

#include "common/error.h"
#include "mesh/closest_point.h"
#include "mesh/curvature.h"
#include "metrics/quality.h"
#include "metrics/self_intersections.h"
#include "voronoi/clip.h"


namespace lrvd {

namespace {

// Rounds of the third run without a better state after which the rings round the tip caps
// (DualDefects::tip_cap_rings) get the caps' lower density too, for the rest of the run.
constexpr int kRingLoweringAfter = 3;

// Cells that are not disks (more than one boundary loop: a ring around a thin tube; or an Euler
// characteristic V - E + F below 1: a handle inside the cell, smaller than it) and pairs of
// cells that share more than one boundary arc (paper Fig. 13): the dual is wrong there even when
// it looks like a manifold. Also, in `strips`, the pairs whose one shared arc runs from the mesh
// boundary to the mesh boundary through no triple point: across a strip narrower than the cells,
// where the dual has no edge between them. Boundary pieces are joined through their shared symbolic
// vertices.
void add_cell_topology_defects(const Diagram& diagram, const SurfaceMesh& mesh, std::set<int>& defect,
                               std::vector<std::pair<int, int>>& strips) {
  using Key = std::pair<int, int>;  // (cell, 0) for a cell's whole boundary, (i, j + 1) for arc i|j
  struct Piece {
    Key key;
    SymbolicVertex u, w;
  };
  std::vector<Piece> pieces;
  std::vector<SymbolicVertex> arc_ends_on_boundary;  // arc vertices on a boundary edge of the mesh
  std::unordered_map<SymbolicVertex, int, SymbolicVertexHash> ids;  // every polygon vertex, numbered
  auto id_of = [&](const SymbolicVertex& q) { return ids.try_emplace(q, static_cast<int>(ids.size())).first->second; };
  // Per cell, for its Euler characteristic: polygons, polygon edges shared with the cell's own
  // polygon across a mesh edge (each counted from both sides), the other edges, and (cell, vertex).
  const int cells = diagram.sample_count;
  std::vector<int> faces(cells, 0), inner_sides(cells, 0), outer_edges(cells, 0);
  std::vector<char> unknown_edge(cells, 0);
  std::vector<std::pair<int, int>> cell_vertices;
  for (const CellPolygon& poly : diagram.polygons) {
    const SymbolicVertex* v = diagram.polygon_vertices(poly);
    const Triangle& tri = mesh.triangle(poly.triangle);
    ++faces[poly.cell];
    for (int k = 0; k < poly.vertex_count; ++k) {
      const SymbolicVertex &u = v[k], &w = v[(k + 1) % poly.vertex_count];
      cell_vertices.push_back({poly.cell, id_of(u)});
      int other = -1;  // the neighbour cell across this edge, or -2 on the mesh boundary
      for (int e = 0; e < 3 && other == -1; ++e)
        if (u.on_mesh_edge(tri[e], tri[(e + 1) % 3]) && w.on_mesh_edge(tri[e], tri[(e + 1) % 3]))
          other = mesh.neighbor(poly.triangle, e) < 0 ? -2 : -3;
      if (other == -3) {  // inside the cell, across a mesh edge
        ++inner_sides[poly.cell];
        continue;
      }
      if (other == -1)
        for (int l : u.label)
          if (l >= 0 && l != poly.cell && w.has_label(l)) other = l;
      if (other == -1) {
        unknown_edge[poly.cell] = 1;
        continue;
      }
      ++outer_edges[poly.cell];
      pieces.push_back({{poly.cell, 0}, u, w});
      if (other >= 0 && poly.cell < other) {
        pieces.push_back({{poly.cell, other + 1}, u, w});
        for (const SymbolicVertex* q : {&u, &w})
          for (int e = 0; e < 3; ++e)
            if (q->type == SymbolicVertex::Type::B && mesh.neighbor(poly.triangle, e) < 0 &&
                q->on_mesh_edge(tri[e], tri[(e + 1) % 3]))
              arc_ends_on_boundary.push_back(*q);
      }
    }
  }
  // V - E + F of each cell: 1 for a disk, 0 for a ring, -1 for a disk with a handle in it.
  std::sort(cell_vertices.begin(), cell_vertices.end());
  cell_vertices.erase(std::unique(cell_vertices.begin(), cell_vertices.end()), cell_vertices.end());
  std::vector<int> euler(faces);
  for (const auto& [cell, vertex] : cell_vertices) ++euler[cell];
  for (int c = 0; c < cells; ++c) {
    euler[c] -= inner_sides[c] / 2 + outer_edges[c];
    if (faces[c] > 0 && !unknown_edge[c] && inner_sides[c] % 2 == 0 && euler[c] < 1) defect.insert(c);
  }
  // Count connected components per key with a union-find over the key's vertices: the pieces
  // sorted by key, the vertices numbered with the cells' ones.
  struct Link {
    Key key;
    int u, w;
    bool operator<(const Link& o) const { return key < o.key; }
  };
  // Grouped by cell (a counting sort), then each cell's few pieces sorted by key.
  std::vector<int> first_of_cell(diagram.sample_count + 1, 0);
  for (const Piece& p : pieces) ++first_of_cell[p.key.first + 1];
  for (int c = 0; c < diagram.sample_count; ++c) first_of_cell[c + 1] += first_of_cell[c];
  std::vector<Link> links(pieces.size());
  std::vector<int> next(first_of_cell.begin(), first_of_cell.end() - 1);
  for (const Piece& p : pieces) {
    const int u = id_of(p.u);
    links[next[p.key.first]++] = {p.key, u, id_of(p.w)};
  }
  // Per vertex id: 1 for a triple point (type C), 2 for an arc's end on the mesh boundary.
  std::vector<char> kind(ids.size(), 0);
  for (const auto& [q, id] : ids)
    if (q.type == SymbolicVertex::Type::C) kind[id] = 1;
  for (const SymbolicVertex& q : arc_ends_on_boundary) kind[ids.at(q)] = 2;
  for (int c = 0; c < diagram.sample_count; ++c)
    std::sort(links.begin() + first_of_cell[c], links.begin() + first_of_cell[c + 1]);
  std::vector<int> parent(ids.size(), -1);  // -1: not in the current key's forest
  std::vector<int> touched;
  auto root = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (size_t first = 0; first < links.size();) {
    size_t last = first;
    int components = 0;
    bool triple = false, boundary_end = false;
    for (; last < links.size() && links[last].key == links[first].key; ++last)
      for (int x : {links[last].u, links[last].w}) {
        if (parent[x] < 0) parent[x] = x, touched.push_back(x), ++components;
        triple = triple || kind[x] == 1;
        boundary_end = boundary_end || kind[x] == 2;
      }
    for (size_t k = first; k < last; ++k) {
      const int ra = root(links[k].u), rb = root(links[k].w);
      if (ra != rb) parent[ra] = rb, --components;
    }
    if (components > 1) {
      defect.insert(links[first].key.first);
      if (links[first].key.second > 0) defect.insert(links[first].key.second - 1);
    } else if (links[first].key.second > 0 && boundary_end && !triple) {
      strips.push_back({links[first].key.first, links[first].key.second - 1});
    }
    for (int x : touched) parent[x] = -1;
    touched.clear();
    first = last;
  }
}

// Vertices whose triangles form more than one fan (two triangles around v are in one fan when a
// chain of triangles sharing edges (v, x) joins them): the dual is pinched there, also where every
// edge has one or two triangles (an open mesh's dual, or a closed one's whose Euler characteristic
// happens to match).
void add_pinched_vertices(const DualMesh& dual, std::set<int>& defect) {
  // (v, x, triangle) for each edge (v, x) of each triangle, sorted: runs per v, then per x.
  struct Spoke {
    int v, x, t;
    bool operator<(const Spoke& o) const { return std::tie(v, x, t) < std::tie(o.v, o.x, o.t); }
  };
  std::vector<Spoke> spokes;
  spokes.reserve(6 * dual.triangles.size());
  for (int t = 0; t < static_cast<int>(dual.triangles.size()); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = dual.triangles[t][e], b = dual.triangles[t][(e + 1) % 3];
      spokes.push_back({a, b, t});
      spokes.push_back({b, a, t});
    }
  std::sort(spokes.begin(), spokes.end());
  std::vector<int> parent;  // union-find over the triangles around one vertex, by their index in `local`
  std::vector<int> local;
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (size_t i = 0, j; i < spokes.size(); i = j) {
    for (j = i; j < spokes.size() && spokes[j].v == spokes[i].v;) ++j;
    local.clear();
    for (size_t k = i; k < j; ++k) local.push_back(spokes[k].t);
    std::sort(local.begin(), local.end());
    local.erase(std::unique(local.begin(), local.end()), local.end());
    parent.resize(local.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto index = [&](int t) { return static_cast<int>(std::lower_bound(local.begin(), local.end(), t) - local.begin()); };
    int fans = static_cast<int>(local.size());
    for (size_t k = i + 1; k < j; ++k)
      if (spokes[k].x == spokes[k - 1].x) {
        const int a = find(index(spokes[k].t)), b = find(index(spokes[k - 1].t));
        if (a != b) parent[a] = b, --fans;
      }
    if (fans > 1) defect.insert(spokes[i].v);
  }
}

// Each boundary loop of the mesh comes back in the dual as a loop of boundary edges through the
// cells along it. A loop met by fewer than three cells is closed over (a hole inside one cell, or
// two cells meeting across it), and a cell that meets two loops joins them into one boundary of
// the dual: those cells are where to act when the Euler characteristic is wrong.
void add_closed_over_holes(const Diagram& diagram, const SurfaceMesh& mesh, std::set<int>& hints,
                           std::vector<int>& closed_over) {
  const auto& loops = mesh.boundary_loops();
  std::vector<int> loop_of(mesh.vertex_count(), -1);
  for (size_t l = 0; l < loops.size(); ++l)
    for (int v : loops[l]) loop_of[v] = static_cast<int>(l);
  std::vector<std::pair<int, int>> meets;  // (loop, cell)
  for (const CellPolygon& poly : diagram.polygons) {
    const Triangle& tri = mesh.triangle(poly.triangle);
    const SymbolicVertex* v = diagram.polygon_vertices(poly);
    for (int e = 0; e < 3; ++e) {
      if (mesh.neighbor(poly.triangle, e) >= 0) continue;
      const int a = tri[e], b = tri[(e + 1) % 3];
      for (int k = 0; k < poly.vertex_count; ++k)
        if (v[k].on_mesh_edge(a, b) && v[(k + 1) % poly.vertex_count].on_mesh_edge(a, b)) {
          meets.push_back({loop_of[a], poly.cell});
          break;
        }
    }
  }
  std::sort(meets.begin(), meets.end());
  meets.erase(std::unique(meets.begin(), meets.end()), meets.end());
  std::vector<int> loop_met(diagram.sample_count, -1);
  for (size_t i = 0, j; i < meets.size(); i = j) {
    for (j = i; j < meets.size() && meets[j].first == meets[i].first;) ++j;
    if (j - i < 3) closed_over.push_back(meets[i].first);
    for (size_t k = i; k < j; ++k) {
      const int cell = meets[k].second;
      if (j - i < 3) hints.insert(cell);
      if (loop_met[cell] >= 0 && loop_met[cell] != meets[i].first) hints.insert(cell);
      loop_met[cell] = meets[i].first;
    }
  }
}

}  // namespace

DualDefects find_dual_defects(const DualMesh& dual, const Diagram& diagram, const SurfaceMesh& mesh,
                              const Samples& samples, bool input_closed, const InputCrossings& inherited) {
  // Each edge and each vertex triple with its count, as runs of a sorted list.
  std::vector<std::pair<int, int>> edge_list;
  std::vector<Triangle> vertex_sets;
  edge_list.reserve(3 * dual.triangles.size());
  vertex_sets.reserve(dual.triangles.size());
  for (const Triangle& t : dual.triangles) {
    for (int e = 0; e < 3; ++e) edge_list.push_back({std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3])});
    Triangle sorted = t;
    std::sort(sorted.begin(), sorted.end());
    vertex_sets.push_back(sorted);
  }
  std::sort(edge_list.begin(), edge_list.end());
  std::sort(vertex_sets.begin(), vertex_sets.end());
  std::set<int> defect;
  int edges = 0;
  for (size_t i = 0, j; i < edge_list.size(); i = j, ++edges) {
    for (j = i + 1; j < edge_list.size() && edge_list[j] == edge_list[i];) ++j;
    const size_t count = j - i;
    if (count > 2 || (count == 1 && input_closed)) defect.insert({edge_list[i].first, edge_list[i].second});
  }
  for (size_t i = 0, j; i < vertex_sets.size(); i = j) {
    for (j = i + 1; j < vertex_sets.size() && vertex_sets[j] == vertex_sets[i];) ++j;
    if (j - i > 1) defect.insert(vertex_sets[i].begin(), vertex_sets[i].end());
  }
  for (int t : dual.merged_into) defect.insert(dual.triangles[t].begin(), dual.triangles[t].end());
  add_pinched_vertices(dual, defect);
  std::set<int> hints;
  std::vector<std::pair<int, int>> strips;
  add_cell_topology_defects(diagram, mesh, hints, strips);
  std::vector<int> closed_over;
  if (!input_closed) add_closed_over_holes(diagram, mesh, hints, closed_over);
  // The dual's Euler characteristic against the mesh's: a manifold dual can still have lost a
  // handle (a cell wrapping a tube) or a hole of an open mesh (a cell around it), which only the
  // cell-topology hints locate.
  const bool euler_ok = static_cast<int>(dual.positions.size()) - edges + static_cast<int>(dual.triangles.size()) ==
                        mesh.euler_characteristic();
  // A sample in no triangle: its cell meets fewer than two others at a triple point (an island).
  std::vector<char> used(dual.positions.size(), 0);
  for (const Triangle& t : dual.triangles)
    for (int v : t) used[v] = 1;
  for (size_t i = 0; i < used.size(); ++i)
    if (!used[i]) defect.insert(static_cast<int>(i));
  // Unused samples whose disk cells meet one other cell: cornered when they meet the boundary of an
  // open mesh, tip caps when they hold more than π of angle deficit. (A row of unused cells across
  // a strip narrower than the cells, each with two neighbours, needs more samples, not fewer.) A
  // cell at a defect that meets exactly two others and no boundary is a tip cap too when it holds
  // that much: the two share two arcs round it, and its two triangles repeat each other.
  std::vector<int> cornered, tip_caps, tip_cap_rings;
  if (!defect.empty()) {  // unused samples are among the defects
    std::vector<char> at_defect(used.size(), 0), on_boundary(used.size(), 0);
    for (int i : defect) at_defect[i] = 1;
    struct Neighbours {
      int first = -1, second = -1;
      bool more = false;
      int count() const { return more ? 3 : (first >= 0) + (second >= 0); }
    };
    std::vector<Neighbours> neighbours(used.size());
    for (const CellPolygon& poly : diagram.polygons) {
      if (!at_defect[poly.cell]) continue;
      const SymbolicVertex* v = diagram.polygon_vertices(poly);
      Neighbours& n = neighbours[poly.cell];
      for (int k = 0; k < poly.vertex_count; ++k)
        for (int a = 0; a < v[k].num_labels(); ++a) {
          const int l = v[k].label[a];
          if (l == poly.cell || l == n.first || l == n.second) continue;
          if (n.first < 0)
            n.first = l;
          else if (n.second < 0)
            n.second = l;
          else
            n.more = true;
        }
      const unsigned along = polygon_edges(v, poly.vertex_count, mesh.triangle(poly.triangle)).along;
      for (int e = 0; e < 3; ++e)
        if ((along >> e & 1u) && mesh.neighbor(poly.triangle, e) < 0) on_boundary[poly.cell] = 1;
    }
    std::vector<int> capped;  // candidates: no boundary, one neighbour (unused) or two (at a defect)
    for (int i = 0; i < static_cast<int>(used.size()); ++i) {
      const int count = neighbours[i].count();
      if (used[i]) {
        if (at_defect[i] && count == 2 && !on_boundary[i]) capped.push_back(i);
        continue;
      }
      if (hints.count(i) || count > 1) continue;
      if (on_boundary[i] && !input_closed)
        cornered.push_back(i);
      else if (!on_boundary[i] && count == 1)
        capped.push_back(i);
    }
    if (!capped.empty()) {
      // The mesh vertices inside each candidate's cell (corners of its polygons), each counted once.
      const std::vector<double> deficit = angle_deficits(mesh);
      std::vector<char> candidate(used.size(), 0);
      for (int i : capped) candidate[i] = 1;
      std::vector<std::pair<int, int>> inside;
      for (const CellPolygon& poly : diagram.polygons) {
        if (!candidate[poly.cell]) continue;
        const SymbolicVertex* v = diagram.polygon_vertices(poly);
        for (int k = 0; k < poly.vertex_count; ++k)
          if (v[k].type == SymbolicVertex::Type::A) inside.push_back({poly.cell, v[k].v[0]});
      }
      std::sort(inside.begin(), inside.end());
      inside.erase(std::unique(inside.begin(), inside.end()), inside.end());
      std::vector<double> gathered(used.size(), 0.0);
      for (const auto& [cell, vertex] : inside) gathered[cell] += deficit[vertex];
      for (int i : capped)
        if (gathered[i] > M_PI) {
          tip_caps.push_back(i);
          for (const int n : {neighbours[i].first, neighbours[i].second})
            if (n >= 0 && hints.count(n)) tip_cap_rings.push_back(n);
        }
    }
  }
  // Two used cells that meet across a strip narrower than them: the dual lacks their edge and comes
  // apart there (an unused one is a topological defect already, and maybe cornered).
  for (const auto& [i, j] : strips)
    if (used[i] && used[j]) hints.insert({i, j});
  // Triangles that cut through each other (nearby sheets sampled too coarsely).
  const std::vector<char> testable = proper_triangles(dual.positions, dual.triangles);
  std::set<int> crossing;
  const auto pairs = find_self_intersections(dual.positions, dual.triangles, testable);
  for (const auto& [s, t] : pairs) {
    if (inherited.inherited(samples, dual.triangles[s], dual.triangles[t])) continue;
    crossing.insert(dual.triangles[s].begin(), dual.triangles[s].end());
    crossing.insert(dual.triangles[t].begin(), dual.triangles[t].end());
  }
  DualDefects out;
  out.topological.assign(defect.begin(), defect.end());
  out.crossing.assign(crossing.begin(), crossing.end());
  out.cell_topology.assign(hints.begin(), hints.end());
  out.cornered = std::move(cornered);
  out.tip_caps = std::move(tip_caps);
  std::sort(tip_cap_rings.begin(), tip_cap_rings.end());
  tip_cap_rings.erase(std::unique(tip_cap_rings.begin(), tip_cap_rings.end()), tip_cap_rings.end());
  out.tip_cap_rings = std::move(tip_cap_rings);
  out.closed_over_loops = std::move(closed_over);
  out.euler_ok = euler_ok;
  out.crossing_pairs = pairs;
  return out;
}

namespace {

// Per cell: 1 for the defect cells, 2 for the cells that share a diagram vertex with one, else 0.
std::vector<char> defect_neighbourhood(const Diagram& diagram, const std::vector<int>& defect) {
  std::vector<char> involved(diagram.sample_count, 0);
  for (int i : defect) involved[i] = 1;
  for (const SymbolicVertex& q : diagram.vertices)
    for (int a = 0; a < q.num_labels(); ++a)
      if (involved[q.label[a]] == 1)
        for (int b = 0; b < q.num_labels(); ++b)
          if (!involved[q.label[b]]) involved[q.label[b]] = 2;
  return involved;
}

// Multiplies the density on the triangles of the defect cells and of their neighbours, so that the
// CVT draws more samples into the thin part they wrap. Returns how many triangles it raised: all of
// them when every cell is at a defect or next to one, which leaves the CVT as it was (its energy
// and gradient only scale).
std::size_t raise_density(const Diagram& diagram, const std::vector<int>& defect, double factor,
                          std::vector<double>& density) {
  const std::vector<char> involved = defect_neighbourhood(diagram, defect);
  std::vector<char> raised(density.size(), 0);
  std::size_t count = 0;
  for (const CellPolygon& poly : diagram.polygons)
    if (involved[poly.cell] && !raised[poly.triangle]) {
      raised[poly.triangle] = 1;
      density[poly.triangle] *= factor;
      ++count;
    }
  return count;
}

// Divides the density on the triangles of the given cells (their own, not their neighbours'), so
// that the CVT makes those cells larger.
void lower_density(const Diagram& diagram, const std::vector<int>& cells, double factor, std::vector<double>& density) {
  std::vector<char> lowered_cell(diagram.sample_count, 0), lowered(density.size(), 0);
  for (int c : cells) lowered_cell[c] = 1;
  for (const CellPolygon& poly : diagram.polygons)
    if (lowered_cell[poly.cell] && !lowered[poly.triangle]) {
      lowered[poly.triangle] = 1;
      density[poly.triangle] /= factor;
    }
}

// Moves samples into the defect cells: for each one, the sample of the lightest cell away from
// every defect (from a component that keeps more than the fewest vertices its topology needs) goes
// to the point of the defect cell farthest from its sample (across the tube a ring cell wraps,
// the tip a cap cell covers). A raised density draws samples into a thin part only as far as a
// CVT round carries them; this brings them there at once, also from another component. Returns
// how many samples moved.
int relocate_samples(const Diagram& diagram, const SurfaceMesh& mesh, const std::vector<double>& density,
                     const std::vector<int>& defect, Samples& samples) {
  const int n = samples.size();
  const std::vector<char> involved = defect_neighbourhood(diagram, defect);
  const std::vector<int>& component = mesh.triangle_components();
  auto component_of = [&](int sample) { return component[samples.triangles[sample]]; };
  std::vector<int> count(mesh.component_count(), 0);
  for (int i = 0; i < n; ++i) ++count[component_of(i)];
  const std::vector<int> fewest = mesh.minimum_vertex_counts();
  const CellIntegrals cells = integrate_cells(diagram, mesh, samples, &density);
  std::vector<int> donors;
  for (int i = 0; i < n; ++i)
    if (!involved[i]) donors.push_back(i);
  std::sort(donors.begin(), donors.end(), [&](int a, int b) { return std::tie(cells.area[a], a) < std::tie(cells.area[b], b); });
  struct Farthest {
    double d2 = -1;
    Vec3 p;
    int triangle = -1;
  };
  std::vector<Farthest> far(n);
  const SymbolicContext ctx = diagram.context(mesh);
  for (const CellPolygon& poly : diagram.polygons) {
    if (involved[poly.cell] != 1) continue;
    const SymbolicVertex* v = diagram.polygon_vertices(poly);
    for (int k = 0; k < poly.vertex_count; ++k) {
      const Vec3 p = position(v[k], ctx);
      const double d2 = squared_distance(p, samples.positions[poly.cell]);
      if (d2 > far[poly.cell].d2) far[poly.cell] = {d2, p, poly.triangle};
    }
  }
  std::vector<int> targets(defect);
  std::sort(targets.begin(), targets.end());
  targets.erase(std::unique(targets.begin(), targets.end()), targets.end());
  int moved = 0;
  size_t next = 0;
  std::vector<Vec3> placed;  // two defect cells may share their farthest point (a vertex of both)
  for (int d : targets) {
    if (far[d].triangle < 0 || std::find(placed.begin(), placed.end(), far[d].p) != placed.end()) continue;
    placed.push_back(far[d].p);
    while (next < donors.size() && count[component_of(donors[next])] <= fewest[component_of(donors[next])]) ++next;
    if (next == donors.size()) break;
    const int s = donors[next++];
    --count[component_of(s)];
    const Triangle& tri = mesh.triangle(far[d].triangle);
    const ClosestPoint c = closest_point_on_triangle(far[d].p, mesh.position(tri[0]), mesh.position(tri[1]), mesh.position(tri[2]));
    samples.positions[s] = c.point;
    samples.triangles[s] = far[d].triangle;
    samples.barycentric[s] = c.barycentric;
    ++count[component[far[d].triangle]];
    ++moved;
  }
  return moved;
}

// When a defect sample of `kept` lies on a component that holds at most one sample more than its
// topology needs in `start` (the samples the runs began from), moves two samples onto every such
// component of `start`: each from the component with the most samples above its fewest (which
// keeps at least two above), its highest-index one, to the centroid of the receiving component's
// triangle farthest from that component's samples. Returns how many samples moved (0: no defect
// there, one component, or none to spare).
int add_samples_to_starved_components(const SurfaceMesh& mesh, const Samples& kept, const std::vector<int>& defect,
                                      Samples& start) {
  constexpr int kMargin = 2;
  const int components = mesh.component_count();
  if (components < 2) return 0;
  const std::vector<int>& component = mesh.triangle_components();
  const std::vector<int> fewest = mesh.minimum_vertex_counts();
  std::vector<int> count(components, 0);
  for (int t : start.triangles) ++count[component[t]];
  // Any defect on such a component: every such component gets the margin (the others' samples
  // move too, so a component spared now may fail next).
  const bool defect_on_starved = std::any_of(defect.begin(), defect.end(), [&](int s) {
    const int c = component[kept.triangles[s]];
    return count[c] <= fewest[c] + 1;
  });
  if (!defect_on_starved) return 0;
  std::vector<int> starved;
  for (int c = 0; c < components; ++c)
    if (count[c] <= fewest[c] + 1) starved.push_back(c);
  std::vector<char> is_starved(components, 0);
  for (int c : starved) is_starved[c] = 1;
  std::vector<std::vector<int>> triangles_of(components);
  for (int t = 0; t < mesh.triangle_count(); ++t)
    if (is_starved[component[t]]) triangles_of[component[t]].push_back(t);
  const auto centroid = [&](int t) {
    const Triangle& tri = mesh.triangle(t);
    return (mesh.position(tri[0]) + mesh.position(tri[1]) + mesh.position(tri[2])) / 3.0;
  };
  int moved = 0;
  for (int c : starved)
    for (int k = 0; k < kMargin; ++k) {
      int donor = -1;
      for (int d = 0; d < components; ++d)
        if (!is_starved[d] && count[d] - 1 >= fewest[d] + kMargin &&
            (donor < 0 || count[d] - fewest[d] > count[donor] - fewest[donor]))
          donor = d;
      if (donor < 0) return moved;
      int sample = start.size() - 1;
      while (component[start.triangles[sample]] != donor) --sample;
      // The farthest triangle centroid of c from c's samples (distances to the nearest one); c holds
      // a few samples, so they are gathered first.
      std::vector<Vec3> own;
      for (int s = 0; s < start.size(); ++s)
        if (component[start.triangles[s]] == c) own.push_back(start.positions[s]);
      double best = -1;
      int best_triangle = -1;
      for (int t : triangles_of[c]) {
        const Vec3 p = centroid(t);
        double nearest = std::numeric_limits<double>::infinity();
        for (const Vec3& q : own) nearest = std::min(nearest, squared_distance(p, q));
        if (nearest > best) best = nearest, best_triangle = t;
      }
      if (!(best > 0)) break;  // every centroid holds a sample already: no place left for another
      start.positions[sample] = centroid(best_triangle);
      start.triangles[sample] = best_triangle;
      start.barycentric[sample] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
      --count[donor];
      ++count[c];
      ++moved;
    }
  return moved;
}

// Another run's result replaces `result` when it leaves fewer defects; the counters of work done
// (rounds, iterations, diagrams) cover both either way.
void keep_if_fewer(RemeshResult again, DualDefects again_defects, RemeshResult& result, DualDefects& defects) {
  again.repair_rounds += result.repair_rounds;
  again.total_iterations += result.total_iterations;
  again.diagram_evaluations += result.diagram_evaluations;
  if (again_defects.fewer_than(defects)) {
    result = std::move(again);
    defects = std::move(again_defects);
  } else {
    result.repair_rounds = again.repair_rounds;
    result.total_iterations = again.total_iterations;
    result.diagram_evaluations = again.diagram_evaluations;
  }
}

}  // namespace

std::string DualDefects::describe() const {
  if (empty()) return "no defect";
  std::vector<std::string> parts;
  auto count = [](size_t n, const char* noun) { return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s"); };
  if (!topological.empty()) parts.push_back(count(topological.size(), "sample") + " at topological defects");
  if (!crossing.empty()) parts.push_back(fmt::format("{} at crossing triangles", crossing.size()));
  if (!euler_ok)
    parts.push_back(fmt::format("the wrong Euler characteristic ({} {})", count(cell_topology.size(), "cell"),
                                cell_topology.size() == 1 ? "not a disk or sharing two arcs"  // a strip flags two
                                                           : "not disks, sharing two arcs or meeting across a strip"));
  std::string out = parts[0];
  for (size_t k = 1; k < parts.size(); ++k) out += ", " + parts[k];
  return out;
}

RemeshResult remesh_cvt(const SurfaceMesh& reference, const SurfaceMesh& mesh, const Samples& initial,
                        const RemeshOptions& options) {
  require_workable_model(reference, "remeshing");
  require_workable_model(mesh, "remeshing");
  require_remesh_vertex_count(reference, initial.size());
  if (mesh.component_count() != reference.component_count() ||
      mesh.euler_characteristic() != reference.euler_characteristic() ||
      mesh.boundary_loops().size() != reference.boundary_loops().size())
    throw InputError(fmt::format("remesh_cvt: the mesh ({} components, Euler characteristic {}, {} boundary loops) is "
                                 "not a refinement of the reference ({}, {}, {})",
                                 mesh.component_count(), mesh.euler_characteristic(), mesh.boundary_loops().size(),
                                 reference.component_count(), reference.euler_characteristic(),
                                 reference.boundary_loops().size()));
  if (!(options.ease_fraction >= 0 && options.ease_fraction <= 1) || options.ease_iterations < 0)
    throw InputError(fmt::format("remesh options: ease_fraction ({}) must be in [0, 1] and ease_iterations ({}) not negative",
                                 options.ease_fraction, options.ease_iterations));
  if (options.repair_rounds < 0 || options.repair_iterations < 1 || options.polish_steps < 0)
    throw InputError(fmt::format("remesh options: repair_rounds ({}) and polish_steps ({}) may not be negative, and "
                                 "repair_iterations ({}) must be at least 1",
                                 options.repair_rounds, options.polish_steps, options.repair_iterations));
  if (options.relax.rounds < 0 || options.relax.worst_triangles < 0)
    throw InputError(fmt::format("remesh options: the relaxation's rounds ({}) and worst_triangles ({}) may not be negative",
                                 options.relax.rounds, options.relax.worst_triangles));
  if (!(options.repair_factor > 1) || !std::isfinite(options.repair_factor))
    throw InputError(fmt::format("remesh options: the repair factor must be a number above 1 (got {})",
                                 options.repair_factor));
  const auto start = std::chrono::steady_clock::now();
  // On the CVT's mesh, whose components the samples' triangles name (the reference's cross alike).
  const InputCrossings inherited(mesh);
  const ClosestPointIndex index(mesh);  // one for every CVT and repair round
  auto progress = [&](const std::string& message) {
    if (options.on_progress) options.on_progress(message);
  };
  // A dual whose only defect is crossings is fitted and untangled; the crossings left, if any, are
  // the ones to act on.
  auto settle = [&](RemeshResult& r, DualDefects& d) {
    if (!options.untangle || !d.topological.empty() || !d.euler_ok || d.crossing.empty()) return;
    // The crossings found in `d` (and then by the fitting) are not searched for again.
    if (options.fit) r.fit = fit_to_surface(r.cvt.diagram, mesh, r.dual, options.fit_options, &index, &d.crossing_pairs);
    r.untangled_from = r.dual;
    r.untangle = untangle_crossings(mesh, r.cvt.samples, r.dual, inherited, options.untangle_options,
                                    options.fit ? &r.fit.crossings : &d.crossing_pairs);
    r.fitted = true;
    std::set<int> left;
    for (const auto& [s, t] : r.untangle.remaining)
      for (int u : {s, t}) left.insert(r.dual.triangles[u].begin(), r.dual.triangles[u].end());
    d.crossing.assign(left.begin(), left.end());
  };
  // The first CVT, then rounds that raise the density where the worst kind of defect is (topology
  // first, crossings next); the state with the fewest defects is the result, with the counters of
  // the whole run.
  // `saw_tip_caps` is set when some round's dual had a cap on a sharp tip. The third run starts from
  // the second's first CVT (the same samples, options and result), kept here, not computed again.
  struct Start {
    RemeshResult result;
    DualDefects defects;
  };
  std::optional<Start> sheets_start;
  // Runs tried, and those that stopped at a round that would have raised the density everywhere.
  int runs = 0, saturated_runs = 0;
  auto optimise_and_repair = [&](const Samples& start_samples, bool keep_to_sheets, bool lower_tip_caps,
                                 DualDefects& best_defects, bool& saw_tip_caps) {
    ++runs;
    CvtOptions first = options.cvt;
    first.keep_to_sheets = keep_to_sheets;
    RemeshResult result;
    DualDefects defects;
    if (keep_to_sheets && sheets_start) {
      result = sheets_start->result;
      defects = sheets_start->defects;
      result.total_iterations = result.diagram_evaluations = 0;  // the counters count work done
    } else {
      result.cvt = optimize_cvt(mesh, start_samples, first, nullptr, &index);
      result.total_iterations = result.cvt.iterations;
      result.diagram_evaluations = result.cvt.diagram_evaluations;
      result.dual = compute_dual(result.cvt.diagram, mesh, result.cvt.samples);
      defects = find_dual_defects(result.dual, result.cvt.diagram, mesh, result.cvt.samples, reference.is_closed(), inherited);
      settle(result, defects);
      if (keep_to_sheets && options.tip_caps_retry) sheets_start = Start{result, defects};
    }
    CvtOptions again = first;
    again.iterations = options.repair_iterations;
    again.lloyd_warmup = 1;
    if (again.triangle_density.empty())
      again.triangle_density = options.cvt.density == CvtDensity::Curvature
                                   ? curvature_density(mesh, initial.size())
                                   : std::vector<double>(mesh.triangle_count(), 1.0);
    const std::vector<double> base_density = again.triangle_density;  // before any round changes it
    progress(fmt::format("{}CVT: {} iterations, {} diagrams, energy {:.6g}; the dual has {}",
                         lower_tip_caps ? "third run, from the second's first " : keep_to_sheets ? "second run, " : "",
                         result.cvt.iterations, result.cvt.diagram_evaluations, result.cvt.energy, defects.describe()));
    RemeshResult best = result;
    best_defects = defects;
    std::vector<double> best_density = first.triangle_density;
    int rounds_without_progress = 0;  // since the best state so far
    bool lower_rings = false;         // the third run's caps stalled: their rings are lowered from then on
    // Rounds end when nothing is left to repair, or when no cell is known to act on (a wrong Euler
    // characteristic that no defect finder locates).
    for (int round = 0; round < options.repair_rounds && !defects.empty() && !defects.where_to_act().empty(); ++round) {
      // Cornered cells get a lower density, the other defects a higher one; so do caps on sharp
      // tips in the third run (before it they are left to the raise, which keeps more of the tip:
      // lowered from the first run, triceratops 1000's Hausdorff distance went 0.47 -> 2.11 %).
      // Both are topological defects, which are acted on first.
      saw_tip_caps = saw_tip_caps || !defects.tip_caps.empty();
      std::vector<int> lowered = defects.cornered;
      if (lower_tip_caps) {
        lowered.insert(lowered.end(), defects.tip_caps.begin(), defects.tip_caps.end());
        // No better state for kRingLoweringAfter rounds: from then on the rings round the caps
        // are lowered too, so a cap can take the narrowing part below it (a larger cap).
        lower_rings = lower_rings || rounds_without_progress >= kRingLoweringAfter;
        if (lower_rings) lowered.insert(lowered.end(), defects.tip_cap_rings.begin(), defects.tip_cap_rings.end());
        std::sort(lowered.begin(), lowered.end());
        lowered.erase(std::unique(lowered.begin(), lowered.end()), lowered.end());
      }
      std::vector<int> raised;
      if (lowered.empty())
        raised = defects.where_to_act();
      else
        std::set_difference(defects.topological.begin(), defects.topological.end(), lowered.begin(), lowered.end(),
                            std::back_inserter(raised));
      if (!lowered.empty()) lower_density(result.cvt.diagram, lowered, options.repair_factor, again.triangle_density);
      const std::size_t raised_triangles =
          raised.empty() ? 0 : raise_density(result.cvt.diagram, raised, options.repair_factor, again.triangle_density);
      // Every cell at a defect or next to one, and none lowered: the surface is thinner than the
      // cells (or has more handles than they can hold) everywhere, which only more vertices mend.
      // (`again` is not used after the loop: the density raised here goes with the run.)
      if (lowered.empty() && raised_triangles == again.triangle_density.size()) {
        ++saturated_runs;
        progress(fmt::format("repair round {}: every cell is at a defect or next to one, and a density raised "
                             "everywhere changes nothing: the run stops",
                             round + 1));
        break;
      }
      ++result.repair_rounds;
      progress(lowered.empty()
                   ? fmt::format("repair round {} of {}: density x{} around {} samples and their neighbours", round + 1,
                                 options.repair_rounds, options.repair_factor, raised.size())
                   : fmt::format("repair round {} of {}: density x{} around {} samples and their neighbours, /{} in "
                                 "{} cells at sharp corners or tips",
                                 round + 1, options.repair_rounds, options.repair_factor, raised.size(),
                                 options.repair_factor, lowered.size()));
      // The second run also moves samples into the defect cells (the first, whose raised density
      // suffices on the 20 rows of docs/results.md, leaves them to the CVT: moving them there too
      // took elk 516 to Qmin 0.554, docs/decisions.md); not into the cells that are to grow.
      const bool moved = keep_to_sheets && !raised.empty() &&
                         relocate_samples(result.cvt.diagram, mesh, again.triangle_density, raised, result.cvt.samples) > 0;
      // The diagram of the samples is the last one computed: the density changed, the diagram not.
      result.cvt = optimize_cvt(mesh, result.cvt.samples, again, moved ? nullptr : &result.cvt.diagram, &index);
      result.total_iterations += result.cvt.iterations;
      result.diagram_evaluations += result.cvt.diagram_evaluations;
      result.dual = compute_dual(result.cvt.diagram, mesh, result.cvt.samples);
      defects = find_dual_defects(result.dual, result.cvt.diagram, mesh, result.cvt.samples, reference.is_closed(), inherited);
      result.fitted = false;
      result.fit = {};
      result.untangle = {};
      settle(result, defects);
      progress(fmt::format("repair round {}: {} iterations, energy {:.6g}; the dual has {}", round + 1,
                           result.cvt.iterations, result.cvt.energy, defects.describe()));
      if (defects.fewer_than(best_defects)) {
        best_defects = defects;
        best = result;
        best_density = again.triangle_density;
        rounds_without_progress = 0;
      } else {
        ++rounds_without_progress;
      }
    }
    // A state without defects gets its Lloyd steps (RemeshOptions::polish_steps), with the density
    // it was optimised for; they stand if its dual still has no defect. A state whose crossings
    // were untangled (settle) is kept as it is.
    const bool clean = best_defects.empty() && !best.fitted;
    auto polish = [&](RemeshResult& state, const std::vector<double>& density) {
      if (options.polish_steps == 0 || first.optimizer != CvtOptimizer::Lbfgs) return;
      CvtOptions lloyd = first;
      lloyd.optimizer = CvtOptimizer::Lloyd;
      lloyd.iterations = options.polish_steps;
      lloyd.triangle_density = density;
      CvtResult polished = optimize_cvt(mesh, state.cvt.samples, lloyd, &state.cvt.diagram, &index);
      result.total_iterations += polished.iterations;
      result.diagram_evaluations += polished.diagram_evaluations;
      DualMesh dual = compute_dual(polished.diagram, mesh, polished.samples);
      DualDefects after = find_dual_defects(dual, polished.diagram, mesh, polished.samples, reference.is_closed(), inherited);
      progress(fmt::format("{} Lloyd step{} on the samples: the dual has {}{}", polished.iterations,
                           polished.iterations == 1 ? "" : "s", after.describe(),
                           after.empty() ? "" : ", the state before them stands"));
      if (!after.empty()) return;
      // The kept CVT is the run and its polish: its history, iterations and evaluations cover both.
      polished.energy_history.insert(polished.energy_history.begin(), state.cvt.energy_history.begin(),
                                     state.cvt.energy_history.end() - 1);
      polished.iterations += state.cvt.iterations;
      polished.diagram_evaluations += state.cvt.diagram_evaluations;
      polished.line_search_stopped = state.cvt.line_search_stopped;
      polished.time_s += state.cvt.time_s;
      state.cvt = std::move(polished);
      state.dual = std::move(dual);
      state.polished = true;
    };
    if (clean) polish(best, best_density);
    // A state the repair rounds left without defects is optimised again with the raised density
    // eased part of the way back (RemeshOptions::ease_iterations), and takes its Lloyd steps too;
    // it stands if its dual has no defect and a better worst triangle than the state before.
    if (clean && options.ease_iterations > 0 && result.repair_rounds > 0 && best_density.size() == base_density.size()) {
      CvtOptions eased = again;
      eased.iterations = options.ease_iterations;
      for (std::size_t t = 0; t < base_density.size(); ++t)
        eased.triangle_density[t] = base_density[t] * std::pow(best_density[t] / base_density[t], 1 - options.ease_fraction);
      CvtResult eased_cvt = optimize_cvt(mesh, best.cvt.samples, eased, &best.cvt.diagram, &index);
      // The candidate is `best` with the eased CVT: copied with its CVT moved out, and back.
      CvtResult best_cvt = std::move(best.cvt);
      RemeshResult candidate = best;
      best.cvt = std::move(best_cvt);
      candidate.cvt = std::move(eased_cvt);
      candidate.polished = false;
      result.total_iterations += candidate.cvt.iterations;
      result.diagram_evaluations += candidate.cvt.diagram_evaluations;
      candidate.dual = compute_dual(candidate.cvt.diagram, mesh, candidate.cvt.samples);
      const DualDefects after =
          find_dual_defects(candidate.dual, candidate.cvt.diagram, mesh, candidate.cvt.samples, reference.is_closed(),
                            inherited);
      progress(fmt::format("{} iterations with the density eased {}% of the way back: the dual has {}{}",
                           candidate.cvt.iterations, std::lround(100 * options.ease_fraction), after.describe(),
                           after.empty() ? "" : ", the state before them stands"));
      if (after.empty()) {
        polish(candidate, eased.triangle_density);
        const double q_before = shape_metrics(best.dual.positions, best.dual.triangles).q_min;
        const double q_after = shape_metrics(candidate.dual.positions, candidate.dual.triangles).q_min;
        const bool better = q_after > q_before;
        progress(better ? fmt::format("the eased state: worst triangle {:.3f} -> {:.3f}, kept", q_before, q_after)
                        : fmt::format("the eased state: worst triangle {:.3f}, not above {:.3f}: the state before stands",
                                      q_after, q_before));
        if (better) {
          // The history, iterations and evaluations of the kept CVT cover the state it started from.
          std::vector<double>& history = candidate.cvt.energy_history;
          history.insert(history.begin(), best.cvt.energy_history.begin(), best.cvt.energy_history.end() - 1);
          candidate.cvt.iterations += best.cvt.iterations;
          candidate.cvt.diagram_evaluations += best.cvt.diagram_evaluations;
          candidate.cvt.time_s += best.cvt.time_s;
          candidate.eased = true;
          best = std::move(candidate);
        }
      }
    }
    best.repair_rounds = result.repair_rounds;
    best.total_iterations = result.total_iterations;
    best.diagram_evaluations = result.diagram_evaluations;
    return best;
  };
  // The first run from `start`, then the second and third when defects are left.
  auto run_from = [&](const Samples& start, DualDefects& defects) {
    sheets_start.reset();
    bool first_saw_tip_caps = false;  // unused: the third run repeats the second, not the first
    RemeshResult result = optimise_and_repair(start, false, false, defects, first_saw_tip_caps);
    bool saw_tip_caps = false;  // in the second run: the third differs from it only from such a round on
    // Runs the whole loop again and keeps it if it ends with fewer defects; the counters cover every run.
    auto retry = [&](bool keep_to_sheets, bool lower_tip_caps, bool& saw) {
      DualDefects again_defects;
      RemeshResult again = optimise_and_repair(start, keep_to_sheets, lower_tip_caps, again_defects, saw);
      again.kept_to_sheets = keep_to_sheets;
      again.tip_caps_lowered = lower_tip_caps;
      keep_if_fewer(std::move(again), std::move(again_defects), result, defects);
    };
    // Defects left: the whole run again with every sample kept to its own sheet (the centroid of a
    // cell wrapping a thin wall lies in the wall or in the gap beside it, and the closest point of the
    // surface to it is often on the other side: samples drain from one side to the other there).
    if (!defects.empty() && options.keep_to_sheets_retry) {
      progress(fmt::format("defects left after {} rounds: the run again with every sample kept to its own sheet",
                           result.repair_rounds));
      retry(true, false, saw_tip_caps);
    }
    // Defects left, and caps on sharp tips among them at some round: a third run that lowers the
    // density on those caps.
    if (!defects.empty() && saw_tip_caps && options.keep_to_sheets_retry && options.tip_caps_retry) {
      progress(fmt::format("defects left after {} rounds, caps on sharp tips among them: the second run again with "
                           "a lower density on those caps",
                           result.repair_rounds));
      bool ignored = false;
      retry(true, true, ignored);
    }
    return result;
  };
  DualDefects defects;
  RemeshResult result = run_from(initial, defects);
  // Defects left on a component that holds no more samples than its topology needs, or one more (a
  // CVT of four samples on an elongated part is a chain of ring cells, not a tetrahedron): the runs
  // again with two more samples on every such component, taken from the components with the most
  // to spare (CGAL's bones at 200: 32 samples onto 16 of its 26 bones). Samples do not change
  // components otherwise, but for the second run's moves. One defect there is enough: the other
  // components' CVTs change too, so one spared now may fail in the new runs.
  if (!defects.empty() && options.reallocation_retry) {
    Samples moved = initial;
    const int added = add_samples_to_starved_components(mesh, result.cvt.samples, defects.where_to_act(), moved);
    if (added > 0) {
      progress(fmt::format("defects left after {} rounds on a component holding the fewest samples its topology "
                           "needs or one more: the runs again from the start, {} samples moved onto such components",
                           result.repair_rounds, added));
      DualDefects again_defects;
      RemeshResult again = run_from(moved, again_defects);
      again.samples_reallocated = added;
      keep_if_fewer(std::move(again), std::move(again_defects), result, defects);
      result.reallocation_tried = added;
    }
  }
  if (!result.fitted) {
    // `defects` are those of result.dual (found before the fitting, which is not done yet).
    // `defects.crossing_pairs` are those of result.dual as long as no vertex moved.
    const std::vector<std::pair<int, int>>* crossings = &defects.crossing_pairs;
    if (options.relax.rounds > 0) {
      const double before = shape_metrics(result.dual.positions, result.dual.triangles).q_min;
      result.relax = relax_worst_triangles(mesh, index, result.cvt.samples, result.dual, options.relax, crossings);
      crossings = &result.relax.crossings;
      progress(fmt::format("{} vertices of the worst triangles moved towards their neighbours: worst triangle {:.3f} -> "
                           "{:.3f}",
                           result.relax.moved, before, shape_metrics(result.dual.positions, result.dual.triangles).q_min));
    }
    if (options.fit) {
      progress("fitting the vertices to the surface");
      result.fit = fit_to_surface(result.cvt.diagram, mesh, result.dual, options.fit_options, &index, crossings);
    }
    if (options.untangle) {
      result.untangled_from = result.dual;
      result.untangle = untangle_crossings(mesh, result.cvt.samples, result.dual, inherited, options.untangle_options,
                                           options.fit ? &result.fit.crossings : crossings);
    }
  }
  // Crossings left in the state kept: the vertices may go further.
  for (double reach : options.final_max_moves) {
    if (!options.untangle || result.untangle.remaining.empty()) break;
    UntangleOptions further = options.untangle_options;
    further.max_move = reach;
    DualMesh dual = result.untangled_from;
    UntangleResult untangled = untangle_crossings(mesh, result.cvt.samples, dual, inherited, further,
                                                  options.fit ? &result.fit.crossings : nullptr);
    if (untangled.crossings_after < result.untangle.crossings_after) {
      result.dual = std::move(dual);
      result.untangle = std::move(untangled);
    }
  }
  result.untangled_from = {};
  // Only when no run got past such a round: a run that went on (the third, lowering the density on
  // caps at sharp tips) and ran out of rounds may mend with more rounds, not only more vertices.
  result.repair_saturated = saturated_runs == runs && !defects.empty();
  result.runs = runs;
  result.defects = std::move(defects);
  result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

void require_remesh_vertex_count(const SurfaceMesh& input, int n) {
  const int fewest = input.minimum_vertex_count();
  if (n < fewest)
    throw InputError(fmt::format("{} {} too few for this surface: no triangle mesh with its topology ({} "
                                 "component{}, Euler characteristic {}{}) has fewer than {}",
                                 n, n == 1 ? "vertex is" : "vertices are", input.component_count(),
                                 input.component_count() == 1 ? "" : "s", input.euler_characteristic(),
                                 input.boundary_loops().empty()
                                     ? std::string()
                                     : fmt::format(", {} boundary loop{}", input.boundary_loops().size(),
                                                   input.boundary_loops().size() == 1 ? "" : "s"),
                                 fewest));
}

void order_for_remeshing(SurfaceMesh& mesh, Samples& samples) {
  check_samples(mesh, samples);
  if (mesh.triangle_count() < kSpatialOrderMinTriangles) return;
  std::vector<int> new_triangle;
  mesh = spatially_ordered(mesh, &new_triangle);
  for (int& t : samples.triangles) t = new_triangle[t];
}

RemeshResult remesh_to(const SurfaceMesh& input, int n, uint64_t seed, const RemeshOptions& options) {
  require_workable_model(input, "remeshing");
  require_remesh_vertex_count(input, n);
  const double length = suggested_refinement_length(input, n);
  const bool refine = length > 0 && input.max_edge_length() > length;
  const double at_most = refine ? kRefinedTriangleMargin * expected_refined_triangle_count(input, length) : 0;
  if (at_most > kMaxRefinedTriangles)
    throw InputError(fmt::format("{} vertices would need the mesh refined to about {:.3g} triangles (limit {:.3g}): "
                                 "use fewer vertices",
                                 n, at_most, kMaxRefinedTriangles));
  SurfaceMesh mesh = refine ? refine_long_edges(input, length) : input;
  Samples samples = mesh.component_count() > 1 ? sample_by_component(mesh, n, seed, mesh.minimum_vertex_counts())
                                               : sample_uniform(mesh, n, seed);
  order_for_remeshing(mesh, samples);
  return remesh_cvt(input, mesh, samples, options);
}

}  // namespace lrvd
