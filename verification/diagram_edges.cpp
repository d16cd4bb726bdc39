// Properties decided along mesh edges: (2) each cell is one connected region, (6) both triangles
// beside a mesh edge split it at the same points with the same cells. Recomputed here from the
// polygons and the exact parameters of their vertices along the edge, independently of the
// diagram's own helpers (cell_components), so a bug there shows up.
// Part of verify_diagram (verification/diagram_check.h), its helpers in verification/diagram_geometry.h.
#include <algorithm>
#include <array>
#include <numeric>
#include <tuple>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/parallel_for.h>

#include "verification/diagram_geometry.h"

namespace lrvd::verify_detail {

namespace {

// A polygon edge lying along a mesh edge (lo, hi), lo < hi, oriented from lo towards hi.
struct Segment {
  int start = -1, end = -1;  // exact vertex ids
  EdgePosition s0, s1;       // along the edge, 0 at lo, 1 at hi
  int cell = -1;
  int polygon = -1;
};

bool symbolic_less(const SymbolicVertex& a, const SymbolicVertex& b) {
  return std::tie(a.type, a.v, a.label) < std::tie(b.type, b.v, b.label);
}

int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// A polygon edge along an edge of its triangle, by its ends' exact vertex ids (lo < hi, or equal for
// a vertex repeated); a triangle's in polygon order.
struct SideSegment {
  int edge, lo, hi, cell, polygon;
  bool same_split(const SideSegment& o) const { return lo == o.lo && hi == o.hi && cell == o.cell; }
};

// The SideSegments of every triangle, found in one pass over its polygons' vertices: triangle t's
// are segments[first[t]] .. segments[first[t + 1] - 1], in chunks of kCheckChunk triangles.
struct Sides {
  std::vector<std::vector<SideSegment>> segments;  // per chunk
  std::vector<int> first;                          // per triangle, into its chunk's list; per chunk one more
  const SideSegment* begin(int t) const { return segments[t / kCheckChunk].data() + first[t + t / kCheckChunk]; }
  const SideSegment* end(int t) const { return segments[t / kCheckChunk].data() + first[t + t / kCheckChunk + 1]; }
};

Sides side_segments(const SurfaceMesh& mesh, const Diagram& diagram, const std::vector<char>& polygon_ok,
                    const VertexIndex& vertices) {
  const int nt = mesh.triangle_count(), chunks = (nt + kCheckChunk - 1) / kCheckChunk;
  Sides sides;
  sides.segments.resize(chunks);
  sides.first.resize(nt + chunks);
  tbb::parallel_for(0, chunks, [&](int c) {
    std::vector<SideSegment>& out = sides.segments[c];
    std::vector<std::uint8_t> bits;
    for (int t = c * kCheckChunk; t < std::min(nt, (c + 1) * kCheckChunk); ++t) {
      sides.first[t + c] = static_cast<int>(out.size());
      const Triangle& tri = mesh.triangle(t);
      for (int p = diagram.triangle_offsets[t]; p < diagram.triangle_offsets[t + 1]; ++p) {
        if (!polygon_ok[p]) continue;
        const CellPolygon& poly = diagram.polygons[p];
        const SymbolicVertex* verts = diagram.polygon_vertices(poly);
        const int* ids = vertices.of_diagram_vertex.data() + poly.first_vertex;
        bits.resize(poly.vertex_count);
        for (int k = 0; k < poly.vertex_count; ++k) bits[k] = edges_of(verts[k], tri);
        for (int k = 0; k < poly.vertex_count; ++k) {
          const int k1 = k + 1 == poly.vertex_count ? 0 : k + 1;
          const int along = bits[k] & bits[k1];
          for (int e = 0; e < 3; ++e)
            if (along >> e & 1)
              out.push_back({e, std::min(ids[k], ids[k1]), std::max(ids[k], ids[k1]), poly.cell, p});
        }
      }
    }
    sides.first[std::min(nt, (c + 1) * kCheckChunk) + c] = static_cast<int>(out.size());
  });
  return sides;
}

// The edges of a range of triangles (each edge from its lower triangle): (6) into `conforming`,
// and for (2) the pairs of polygons an edge joins, in the order met.
class EdgeChecker {
 public:
  EdgeChecker(const SurfaceMesh& mesh, const Diagram& diagram, const std::vector<char>& polygon_ok,
              const std::vector<char>& piece, const VertexIndex& vertices, const Sides& sides,
              PropertyResult& conforming, std::vector<std::pair<int, int>>& joins)
      : mesh_(mesh), diagram_(diagram), polygon_ok_(polygon_ok), piece_(piece), vertices_(vertices), sides_(sides),
        conforming_(conforming), joins_(joins) {}

  void check_triangles(int begin, int end) {
    for (int t = begin; t < end; ++t)
      for (int e = 0; e < 3; ++e) {
        const int across = mesh_.neighbor(t, e);
        if (across < t) continue;  // boundary edge, or seen from the other side already
        check_edge(t, e, across, mesh_.neighbor_edge(t, e));
      }
  }

 private:
  EdgePosition parameter(int id, int lo) const {
    return EdgePosition::of(id, vertices_.exact.symbolic(id), vertices_.exact[id], lo);
  }

  // visit(from, to, cell, polygon) for each edge of triangle t's usable polygons along the
  // triangle's edge e (from, to: its ends' exact vertex ids, in the polygon's order).
  template <class Visit>
  void for_each_segment(int t, int e, Visit visit) const {
    const Triangle& tri = mesh_.triangle(t);
    const int a = tri[e], b = tri[(e + 1) % 3], lo = std::min(a, b), hi = std::max(a, b);
    // As SymbolicVertex::on_mesh_edge(a, b), inline.
    auto on_edge = [&](const SymbolicVertex& q) {
      return q.type == SymbolicVertex::Type::A ? q.v[0] == a || q.v[0] == b
                                               : q.type == SymbolicVertex::Type::B && q.v[0] == lo && q.v[1] == hi;
    };
    for (int p = diagram_.triangle_offsets[t]; p < diagram_.triangle_offsets[t + 1]; ++p) {
      if (!polygon_ok_[p]) continue;
      const CellPolygon& poly = diagram_.polygons[p];
      const SymbolicVertex* verts = diagram_.polygon_vertices(poly);
      const int* ids = vertices_.of_diagram_vertex.data() + poly.first_vertex;
      for (int k = 0; k < poly.vertex_count; ++k) {
        const int k1 = (k + 1) % poly.vertex_count;
        if (on_edge(verts[k]) && on_edge(verts[k1])) visit(ids[k], ids[k1], poly.cell, p);
      }
    }
  }

  // The segments of triangle t's polygons along its edge e, sorted from lo to hi.
  void collect(int t, int e, std::vector<Segment>& out) const {
    out.clear();
    const Triangle& tri = mesh_.triangle(t);
    const int lo = std::min(tri[e], tri[(e + 1) % 3]);
    for_each_segment(t, e, [&](int from, int to, int cell, int p) {
      Segment s{from, to, parameter(from, lo), parameter(to, lo), cell, p};
      // Zero-length segments (degenerate input) are ordered by identity, alike from both sides.
      const Sign order = compare(s.s1, s.s0);
      if (order == Sign::Negative ||
          (order == Sign::Zero && symbolic_less(vertices_.exact.symbolic(s.end), vertices_.exact.symbolic(s.start)))) {
        std::swap(s.start, s.end);
        std::swap(s.s0, s.s1);
      }
      out.push_back(s);
    });
    std::sort(out.begin(), out.end(), [&](const Segment& x, const Segment& y) {
      if (const Sign c = compare(x.s0, y.s0); c != Sign::Zero) return c == Sign::Negative;
      if (const Sign c = compare(x.s1, y.s1); c != Sign::Zero) return c == Sign::Negative;
      if (x.cell != y.cell) return x.cell < y.cell;
      if (x.start != y.start) return symbolic_less(vertices_.exact.symbolic(x.start), vertices_.exact.symbolic(y.start));
      return symbolic_less(vertices_.exact.symbolic(x.end), vertices_.exact.symbolic(y.end));
    });
  }

  // The SideSegments of triangle t along its edge e, in polygon order.
  void along(int t, int e, std::vector<const SideSegment*>& out) const {
    out.clear();
    for (const SideSegment* s = sides_.begin(t); s != sides_.end(t); ++s)
      if (s->edge == e) out.push_back(s);
  }

  // Both sides have the same segments, by their ends' exact vertex ids and their cells: then they
  // split the edge alike, (6) holds, and for (2) each segment of positive length joins its twin's
  // polygon. (A join the full comparison below would add besides, between segments of one cell
  // overlapping but not twins, needs two polygons of one side overlapping along the edge, which
  // (4) reports: without it (2) can only find more pieces, never fewer.)
  bool same_ids(int t, int e, int across, int e_across, int lo) {
    along(t, e, mine_ids_);
    along(across, e_across, theirs_ids_);
    if (mine_ids_.size() != theirs_ids_.size()) return false;
    // Each segment's twin: the first one left of the other side with the same ends and cell.
    twin_.clear();
    for (const SideSegment* m : mine_ids_) {
      std::size_t k = 0;
      while (k < theirs_ids_.size() && (!theirs_ids_[k] || !m->same_split(*theirs_ids_[k]))) ++k;
      if (k == theirs_ids_.size()) return false;
      twin_.push_back(theirs_ids_[k]);
      theirs_ids_[k] = nullptr;
    }
    ++conforming_.checked;
    for (std::size_t k = 0; k < mine_ids_.size(); ++k) {
      const SideSegment& m = *mine_ids_[k];
      const int p = m.polygon, q = twin_[k]->polygon;
      if (piece_[p] && piece_[q] && compare(parameter(m.lo, lo), parameter(m.hi, lo)) != Sign::Zero)
        joins_.emplace_back(p, q);
    }
    return true;
  }

  void check_edge(int t, int e, int across, int e_across) {
    {
      const Triangle& tri = mesh_.triangle(t);
      if (same_ids(t, e, across, e_across, std::min(tri[e], tri[(e + 1) % 3]))) return;
    }
    collect(t, e, mine_);
    collect(across, e_across, theirs_);
    const Triangle& tri = mesh_.triangle(t);
    const int lo = std::min(tri[e], tri[(e + 1) % 3]), hi = std::max(tri[e], tri[(e + 1) % 3]);

    // (6) the same split points and the same cell on each segment, in the unperturbed geometry: a
    // segment of length zero there (a perturbed side between two vertices at one exact point) is
    // no part of the split, and two such vertices are one split point.
    ++conforming_.checked;
    auto next_segment = [](const std::vector<Segment>& list, size_t k) {
      while (k < list.size() && compare(list[k].s0, list[k].s1) == Sign::Zero) ++k;
      return k;
    };
    bool same = true;
    for (size_t a = next_segment(mine_, 0), b = next_segment(theirs_, 0); same; a = next_segment(mine_, a + 1), b = next_segment(theirs_, b + 1)) {
      if (a == mine_.size() || b == theirs_.size()) {
        same = a == mine_.size() && b == theirs_.size();
        break;
      }
      same = mine_[a].cell == theirs_[b].cell && compare(mine_[a].s0, theirs_[b].s0) == Sign::Zero &&
             compare(mine_[a].s1, theirs_[b].s1) == Sign::Zero;
    }
    if (!same) {
      const auto cells_mine = cells_of(mine_), cells_theirs = cells_of(theirs_);
      if (cells_mine != cells_theirs)
        conforming_.fail(fmt::format("edge ({}, {}): triangle {} sees cells [{}], triangle {} sees [{}]", lo, hi, t,
                                     fmt::join(cells_mine, ", "), across, fmt::join(cells_theirs, ", ")));
      else
        conforming_.fail(fmt::format("edge ({}, {}): triangles {} and {} see cells [{}] but split it at different "
                                     "points: [{}] vs [{}]",
                                     lo, hi, t, across, fmt::join(cells_mine, ", "), split_points(mine_),
                                     split_points(theirs_)));
    }

    // (2) polygons of one cell are joined when their segments overlap in positive length.
    for (const Segment& m : mine_)
      for (const Segment& o : theirs_) {
        if (m.cell != o.cell || !piece_[m.polygon] || !piece_[o.polygon]) continue;
        const EdgePosition& from = compare(m.s0, o.s0) == Sign::Negative ? o.s0 : m.s0;  // the later start
        const EdgePosition& to = compare(m.s1, o.s1) == Sign::Negative ? m.s1 : o.s1;    // the earlier end
        if (compare(from, to) == Sign::Negative) joins_.emplace_back(m.polygon, o.polygon);
      }
  }

  static std::vector<int> cells_of(const std::vector<Segment>& segments) {
    std::vector<int> cells;
    for (const Segment& s : segments) cells.push_back(s.cell);
    return cells;
  }

  std::string split_points(const std::vector<Segment>& segments) const {
    std::vector<std::string> names;
    for (const Segment& s : segments) {
      if (names.empty()) names.push_back(describe(vertices_.exact.symbolic(s.start)));
      names.push_back(describe(vertices_.exact.symbolic(s.end)));
    }
    return fmt::format("{}", fmt::join(names, ", "));
  }

  const SurfaceMesh& mesh_;
  const Diagram& diagram_;
  const std::vector<char>& polygon_ok_;
  const std::vector<char>& piece_;
  const VertexIndex& vertices_;
  const Sides& sides_;
  PropertyResult& conforming_;
  std::vector<std::pair<int, int>>& joins_;
  std::vector<Segment> mine_, theirs_;
  std::vector<const SideSegment*> mine_ids_, theirs_ids_, twin_;
};

// (2) from the polygons joined along mesh edges (union-find over `parent`).
void count_components(const Samples& samples, const Diagram& diagram, const std::vector<char>& piece,
                      std::vector<int>& parent, DiagramVerification& out) {
  const int n = diagram.sample_count;
  // The pieces of each cell, in polygon order: cell i's are order[first[i]] .. order[first[i + 1] - 1].
  std::vector<int> first(n + 1, 0), order;
  for (int p = 0; p < static_cast<int>(diagram.polygons.size()); ++p)
    if (piece[p]) ++first[diagram.polygons[p].cell + 1];
  for (int i = 0; i < n; ++i) first[i + 1] += first[i];
  order.resize(first[n]);
  std::vector<int> next(first.begin(), first.end() - 1);
  for (int p = 0; p < static_cast<int>(diagram.polygons.size()); ++p)
    if (piece[p]) order[next[diagram.polygons[p].cell]++] = p;
  std::vector<int> roots, polys;
  for (int i = 0; i < n; ++i) {
    ++out.connected.checked;
    polys.assign(order.begin() + first[i], order.begin() + first[i + 1]);
    roots.clear();
    for (int p : polys) roots.push_back(find_root(parent, p));
    std::vector<int> distinct = roots;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    if (distinct.size() <= 1) continue;  // an empty cell is (1)'s business, not connectedness
    ++out.cells_with_multiple_components;
    // The main piece holds the sample; the first other piece is named as the stray one.
    int home = roots.front();
    for (size_t k = 0; k < polys.size(); ++k)
      if (i < samples.size() && diagram.polygons[polys[k]].triangle == samples.triangles[i]) home = roots[k];
    int stray = -1;
    std::vector<int> triangles;
    for (size_t k = 0; k < polys.size(); ++k) {
      if (roots[k] == home || (stray >= 0 && roots[k] != stray)) continue;
      stray = roots[k];
      triangles.push_back(diagram.polygons[polys[k]].triangle);
    }
    const size_t shown = std::min<size_t>(triangles.size(), 8);
    out.connected.fail(fmt::format("cell {}: {} pieces, stray piece in triangle{} {}{}", i, distinct.size(),
                                   triangles.size() > 1 ? "s" : "",
                                   fmt::join(triangles.begin(), triangles.begin() + shown, ", "),
                                   triangles.size() > shown ? ", ..." : ""));
  }
}

}  // namespace

void check_edges(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram,
                 const std::vector<char>& polygon_ok, const std::vector<char>& piece, const VertexIndex& vertices,
                 DiagramVerification& out) {
  // The edges in parallel, by fixed chunks of triangles merged in order; the joins then in that order.
  const int chunks = (mesh.triangle_count() + kCheckChunk - 1) / kCheckChunk;
  std::vector<PropertyResult> conforming(chunks);
  std::vector<std::vector<std::pair<int, int>>> joins(chunks);
  const Sides sides = side_segments(mesh, diagram, polygon_ok, vertices);
  tbb::parallel_for(0, chunks, [&](int c) {
    EdgeChecker(mesh, diagram, polygon_ok, piece, vertices, sides, conforming[c], joins[c])
        .check_triangles(c * kCheckChunk, std::min(mesh.triangle_count(), (c + 1) * kCheckChunk));
  });
  std::vector<int> parent(diagram.polygons.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (int c = 0; c < chunks; ++c) {
    merge_into(out.conforming, conforming[c]);
    for (const auto& [a, b] : joins[c]) {
      const int ra = find_root(parent, a), rb = find_root(parent, b);
      if (ra != rb) parent[ra] = rb;
    }
  }
  count_components(samples, diagram, piece, parent, out);
}

}  // namespace lrvd::verify_detail
