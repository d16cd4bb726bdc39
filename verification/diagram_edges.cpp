// Properties decided along mesh edges: (2) each cell is one connected region, (6) both triangles
// beside a mesh edge split it at the same points with the same cells. Recomputed here from the
// polygon sides along each edge that the triangle pass listed (and, where the two sides differ,
// from the exact parameters of their vertices along the edge), independently of the diagram's own
// helpers (cell_components), so a bug there shows up. Also counts each edge's type B vertices.
// Part of verify_diagram (verification/diagram_check.h); the triangle pass: diagram_triangle.cpp.
#include "verification/diagram_edges.h"

#include <algorithm>
#include <array>
#include <deque>
#include <numeric>
#include <tuple>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/parallel_for.h>

#include "verification/diagram_vertices.h"

namespace lrvd::verify_detail {

namespace {

// A polygon edge lying along a mesh edge (lo, hi), lo < hi, oriented from lo towards hi.
struct Segment {
  std::uint64_t start = 0, end = 0;  // the ends' identities
  const SymbolicVertex* q0 = nullptr;  // the ends
  const SymbolicVertex* q1 = nullptr;
  EdgePosition s0, s1;  // along the edge, 0 at lo, 1 at hi
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

// The edges of a range of triangles (each edge from its lower triangle): (6) into `conforming`,
// for (2) the pairs of polygons an edge joins, in the order met, and the number of distinct type
// B vertices on them (a boundary edge's from its one triangle).
class EdgeChecker {
 public:
  EdgeChecker(const DiagramInput& in, const std::vector<TriangleChunk>& chunks, EdgeChunk& out)
      : in_(in), mesh_(in.mesh), diagram_(in.d), chunks_(chunks), out_(out) {}

  // The edges of triangles [begin, end) (a chunk) seen from their lower triangle: `inner`, those
  // whose other triangle is in the chunk too, and the boundary edges; else those to a later chunk.
  void check_triangles(int begin, int end, bool inner) {
    for (int t = begin; t < end; ++t)
      for (int e = 0; e < 3; ++e) {
        const int across = mesh_.neighbor(t, e);
        if (across < 0) {
          if (inner) out_.b_vertices += b_count(t, e) >= 0 ? b_count(t, e) : distinct_b(t, e, -1, -1);
          continue;
        }
        if (across < t || (across < end) != inner) continue;  // seen from the other side, or in the other pass
        const int e_across = mesh_.neighbor_edge(t, e);
        const bool same = check_edge(t, e, across, e_across);
        const bool counted = same && b_count(t, e) >= 0 && b_count(across, e_across) >= 0;
        out_.b_vertices += counted ? b_count(t, e) : distinct_b(t, e, across, e_across);
      }
  }

 private:
  // The sides of triangle t along its edge e, in polygon order.
  const SideSegment* sides_begin(int t, int e) const {
    const TriangleChunk& c = chunks_[t / kCheckChunk];
    return c.sides.data() + c.first_side[3 * (t % kCheckChunk) + e];
  }
  const SideSegment* sides_end(int t, int e) const {
    const TriangleChunk& c = chunks_[t / kCheckChunk];
    return c.sides.data() + c.first_side[3 * (t % kCheckChunk) + e + 1];
  }
  int b_count(int t, int e) const { return chunks_[t / kCheckChunk].b_count[t % kCheckChunk][e]; }

  // The identity along the edge of q, a vertex on it (as TriangleChecker gives it).
  std::uint64_t key(const SymbolicVertex& q) const {
    if (q.type == SymbolicVertex::Type::A && q.v[1] == -1 && q.v[2] == -1 && q.label[0] == -1 &&
        q.label[1] == -1 && q.label[2] == -1)
      return corner_key(q.v[0]);
    return q.type == SymbolicVertex::Type::B ? edge_key(q) : in_.irregular_key(q);
  }

  // The position along the edge of q, measured from mesh vertex `lo`; a type B vertex's point is
  // made here (kept until the next edge).
  EdgePosition parameter(const SymbolicVertex& q, int lo) {
    if (q.type != SymbolicVertex::Type::B) return EdgePosition::of(key(q), q, ExactVertex{}, lo);
    points_.push_back(ExactVertex::of(q, in_.context, &in_.rationals));
    return EdgePosition::of(key(q), q, points_.back(), lo);
  }

  // Whether a side of positive length in the filter's eyes is one, exactly.
  bool positive_length(const SideSegment& s, int t) {
    if (s.length != SideLength::Undecided) return s.length == SideLength::Positive;
    const Triangle& tri = mesh_.triangle(t);
    const int lo = std::min(tri[s.edge], tri[(s.edge + 1) % 3]);
    const CellPolygon& poly = diagram_.polygons[s.polygon];
    const SymbolicVertex* verts = diagram_.polygon_vertices(poly);
    return compare(parameter(verts[s.k], lo), parameter(verts[(s.k + 1) % poly.vertex_count], lo)) != Sign::Zero;
  }

  // visit(q0, q1, cell, polygon) for each edge (q0, q1) of triangle t's usable polygons along the
  // triangle's edge e, in the polygon's order.
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
      if (!(in_.polygon_state[p] & kUsable)) continue;
      const CellPolygon& poly = diagram_.polygons[p];
      const SymbolicVertex* verts = diagram_.polygon_vertices(poly);
      for (int k = 0; k < poly.vertex_count; ++k) {
        const int k1 = (k + 1) % poly.vertex_count;
        if (on_edge(verts[k]) && on_edge(verts[k1])) visit(verts[k], verts[k1], poly.cell, p);
      }
    }
  }

  // The segments of triangle t's polygons along its edge e, sorted from lo to hi.
  void collect(int t, int e, std::vector<Segment>& out) {
    out.clear();
    const Triangle& tri = mesh_.triangle(t);
    const int lo = std::min(tri[e], tri[(e + 1) % 3]);
    for_each_segment(t, e, [&](const SymbolicVertex& q0, const SymbolicVertex& q1, int cell, int p) {
      Segment s{key(q0), key(q1), &q0, &q1, parameter(q0, lo), parameter(q1, lo), cell, p};
      // Zero-length segments (degenerate input) are ordered by identity, alike from both sides.
      const Sign order = compare(s.s1, s.s0);
      if (order == Sign::Negative || (order == Sign::Zero && symbolic_less(*s.q1, *s.q0))) {
        std::swap(s.start, s.end);
        std::swap(s.q0, s.q1);
        std::swap(s.s0, s.s1);
      }
      out.push_back(s);
    });
    std::sort(out.begin(), out.end(), [&](const Segment& x, const Segment& y) {
      if (const Sign c = compare(x.s0, y.s0); c != Sign::Zero) return c == Sign::Negative;
      if (const Sign c = compare(x.s1, y.s1); c != Sign::Zero) return c == Sign::Negative;
      if (x.cell != y.cell) return x.cell < y.cell;
      if (x.start != y.start) return symbolic_less(*x.q0, *y.q0);
      return symbolic_less(*x.q1, *y.q1);
    });
  }

  // Both sides have the same segments, by their ends' identities and their cells: then they
  // split the edge alike, (6) holds, and for (2) each segment of positive length joins its twin's
  // polygon. (A join the full comparison below would add besides, between segments of one cell
  // overlapping but not twins, needs two polygons of one side overlapping along the edge, which
  // (4) reports: without it (2) can only find more pieces, never fewer.)
  bool same_ids(int t, int e, int across, int e_across) {
    const SideSegment *mine = sides_begin(t, e), *mine_end = sides_end(t, e);
    const SideSegment *theirs = sides_begin(across, e_across), *theirs_end = sides_end(across, e_across);
    const std::size_t n = mine_end - mine;
    if (n != static_cast<std::size_t>(theirs_end - theirs)) return false;
    // Each segment's twin: the first one left of the other side with the same ends and cell.
    twin_.resize(n);
    taken_.resize(n);
    std::fill(taken_.begin(), taken_.end(), 0);
    for (std::size_t a = 0; a < n; ++a) {
      std::size_t k = 0;
      while (k < n && (taken_[k] || !mine[a].same_split(theirs[k]))) ++k;
      if (k == n) return false;
      twin_[a] = static_cast<int>(k);
      taken_[k] = 1;
    }
    ++out_.checked;
    for (std::size_t k = 0; k < n; ++k) {
      const SideSegment& m = mine[k];
      const int p = m.polygon, q = theirs[twin_[k]].polygon;
      if ((in_.polygon_state[p] & kPiece) && (in_.polygon_state[q] & kPiece) && positive_length(m, t))
        out_.joins.emplace_back(p, q);
    }
    return true;
  }

  // Checks the edge; whether both sides had the same segments (same_ids).
  bool check_edge(int t, int e, int across, int e_across) {
    if (!points_.empty()) points_.clear();
    if (same_ids(t, e, across, e_across)) return true;
    collect(t, e, mine_);
    collect(across, e_across, theirs_);
    const Triangle& tri = mesh_.triangle(t);
    const int lo = std::min(tri[e], tri[(e + 1) % 3]), hi = std::max(tri[e], tri[(e + 1) % 3]);
    check_split(t, e, across, lo, hi);
    // (2) polygons of one cell are joined when their segments overlap in positive length.
    for (const Segment& m : mine_)
      for (const Segment& o : theirs_) {
        if (m.cell != o.cell || !(in_.polygon_state[m.polygon] & kPiece) || !(in_.polygon_state[o.polygon] & kPiece))
          continue;
        const EdgePosition& from = compare(m.s0, o.s0) == Sign::Negative ? o.s0 : m.s0;  // the later start
        const EdgePosition& to = compare(m.s1, o.s1) == Sign::Negative ? m.s1 : o.s1;    // the earlier end
        if (compare(from, to) == Sign::Negative) out_.joins.emplace_back(m.polygon, o.polygon);
      }
    return false;
  }

  // (6) the same split points and the same cell on each segment, in the unperturbed geometry: a
  // segment of length zero there (a perturbed side between two vertices at one exact point) is
  // no part of the split, and two such vertices are one split point.
  void check_split(int t, int e, int across, int lo, int hi) {
    ++out_.checked;
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
    if (same) return;
    const auto cells_mine = cells_of(mine_), cells_theirs = cells_of(theirs_);
    if (cells_mine != cells_theirs)
      out_.failures.emplace_back(3 * t + e, fmt::format("edge ({}, {}): triangle {} sees cells [{}], triangle {} sees [{}]",
                                                        lo, hi, t, fmt::join(cells_mine, ", "), across,
                                                        fmt::join(cells_theirs, ", ")));
    else
      out_.failures.emplace_back(3 * t + e, fmt::format("edge ({}, {}): triangles {} and {} see cells [{}] but split it "
                                                        "at different points: [{}] vs [{}]",
                                                        lo, hi, t, across, fmt::join(cells_mine, ", "),
                                                        split_points(mine_), split_points(theirs_)));
  }

  // The distinct type B vertices on the edge, from the polygons of its triangles (across < 0: a
  // boundary edge), when the sides do not tell.
  std::int64_t distinct_b(int t, int e, int across, int e_across) {
    keys_.clear();
    add_b_keys(t, e);
    if (across >= 0) add_b_keys(across, e_across);
    std::sort(keys_.begin(), keys_.end());
    return std::unique(keys_.begin(), keys_.end()) - keys_.begin();
  }

  void add_b_keys(int t, int e) {
    const Triangle& tri = mesh_.triangle(t);
    for (int p = diagram_.triangle_offsets[t]; p < diagram_.triangle_offsets[t + 1]; ++p) {
      const CellPolygon& poly = diagram_.polygons[p];
      for (int k = 0; k < poly.vertex_count; ++k) {
        const SymbolicVertex& q = diagram_.vertices[poly.first_vertex + k];
        if (q.type == SymbolicVertex::Type::B && well_formed(q, mesh_.vertex_count(), diagram_.sample_count) &&
            (edges_of(q, tri) >> e & 1))
          keys_.push_back(edge_key(q));
      }
    }
  }

  static std::vector<int> cells_of(const std::vector<Segment>& segments) {
    std::vector<int> cells;
    for (const Segment& s : segments) cells.push_back(s.cell);
    return cells;
  }

  static std::string split_points(const std::vector<Segment>& segments) {
    std::vector<std::string> names;
    for (const Segment& s : segments) {
      if (names.empty()) names.push_back(describe(*s.q0));
      names.push_back(describe(*s.q1));
    }
    return fmt::format("{}", fmt::join(names, ", "));
  }

  const DiagramInput& in_;
  const SurfaceMesh& mesh_;
  const Diagram& diagram_;
  const std::vector<TriangleChunk>& chunks_;
  EdgeChunk& out_;
  std::deque<ExactVertex> points_;  // the type B vertices' points of the edge at hand
  std::vector<Segment> mine_, theirs_;
  std::vector<int> twin_;     // same_ids: each side's twin on the other side
  std::vector<char> taken_;
  std::vector<std::uint64_t> keys_;
};

// (2) from the polygons joined along mesh edges (union-find over `parent`).
void count_components(const Samples& samples, const Diagram& diagram, const std::vector<std::uint8_t>& state,
                      std::vector<int>& parent, DiagramVerification& out) {
  const int n = diagram.sample_count;
  // The pieces of each cell, in polygon order: cell i's are order[first[i]] .. order[first[i + 1] - 1].
  std::vector<int> first(n + 1, 0), order;
  for (int p = 0; p < static_cast<int>(diagram.polygons.size()); ++p)
    if (state[p] & kPiece) ++first[diagram.polygons[p].cell + 1];
  for (int i = 0; i < n; ++i) first[i + 1] += first[i];
  order.resize(first[n]);
  std::vector<int> next(first.begin(), first.end() - 1);
  for (int p = 0; p < static_cast<int>(diagram.polygons.size()); ++p)
    if (state[p] & kPiece) order[next[diagram.polygons[p].cell]++] = p;
  std::vector<int> roots, polys;
  for (int i = 0; i < n; ++i) {
    ++out.connected.checked;
    polys.assign(order.begin() + first[i], order.begin() + first[i + 1]);
    roots.clear();
    for (int p : polys) roots.push_back(find_root(parent, p));
    // An empty cell is (1)'s business, not connectedness; one root is one piece.
    if (std::all_of(roots.begin(), roots.end(), [&](int r) { return r == roots.front(); })) continue;
    std::vector<int> distinct = roots;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
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

void check_inner_edges(const DiagramInput& in, std::vector<TriangleChunk>& chunks, int c, EdgeChunk& out) {
  const SurfaceMesh& mesh = in.mesh;
  const int begin = c * kCheckChunk, end = std::min(mesh.triangle_count(), begin + kCheckChunk);
  EdgeChecker(in, chunks, out).check_triangles(begin, end, true);
  // Only the sides along edges to other chunks are read again.
  TriangleChunk& chunk = chunks[c];
  std::vector<SideSegment> kept;
  std::vector<int> first;
  first.reserve(chunk.first_side.size());
  for (int t = begin; t < end; ++t)
    for (int e = 0; e < 3; ++e) {
      first.push_back(static_cast<int>(kept.size()));
      const int across = mesh.neighbor(t, e);
      if (across < 0 || (across >= begin && across < end)) continue;
      const int j = 3 * (t - begin) + e;
      kept.insert(kept.end(), chunk.sides.begin() + chunk.first_side[j], chunk.sides.begin() + chunk.first_side[j + 1]);
    }
  first.push_back(static_cast<int>(kept.size()));
  chunk.sides.swap(kept);
  chunk.first_side.swap(first);
}

std::int64_t check_edges(const DiagramInput& in, const std::vector<TriangleChunk>& chunks, std::vector<EdgeChunk>& edges,
                         DiagramVerification& out) {
  // The edges between chunks in parallel, by the chunk of their lower triangle; then every chunk's
  // results in order (its offenders by edge), and the joins in that order.
  const int count = static_cast<int>(chunks.size());
  tbb::parallel_for(0, count, [&](int c) {
    EdgeChecker(in, chunks, edges[c])
        .check_triangles(c * kCheckChunk, std::min(in.mesh.triangle_count(), (c + 1) * kCheckChunk), false);
  });
  std::vector<int> parent(in.d.polygons.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::int64_t b_vertices = 0;
  for (EdgeChunk& chunk : edges) {
    std::sort(chunk.failures.begin(), chunk.failures.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    out.conforming.checked += chunk.checked;
    for (const auto& [edge, offender] : chunk.failures) out.conforming.fail(offender);
    for (const auto& [a, b] : chunk.joins) {
      const int ra = find_root(parent, a), rb = find_root(parent, b);
      if (ra != rb) parent[ra] = rb;
    }
    b_vertices += chunk.b_vertices;
  }
  count_components(in.samples, in.d, in.polygon_state, parent, out);
  return b_vertices;
}

}  // namespace lrvd::verify_detail
