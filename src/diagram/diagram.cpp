// Diagram helpers: kinds, sites, cell integrals for CVT and cell connected components.
#include "diagram/diagram.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/error.h"
#include "diagram/clip.h"
#include "mesh/surface_mesh.h"

namespace lrvd {

std::string to_string(DiagramKind kind) {
  switch (kind) {
    case DiagramKind::Lrvd: return "lrvd";
    case DiagramKind::Rvd: return "rvd";
    case DiagramKind::Lrpd: return "lrpd";
    case DiagramKind::Rpd: return "rpd";
  }
  return "?";
}

DiagramKind diagram_kind_from_string(const std::string& name) {
  for (DiagramKind k : {DiagramKind::Lrvd, DiagramKind::Rvd, DiagramKind::Lrpd, DiagramKind::Rpd})
    if (to_string(k) == name) return k;
  throw InputError(fmt::format("unknown diagram '{}': use lrvd, rvd, lrpd or rpd", name));
}

bool is_localized(DiagramKind kind) { return kind == DiagramKind::Lrvd || kind == DiagramKind::Lrpd; }
bool is_power(DiagramKind kind) { return kind == DiagramKind::Lrpd || kind == DiagramKind::Rpd; }

SymbolicContext Diagram::context(const SurfaceMesh& mesh) const {
  return checked_context(mesh.positions().data(), mesh.positions().size(), sites.data(), sites.size());
}

std::vector<Site> make_sites(const Samples& samples, bool weighted) {
  std::vector<Site> sites(samples.size());
  for (int i = 0; i < samples.size(); ++i) sites[i] = Site{samples.positions[i], weighted ? samples.weight(i) : 0.0, i};
  return sites;
}

namespace {

// q == r for two type (b) or (c) vertices, the labels (which differ most often) first.
bool same_vertex(const SymbolicVertex& q, const SymbolicVertex& r) {
  return q.label[1] == r.label[1] && q.label[0] == r.label[0] && q.label[2] == r.label[2] && q.v[0] == r.v[0] &&
         q.v[1] == r.v[1] && q.v[2] == r.v[2] && q.type == r.type;
}

}  // namespace

std::string diagram_layout_error(const Diagram& d, const SurfaceMesh& mesh) {
  const int nt = mesh.triangle_count(), nv = mesh.vertex_count(), n = d.sample_count;
  if (n < 0) return fmt::format("it has {} cells", n);
  if (d.triangle_offsets.size() != static_cast<std::size_t>(nt) + 1)
    return fmt::format("it was built on a mesh of {} triangles, not on this one of {}",
                       d.triangle_offsets.empty() ? 0 : d.triangle_offsets.size() - 1, nt);
  if (d.triangle_offsets[0] != 0 || d.triangle_offsets[nt] != static_cast<int>(d.polygons.size()))
    return "its triangle offsets do not span its polygons";
  const auto in = [](int x, int size) { return x >= 0 && x < size; };
  for (int t = 0; t < nt; ++t) {
    if (d.triangle_offsets[t + 1] < d.triangle_offsets[t]) return fmt::format("its offsets decrease at triangle {}", t);
    for (int p = d.triangle_offsets[t]; p < d.triangle_offsets[t + 1]; ++p) {
      const CellPolygon& poly = d.polygons[p];
      if (poly.triangle != t || !in(poly.cell, n) || poly.first_vertex < 0 || poly.vertex_count < 0 ||
          static_cast<std::int64_t>(poly.first_vertex) + poly.vertex_count > static_cast<std::int64_t>(d.vertices.size()))
        return fmt::format("polygon {} (triangle {}, cell {}) is out of range", p, poly.triangle, poly.cell);
      for (int k = 0; k < poly.vertex_count; ++k) {
        const SymbolicVertex& q = d.vertices[poly.first_vertex + k];
        const int corners = q.type == SymbolicVertex::Type::A ? 1 : q.type == SymbolicVertex::Type::B ? 2 : 3;
        for (int c = 0; c < corners; ++c)
          if (!in(q.v[c], nv)) return fmt::format("a vertex of polygon {} names mesh vertex {}", p, q.v[c]);
        for (int a = 0; a < q.num_labels(); ++a)
          if (!in(q.label[a], n)) return fmt::format("a vertex of polygon {} names cell {}", p, q.label[a]);
      }
    }
  }
  return {};
}

CellIntegrals integrate_cells(const Diagram& diagram, const SurfaceMesh& mesh, const Samples& samples,
                              const std::vector<double>* triangle_density) {
  if (const std::string error = diagram_layout_error(diagram, mesh); !error.empty())
    throw InputError("integrate_cells: the diagram does not fit the mesh: " + error);
  return integrate_own_cells(diagram, mesh, samples, triangle_density);
}

namespace {

// Cheap checks that the three belong together (a mismatch would read outside the vectors).
void check_integration_inputs(const Diagram& diagram, const SurfaceMesh& mesh, const Samples& samples,
                              const std::vector<double>* triangle_density) {
  const int n = diagram.sample_count;
  if (diagram.triangle_offsets.size() != static_cast<std::size_t>(mesh.triangle_count()) + 1)
    throw InputError(fmt::format("integrate_cells: the diagram was built on a mesh of {} triangles, not on this one of {}",
                                 diagram.triangle_offsets.empty() ? 0 : diagram.triangle_offsets.size() - 1,
                                 mesh.triangle_count()));
  if (samples.size() != n)
    throw InputError(fmt::format("integrate_cells: the diagram has {} cells but {} samples are given", n, samples.size()));
  if (static_cast<int>(diagram.sites.size()) != n)
    throw InputError(fmt::format("integrate_cells: the diagram has {} cells but {} sites", n, diagram.sites.size()));
  if (triangle_density && triangle_density->size() != static_cast<std::size_t>(mesh.triangle_count()))
    throw InputError(fmt::format("integrate_cells: {} densities for {} triangles", triangle_density->size(),
                                 mesh.triangle_count()));
}

struct PolygonIntegrals {
  double area = 0, energy = 0;
  Vec3 moment;  // ∫ρ(x - x_i)
};

// The corners of the polygons of a run of polygons, in polygon order. A type (b) or (c) vertex is
// shared by the polygons of its labels in its triangle, which come in cell order: it is computed by
// the polygon of its smallest label and found in `known_` by the others (position() depends on the
// symbolic vertex alone, so the value is the same). Also sharing the type (b) vertices of the
// triangle across cost more in look-ups than it saved.
class PolygonCorners {
 public:
  PolygonCorners(const Diagram& diagram, const SymbolicContext& ctx) : diagram_(diagram), ctx_(ctx) { known_.reserve(16); }

  // The corners of `poly` minus x, into points[0 .. vertex_count).
  void relative_to(const CellPolygon& poly, const Vec3& x, std::vector<Vec3>& points) {
    if (poly.triangle != known_triangle_) known_.clear(), known_triangle_ = poly.triangle;
    const SymbolicVertex* verts = diagram_.polygon_vertices(poly);
    for (int a = 0; a < poly.vertex_count; ++a) {
      const SymbolicVertex& q = verts[a];
      if (q.type == SymbolicVertex::Type::A) {
        points[a] = ctx_.vertices[q.v[0]] - x;  // a mesh vertex's position is the vertex's own
      } else if (q.label[0] == poly.cell) {
        known_.push_back({q, position(q, ctx_)});
        points[a] = known_.back().position - x;
      } else {
        const Known* k = known_.data();
        const Known* end = k + known_.size();
        while (k != end && !same_vertex(k->q, q)) ++k;
        points[a] = (k != end ? k->position : position(q, ctx_)) - x;
      }
    }
  }

 private:
  struct Known {
    SymbolicVertex q;
    Vec3 position;
  };
  const Diagram& diagram_;
  const SymbolicContext& ctx_;
  std::vector<Known> known_;  // of the current triangle
  int known_triangle_ = -1;
};

// A polygon's integrals, by a fan from its first corner; coordinates relative to x_i keep the
// energy integrand small.
void add_fan_integrals(const std::vector<Vec3>& points, int count, double rho, PolygonIntegrals& out) {
  for (int a = 1; a + 1 < count; ++a) {
    const Vec3 &u = points[0], &v = points[a], &w = points[a + 1];
    const double area = rho * 0.5 * norm(cross(v - u, w - u));
    out.area += area;
    out.moment += area * (u + v + w) / 3.0;
    out.energy += area / 6.0 * (dot(u, u) + dot(v, v) + dot(w, w) + dot(u, v) + dot(v, w) + dot(u, w));
  }
}

}  // namespace

CellIntegrals integrate_own_cells(const Diagram& diagram, const SurfaceMesh& mesh, const Samples& samples,
                                  const std::vector<double>* triangle_density) {
  check_integration_inputs(diagram, mesh, samples, triangle_density);
  const int n = diagram.sample_count;
  // Positions only, no side tests: the range check of context() would be wasted on every evaluation.
  const SymbolicContext ctx{mesh.positions().data(), diagram.sites.data()};
  // Each polygon's integrals in parallel, then summed per cell in polygon order: the same result
  // with any number of threads.
  const int np = static_cast<int>(diagram.polygons.size());
  std::vector<PolygonIntegrals> part(np);
  tbb::parallel_for(tbb::blocked_range<int>(0, np, 512), [&](const tbb::blocked_range<int>& range) {
    std::vector<Vec3> points;
    PolygonCorners corners(diagram, ctx);
    for (int p = range.begin(); p != range.end(); ++p) {
      const CellPolygon& poly = diagram.polygons[p];
      const double rho = triangle_density ? (*triangle_density)[poly.triangle] : 1.0;
      if (static_cast<int>(points.size()) < poly.vertex_count) points.resize(poly.vertex_count);
      corners.relative_to(poly, samples.positions[poly.cell], points);
      add_fan_integrals(points, poly.vertex_count, rho, part[p]);
    }
  });
  CellIntegrals out;
  out.area.assign(n, 0);
  out.centroid.assign(n, Vec3{});
  out.energy.assign(n, 0);
  for (int p = 0; p < np; ++p) {
    const int i = diagram.polygons[p].cell;
    out.area[i] += part[p].area;
    out.centroid[i] += part[p].moment;
    out.energy[i] += part[p].energy;
  }
  for (int i = 0; i < n; ++i) {
    out.centroid[i] = out.area[i] > 0 ? samples.positions[i] + out.centroid[i] / out.area[i] : samples.positions[i];
    out.total_energy += out.energy[i];
  }
  return out;
}

CellComponents cell_components(const Diagram& diagram, const SurfaceMesh& mesh) {
  if (const std::string error = diagram_layout_error(diagram, mesh); !error.empty())
    throw InputError("cell_components: the diagram does not fit the mesh: " + error);
  const int np = static_cast<int>(diagram.polygons.size());
  if (diagram.polygon_along.size() == static_cast<size_t>(np)) return cell_components(diagram, mesh, diagram.polygon_along);
  // The edges each polygon runs along (in parallel), then the joins.
  std::vector<unsigned char> along_edges(np);
  tbb::parallel_for(tbb::blocked_range<int>(0, np, 1024), [&](const tbb::blocked_range<int>& range) {
    for (int p = range.begin(); p != range.end(); ++p) {
      const CellPolygon& poly = diagram.polygons[p];
      along_edges[p] = static_cast<unsigned char>(
          polygon_edges(diagram.polygon_vertices(poly), poly.vertex_count, mesh.triangle(poly.triangle)).along);
    }
  });
  return cell_components(diagram, mesh, along_edges);
}

CellComponents cell_components(const Diagram& diagram, const SurfaceMesh& mesh, const std::vector<unsigned char>& along_edges) {
  const int np = static_cast<int>(diagram.polygons.size());
  const CellPolygon* polygons = diagram.polygons.data();
  const int* offsets = diagram.triangle_offsets.data();
  // Union-find whose root is the least polygon of its set: parent[p] <= p always (links go to the
  // smaller root, path halving only shortens), which the numbering below relies on.
  std::vector<int> parent(np);
  std::iota(parent.begin(), parent.end(), 0);
  auto find_root = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    // The edges joined from t (to a triangle of larger index, so each shared edge once) and, per
    // edge, where the walk over the across triangle's polygons stands.
    unsigned upper = 0;
    int q[3], q_end[3];
    for (int e = 0; e < 3; ++e) {
      const int across = mesh.neighbor(t, e);
      if (across < t) continue;  // no triangle across (-1), or the edge is joined from across
      upper |= 1u << e;
      q[e] = offsets[across];
      q_end[e] = offsets[across + 1];
    }
    if (!upper) continue;
    // Both triangles' polygons come in cell order, a cell having at most one in a triangle: the
    // polygon of p's cell across is found by walks that only move forward.
    for (int p = offsets[t]; p < offsets[t + 1]; ++p) {
      unsigned edges = along_edges[p] & upper;
      if (!edges || (along_edges[p] & kZeroAreaInTheLimit)) continue;
      const int cell = polygons[p].cell;
      do {
        const int e = __builtin_ctz(edges);
        edges &= edges - 1;
        int& r = q[e];
        while (r < q_end[e] && polygons[r].cell < cell) ++r;
        if (r == q_end[e] || polygons[r].cell != cell || (along_edges[r] & kZeroAreaInTheLimit)) continue;
        const int ra = find_root(p), rb = find_root(r);
        if (ra < rb) parent[rb] = ra;
        else if (rb < ra) parent[ra] = rb;
      } while (edges);
    }
  }
  // In polygon order each set's root comes first, so it numbers the set (in its cell) before the
  // set's other polygons; those find the root at their parent's parent, already made a root.
  CellComponents out;
  out.polygon_component.resize(np);
  out.count.assign(diagram.sample_count, 0);
  for (int p = 0; p < np; ++p) {
    if (along_edges[p] & kZeroAreaInTheLimit) {  // joined to nothing, so no root of another
      out.polygon_component[p] = -1;
      continue;
    }
    const int r = parent[parent[p]];
    parent[p] = r;
    out.polygon_component[p] = r == p ? out.count[polygons[p].cell]++ : out.polygon_component[r];
  }
  return out;
}

// The triangles are taken in order, and each polygon is joined to those across its edges to
// triangles of lesser index, which already have their sets: it adopts the first one's root (no
// look-up of its own) and merges the others'. Each join is the one cell_components makes from the
// lesser triangle's side: that polygon runs along the edge, and neither has zero area. The pieces
// of all cells are their polygons (but those of zero area) less the merges, and each cell with a
// polygon has at least one: all are in one piece when the pieces number the cells with a polygon.
bool every_cell_in_one_piece(const Diagram& diagram, const SurfaceMesh& mesh, const std::vector<unsigned char>& along,
                             const std::vector<int>& whole) {
  const int* offsets = diagram.triangle_offsets.data();
  const CellPolygon* polygons = diagram.polygons.data();
  auto whole_cell = [&](int t) { return whole.empty() ? -1 : whole[t]; };
  thread_local std::vector<int> parent;  // per polygon; a large mesh's, so kept for the next call
  parent.resize(diagram.polygons.size());
  auto find_root = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<char> present(diagram.sample_count, 0);
  std::int64_t pieces = 0;
  int cells = 0;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    // The neighbours of lesser index; for each, the edge it shares with t (in its own numbering)
    // and where the walk over its polygons stands: the polygons of both triangles come in cell
    // order, a cell having at most one in a triangle, so the walks only move forward.
    int lower[3], edge[3], at[3], lower_count = 0;
    for (int e = 0; e < 3; ++e) {
      const int q = mesh.neighbor(t, e);
      if (q < 0 || q >= t) continue;
      lower[lower_count] = q;
      at[lower_count] = offsets[q];
      edge[lower_count] = whole_cell(q) >= 0 ? 0 : mesh.neighbor_edge(t, e);
      ++lower_count;
    }
    const int cell_of_whole = whole_cell(t);
    for (int p = offsets[t]; p < offsets[t + 1]; ++p) {
      if (cell_of_whole < 0 && (along[p] & kZeroAreaInTheLimit)) continue;
      const int k = cell_of_whole >= 0 ? cell_of_whole : polygons[p].cell;
      int root = -1;
      for (int a = 0; a < lower_count; ++a) {
        // k's polygon in the lesser triangle, if it runs along the edge and has an area.
        const int q = lower[a];
        int r;
        if (whole_cell(q) >= 0) {
          r = whole_cell(q) == k ? offsets[q] : -1;
        } else {
          int& w = at[a];
          while (w < offsets[q + 1] && polygons[w].cell < k) ++w;
          const bool joins = w < offsets[q + 1] && polygons[w].cell == k && !(along[w] & kZeroAreaInTheLimit) &&
                             (along[w] & (1u << edge[a]));
          r = joins ? w : -1;
        }
        if (r < 0) continue;
        const int b = find_root(r);
        if (root < 0) {
          root = b;
        } else if (b != root) {
          parent[std::max(root, b)] = std::min(root, b);
          root = std::min(root, b);
          --pieces;
        }
      }
      parent[p] = root >= 0 ? root : p;
      if (root < 0) {
        ++pieces;
        if (!present[k]) present[k] = 1, ++cells;
      }
    }
  }
  return pieces == cells;
}

}  // namespace lrvd
