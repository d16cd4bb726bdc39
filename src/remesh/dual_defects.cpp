// The defects of a CVT's dual (remesh/dual_defects.h): its own (bad edges, repeated, merged or unused
// triangles, pinched vertices), crossings, and the cells that are not disks or meet wrongly.
#include "remesh/dual_defects.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>

#include <fmt/format.h>

#include "diagram/clip.h"
#include "mesh/curvature.h"
#include "mesh/self_intersections.h"

namespace lrvd {

namespace {

// Cells that are not disks (more than one boundary loop: a ring around a thin tube; or an Euler
// characteristic V - E + F below 1: a handle inside the cell, smaller than it) and pairs of
// cells that share more than one boundary arc (paper Fig. 13): the dual is wrong there even when
// it looks like a manifold. Also, in `strips`, the pairs whose one shared arc runs from the mesh
// boundary to the mesh boundary through no triple point: across a strip narrower than the cells,
// where the dual has no edge between them. Boundary pieces are joined through their shared symbolic
// vertices. The steps: read the polygons' edges, the cells' Euler characteristics, the boundary
// pieces grouped by key, and their connected components per key.
class CellTopology {
 public:
  CellTopology(const Diagram& diagram, const SurfaceMesh& mesh)
      : diagram_(diagram), mesh_(mesh), cells_(diagram.sample_count), faces_(cells_, 0), inner_sides_(cells_, 0),
        outer_edges_(cells_, 0), unknown_edge_(cells_, 0) {}

  void add_defects(std::set<int>& defect, std::vector<std::pair<int, int>>& strips, std::vector<RingCell>& rings) {
    read_polygon_edges();
    add_cells_not_disks(defect);
    group_pieces_by_key();
    add_split_boundaries(defect, strips);
    measure_rings(rings);
  }

 private:
  using Key = std::pair<int, int>;  // (cell, 0) for a cell's whole boundary, (i, j + 1) for arc i|j
  struct Piece {
    Key key;
    SymbolicVertex u, w;
    int other;  // the cell across, or -2 on the mesh boundary
  };
  struct Link {
    Key key;
    int u, w;
    int other;
    bool operator<(const Link& o) const { return key < o.key; }
  };

  int id_of(const SymbolicVertex& q) { return ids_.try_emplace(q, static_cast<int>(ids_.size())).first->second; }

  // The neighbour cell across polygon edge (u, w) of `poly`: -3 inside the cell across a mesh
  // edge, -2 on the mesh boundary, -1 unknown.
  int cell_across(const CellPolygon& poly, const Triangle& tri, const SymbolicVertex& u, const SymbolicVertex& w) const {
    int other = -1;
    for (int e = 0; e < 3 && other == -1; ++e)
      if (u.on_mesh_edge(tri[e], tri[(e + 1) % 3]) && w.on_mesh_edge(tri[e], tri[(e + 1) % 3]))
        other = mesh_.neighbor(poly.triangle, e) < 0 ? -2 : -3;
    if (other == -1)
      for (int l : u.label)
        if (l >= 0 && l != poly.cell && w.has_label(l)) other = l;
    return other;
  }

  // Per cell, for its Euler characteristic: polygons, polygon edges shared with the cell's own
  // polygon across a mesh edge (each counted from both sides), the other edges, and (cell, vertex);
  // the boundary pieces, and the arc vertices on a boundary edge of the mesh.
  void read_polygon_edges() {
    for (const CellPolygon& poly : diagram_.polygons) {
      const SymbolicVertex* v = diagram_.polygon_vertices(poly);
      const Triangle& tri = mesh_.triangle(poly.triangle);
      ++faces_[poly.cell];
      for (int k = 0; k < poly.vertex_count; ++k) {
        const SymbolicVertex &u = v[k], &w = v[(k + 1) % poly.vertex_count];
        cell_vertices_.push_back({poly.cell, id_of(u)});
        const int other = cell_across(poly, tri, u, w);
        if (other == -3) {  // inside the cell, across a mesh edge
          ++inner_sides_[poly.cell];
          continue;
        }
        if (other == -1) {
          unknown_edge_[poly.cell] = 1;
          continue;
        }
        ++outer_edges_[poly.cell];
        pieces_.push_back({{poly.cell, 0}, u, w, other});
        if (other >= 0 && poly.cell < other) {
          pieces_.push_back({{poly.cell, other + 1}, u, w, other});
          for (const SymbolicVertex* q : {&u, &w})
            for (int e = 0; e < 3; ++e)
              if (q->type == SymbolicVertex::Type::B && mesh_.neighbor(poly.triangle, e) < 0 &&
                  q->on_mesh_edge(tri[e], tri[(e + 1) % 3]))
                arc_ends_on_boundary_.push_back(*q);
        }
      }
    }
  }

  // V - E + F of each cell: 1 for a disk, 0 for a ring, -1 for a disk with a handle in it.
  void add_cells_not_disks(std::set<int>& defect) {
    std::sort(cell_vertices_.begin(), cell_vertices_.end());
    cell_vertices_.erase(std::unique(cell_vertices_.begin(), cell_vertices_.end()), cell_vertices_.end());
    std::vector<int> euler(faces_);
    for (const auto& [cell, vertex] : cell_vertices_) ++euler[cell];
    for (int c = 0; c < cells_; ++c) {
      euler[c] -= inner_sides_[c] / 2 + outer_edges_[c];
      if (faces_[c] > 0 && !unknown_edge_[c] && inner_sides_[c] % 2 == 0 && euler[c] < 1) defect.insert(c);
    }
  }

  // The pieces as links between numbered vertices, grouped by cell (a counting sort), then each
  // cell's few pieces sorted by key; per vertex id, 1 for a triple point (type C), 2 for an arc's
  // end on the mesh boundary.
  void group_pieces_by_key() {
    first_of_cell_.assign(cells_ + 1, 0);
    for (const Piece& p : pieces_) ++first_of_cell_[p.key.first + 1];
    for (int c = 0; c < cells_; ++c) first_of_cell_[c + 1] += first_of_cell_[c];
    links_.resize(pieces_.size());
    std::vector<int> next(first_of_cell_.begin(), first_of_cell_.end() - 1);
    for (const Piece& p : pieces_) {
      const int u = id_of(p.u);
      links_[next[p.key.first]++] = {p.key, u, id_of(p.w), p.other};
    }
    kind_.assign(ids_.size(), 0);
    for (const auto& [q, id] : ids_)
      if (q.type == SymbolicVertex::Type::C) kind_[id] = 1;
    for (const SymbolicVertex& q : arc_ends_on_boundary_) kind_[ids_.at(q)] = 2;
    for (int c = 0; c < cells_; ++c)
      std::sort(links_.begin() + first_of_cell_[c], links_.begin() + first_of_cell_[c + 1]);
  }

  // Connected components per key, with a union-find over the key's vertices: a cell's boundary or
  // a pair's arc in more than one piece is a defect (a ring, measured by measure_rings); a pair's
  // one arc from the mesh boundary to the mesh boundary through no triple point is a strip.
  void add_split_boundaries(std::set<int>& defect, std::vector<std::pair<int, int>>& strips) {
    std::vector<int> parent(ids_.size(), -1);  // -1: not in the current key's forest
    std::vector<int> touched;
    auto root = [&](int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (size_t first = 0; first < links_.size();) {
      size_t last = first;
      int components = 0;
      bool triple = false, boundary_end = false;
      for (; last < links_.size() && links_[last].key == links_[first].key; ++last)
        for (int x : {links_[last].u, links_[last].w}) {
          if (parent[x] < 0) parent[x] = x, touched.push_back(x), ++components;
          triple = triple || kind_[x] == 1;
          boundary_end = boundary_end || kind_[x] == 2;
        }
      for (size_t k = first; k < last; ++k) {
        const int ra = root(links_[k].u), rb = root(links_[k].w);
        if (ra != rb) parent[ra] = rb, --components;
      }
      if (components > 1) {
        defect.insert(links_[first].key.first);
        if (links_[first].key.second > 0) defect.insert(links_[first].key.second - 1);
        rings_.push_back(links_[first].key);
      } else if (links_[first].key.second > 0 && boundary_end && !triple) {
        strips.push_back({links_[first].key.first, links_[first].key.second - 1});
      }
      for (int x : touched) parent[x] = -1;
      touched.clear();
      first = last;
    }
  }

  // How far round each ring of rings_ goes: the shortest loop of its boundary that meets another
  // cell (a cell's own boundary; for a pair sharing two arcs, the two cells' boundaries but those
  // arcs), from the vertices' double positions. Each loop of a ring round a tube goes round it, so
  // the shortest is the closest to the tube's girth (and no shorter). A ring with fewer than two
  // such loops holds a hole (a loop wholly on the mesh boundary), not a part: it is left out.
  void measure_rings(std::vector<RingCell>& rings) {
    if (rings_.empty()) return;
    std::vector<SymbolicVertex> vertex_of(ids_.size());
    for (const auto& [q, id] : ids_) vertex_of[id] = q;
    const SymbolicContext ctx = diagram_.context(mesh_);
    std::vector<const Link*> loop_links;
    for (const Key& ring : rings_) {
      loop_links.clear();
      const int a = ring.first, b = ring.second - 1;  // b = -1: a cell alone
      for (const int c : {a, b}) {
        if (c < 0) continue;
        for (int k = first_of_cell_[c]; k < first_of_cell_[c + 1] && links_[k].key.second == 0; ++k)
          if (links_[k].other != (c == a ? b : a)) loop_links.push_back(&links_[k]);
      }
      const double around = shortest_loop(loop_links, vertex_of, ctx);
      if (around > 0) rings.push_back({a, b, around});
    }
  }

  // The shortest loop of `links` that meets another cell; 0 when fewer than two loops do.
  static double shortest_loop(const std::vector<const Link*>& links, const std::vector<SymbolicVertex>& vertex_of,
                              const SymbolicContext& ctx) {
    std::unordered_map<int, int> parent;
    auto root = [&](int x) {
      auto it = parent.try_emplace(x, x).first;
      while (it->second != x) {
        x = it->second;
        it = parent.find(x);
      }
      return x;
    };
    for (const Link* l : links) {
      const int ra = root(l->u), rb = root(l->w);
      if (ra != rb) parent[ra] = rb;
    }
    std::unordered_map<int, std::pair<double, bool>> loops;  // root -> (length, meets a cell)
    for (const Link* l : links) {
      auto& [length, meets] = loops[root(l->u)];
      length += norm(position(vertex_of[l->u], ctx) - position(vertex_of[l->w], ctx));
      meets = meets || l->other >= 0;
    }
    double shortest = 0;
    int meeting = 0;
    for (const auto& [r, loop] : loops)
      if (loop.second) {
        ++meeting;
        if (shortest == 0 || loop.first < shortest) shortest = loop.first;
      }
    return meeting >= 2 ? shortest : 0;
  }

  const Diagram& diagram_;
  const SurfaceMesh& mesh_;
  const int cells_;
  std::vector<Piece> pieces_;
  std::vector<SymbolicVertex> arc_ends_on_boundary_;  // arc vertices on a boundary edge of the mesh
  std::unordered_map<SymbolicVertex, int, SymbolicVertexHash> ids_;  // every polygon vertex, numbered
  std::vector<int> faces_, inner_sides_, outer_edges_;
  std::vector<char> unknown_edge_;
  std::vector<std::pair<int, int>> cell_vertices_;
  std::vector<int> first_of_cell_;
  std::vector<Link> links_;
  std::vector<char> kind_;
  std::vector<Key> rings_;  // cells whose boundary, and pairs whose shared arcs, come in pieces
};

void add_cell_topology_defects(const Diagram& diagram, const SurfaceMesh& mesh, std::set<int>& defect,
                               std::vector<std::pair<int, int>>& strips, std::vector<RingCell>& rings) {
  CellTopology(diagram, mesh).add_defects(defect, strips, rings);
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

// The cornered cells and tip caps among the samples at defects (as find_dual_defects tells), and the
// tip caps' neighbours among the cell-topology `hints`; `used`: whether each sample is in a triangle.
void find_cornered_and_tip_caps(const Diagram& diagram, const SurfaceMesh& mesh, const std::set<int>& defect,
                                const std::set<int>& hints, const std::vector<char>& used, bool input_closed,
                                std::vector<int>& cornered, std::vector<int>& tip_caps,
                                std::vector<int>& tip_cap_rings) {
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
  std::vector<RingCell> rings;
  add_cell_topology_defects(diagram, mesh, hints, strips, rings);
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
  if (!defect.empty())  // unused samples are among the defects
    find_cornered_and_tip_caps(diagram, mesh, defect, hints, used, input_closed, cornered, tip_caps, tip_cap_rings);
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
  out.rings = std::move(rings);
  out.euler_ok = euler_ok;
  out.crossing_pairs = pairs;
  return out;
}

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

}  // namespace lrvd
