// Refinement by splitting long edges (paper §4.2): every edge longer than a bound (one length, or
// a length field over the vertices) is split at its midpoint, longest first, until none is left.
// The refinements are friends of SurfaceMesh, whose adjacency they build.
#include "mesh/refine.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <numeric>
#include <queue>
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "common/huge_pages.h"
#include "mesh/spatial_order.h"

namespace lrvd {

namespace {

// Splitting every edge longer than L at its midpoint, longest first, leaves triangles of about
// L^2 / 6.5 in area on average (6.5 on feline and ChineseDragon-10kv, 6.2-7.1 on the elk): edges
// end between L/2 and L, so the triangles are smaller than equilateral ones of side L (L^2 / 2.31).
constexpr double kSplitAreaDivisor = 6.5;

// An undirected edge during the splitting and the one or two triangles using it, in the order
// they took it (the order decides which side of a split edge is cut first, so it is kept as the
// splitting has always had it). Each triangle knows the records of its three edges: every look-up
// the splitting makes is then an index, where a hash table of the edges cost a cache miss each
// (the table outgrows the caches on a large mesh: most of the refinement's time).
struct EdgeRecord {
  std::array<int, 2> users;
  bool split = false;
};

// The edge of `tri` joining a and b (two of its corners): corners e and (e + 1) % 3, e being the
// corner after the one that is neither.
int edge_of(const Triangle& tri, int a, int b) {
  return (tri[0] != a && tri[0] != b) ? 1 : (tri[1] != a && tri[1] != b) ? 2 : 0;
}

struct LongEdge {
  double length;
  int a, b;
  int edge;  // its record
  bool operator<(const LongEdge& o) const { return length < o.length; }
};

// The refined mesh's arrays, before they become a SurfaceMesh.
struct Refinement {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<std::array<int, 3>> neighbors;
  int edge_count = 0;
  std::vector<int> components;
};

// Each input triangle's place along a Morton curve through the centroids (morton_order).
std::vector<int> morton_rank(const SurfaceMesh& mesh) {
  const int nt = mesh.triangle_count();
  std::vector<Vec3> centroid(nt);
  for (int t = 0; t < nt; ++t) {
    const Triangle& tri = mesh.triangle(t);
    centroid[t] = (mesh.position(tri[0]) + mesh.position(tri[1]) + mesh.position(tri[2])) / 3.0;
  }
  const std::vector<int> order = morton_order(centroid);
  std::vector<int> rank(nt);
  for (int k = 0; k < nt; ++k) rank[order[k]] = k;
  return rank;
}

// Splits every edge longer than a bound, longest first, and numbers the result (split_long_edges
// below). The state its steps share: the growing arrays, the edge records and the queue of long edges.
class EdgeSplitter {
 public:
  // Each edge's bound is max_length, or, when `values_are_lengths`, the smaller of its ends' values
  // (max_length is then not used); `vertex_values`, when given, are interpolated at the midpoints.
  EdgeSplitter(const SurfaceMesh& mesh, double max_length, std::vector<double>* vertex_values, bool values_are_lengths,
               double max_triangles)
      : mesh_(mesh), max_length_(max_length), vertex_values_(vertex_values), values_are_lengths_(values_are_lengths),
        max_triangles_(max_triangles) {}

  void split_all() {
    reserve_for_expected_size();
    record_input_edges();
    while (!queue_.empty()) {
      const LongEdge edge = queue_.top();
      queue_.pop();
      if (edges_[edge.edge].split) continue;
      split(edge);
      check_triangle_limit();
    }
  }

  // The refined mesh, numbered in `order`; `input_rank`, when given and the order is spatial,
  // receives each input triangle's place on the Morton curve.
  Refinement numbered(RefineOrder order, std::vector<int>* input_rank);

 private:
  void reserve_for_expected_size();
  void record_input_edges();
  void split(const LongEdge& edge);
  void check_triangle_limit() const;
  std::vector<int> vertex_numbers(const std::vector<int>& old_triangle, bool spatial) const;
  void renumber_triangles(const std::vector<int>& old_triangle, const std::vector<int>& new_triangle,
                          const std::vector<int>& new_vertex, Refinement& r) const;
  int new_edge(int t) {
    edges_.push_back({{t, -1}});
    ++live_edges_;
    return static_cast<int>(edges_.size()) - 1;
  }
  void push_if_long(int a, int b, int edge) {
    const double len = distance(positions_[a], positions_[b]);
    const double bound = values_are_lengths_ ? std::min((*vertex_values_)[a], (*vertex_values_)[b]) : max_length_;
    if (len > bound) queue_.push({len, std::min(a, b), std::max(a, b), edge});
  }
  // The triangle count the area alone asks for.
  double area_estimate() const {
    return static_cast<double>(mesh_.triangle_count()) + kSplitAreaDivisor * per_length_squared_;
  }

  const SurfaceMesh& mesh_;
  const double max_length_;
  std::vector<double>* const vertex_values_;
  const bool values_are_lengths_;
  const double max_triangles_;
  double per_length_squared_ = 0;  // area / length², summed over the triangles
  HugePageVector<Vec3> positions_;
  HugePageVector<Triangle> triangles_;
  // The edges: 1.5 a triangle at the end, and one more for each split. `edge_of_triangle_[t][e]`
  // is the record of edge e of t (corners e and e + 1).
  HugePageVector<EdgeRecord> edges_;
  HugePageVector<std::array<int, 3>> edge_of_triangle_;
  int live_edges_ = 0;
  HugePageVector<int> origin_;  // the input triangle each triangle is a piece of
  std::priority_queue<LongEdge> queue_;
};

// The size of the refined mesh, to reserve the arrays that grow (the edge records among them), so
// that none is reallocated on the way (a reallocation copies everything into fresh memory,
// which costs more than the refinement itself on a large mesh): the refined triangles average
// about max_length² / kSplitAreaDivisor in area, a closed mesh gains a
// vertex per two triangles, and the queue holds at most about a third as many edges as there are
// triangles at the end (0.32 on ChineseDragon-10kv). The reservations have room to spare; beyond
// them, the arrays still grow as needed. Only memory depends on this guess, not the refinement.
void EdgeSplitter::reserve_for_expected_size() {
  per_length_squared_ = mesh_.area() / (max_length_ * max_length_);
  if (values_are_lengths_) {
    per_length_squared_ = 0;
    for (int t = 0; t < mesh_.triangle_count(); ++t) {
      const Triangle& tri = mesh_.triangle(t);
      const double shortest = std::min({(*vertex_values_)[tri[0]], (*vertex_values_)[tri[1]], (*vertex_values_)[tri[2]]});
      per_length_squared_ += mesh_.triangle_area(t) / (shortest * shortest);
    }
  }
  const double expected_triangles = std::min({1.1 * area_estimate(), 5e8, max_triangles_});
  const double expected_vertices = mesh_.vertex_count() + 0.5 * (expected_triangles - mesh_.triangle_count());
  positions_.reserve(static_cast<size_t>(expected_vertices));
  positions_.assign(mesh_.positions().begin(), mesh_.positions().end());
  triangles_.reserve(static_cast<size_t>(expected_triangles));
  triangles_.assign(mesh_.triangles().begin(), mesh_.triangles().end());
  if (vertex_values_) vertex_values_->reserve(static_cast<size_t>(expected_vertices));
  edges_.reserve(static_cast<size_t>(2.0 * expected_triangles));
  edge_of_triangle_.reserve(static_cast<size_t>(expected_triangles));
  edge_of_triangle_.resize(triangles_.size());
  origin_.reserve(static_cast<size_t>(expected_triangles));
  origin_.resize(triangles_.size());
  std::iota(origin_.begin(), origin_.end(), 0);
  std::vector<LongEdge> waiting;
  waiting.reserve(static_cast<size_t>(expected_triangles / 2));
  queue_ = std::priority_queue<LongEdge>(std::less<LongEdge>(), std::move(waiting));
}

// The input's edges, each long one queued. An interior edge is first taken by its triangle of
// lower index (the input is a manifold, consistently oriented: each edge is listed once, from the
// side where it runs up).
void EdgeSplitter::record_input_edges() {
  for (int t = 0; t < static_cast<int>(triangles_.size()); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = triangles_[t][e], b = triangles_[t][(e + 1) % 3];
      const int across = mesh_.neighbor(t, e);
      int edge;
      if (across >= 0 && across < t) {
        edge = edge_of_triangle_[across][mesh_.neighbor_edge(t, e)];
        edges_[edge].users[1] = t;
      } else {
        edge = new_edge(t);
      }
      edge_of_triangle_[t][e] = edge;
      if (a < b || across < 0) push_if_long(a, b, edge);
    }
}

// Splits `edge` at its midpoint m: each triangle (u, v, w) on it becomes (u, m, w) and (m, v, w),
// and the new edges that are long are queued.
void EdgeSplitter::split(const LongEdge& edge) {
  EdgeRecord& record = edges_[edge.edge];
  record.split = true;
  --live_edges_;
  const std::array<int, 2> users = record.users;
  const int m = static_cast<int>(positions_.size());
  positions_.push_back(0.5 * (positions_[edge.a] + positions_[edge.b]));
  if (vertex_values_) vertex_values_->push_back(0.5 * ((*vertex_values_)[edge.a] + (*vertex_values_)[edge.b]));
  // The halves (a, m) and (m, b), made by the first triangle and taken by the second.
  int half_a = -1, half_b = -1;
  auto take = [&](int& half, int t) {
    if (half < 0)
      half = new_edge(t);
    else
      edges_[half].users[1] = t;
    return half;
  };
  for (int t : users) {
    if (t < 0) continue;
    // Rotate so that the split edge is (u, v) = corners 0 -> 1 of t, w opposite.
    const Triangle tri = triangles_[t];
    const int e = edge_of(tri, edge.a, edge.b);
    const int u = tri[e], v = tri[(e + 1) % 3], w = tri[(e + 2) % 3];
    const int vw = edge_of_triangle_[t][(e + 1) % 3], wu = edge_of_triangle_[t][(e + 2) % 3];
    const int t_new = static_cast<int>(triangles_.size());
    triangles_[t] = {u, m, w};
    triangles_.push_back({m, v, w});
    origin_.push_back(origin_[t]);
    std::array<int, 2>& vw_users = edges_[vw].users;
    (vw_users[0] == t ? vw_users[0] : vw_users[1]) = t_new;
    const int um = take(u == edge.a ? half_a : half_b, t);
    const int mv = take(v == edge.a ? half_a : half_b, t_new);
    const int mw = new_edge(t);
    edges_[mw].users[1] = t_new;
    edge_of_triangle_[t] = {um, mw, wu};
    edge_of_triangle_.push_back({mv, vw, mw});
    push_if_long(m, w, mw);
  }
  push_if_long(edge.a, m, half_a);
  push_if_long(m, edge.b, half_b);
}

// The area tells the count only where triangles are about as wide as long: a needle's long sides
// split into pieces each as thin as the needle, and the count grows with the length over the
// width, without a bound the area could give.
void EdgeSplitter::check_triangle_limit() const {
  if (static_cast<double>(triangles_.size()) > max_triangles_)
    throw RefinementLimitError(fmt::format(
        "splitting to {} makes more than {:.0f} triangles (the limit) although the area alone asks for "
        "about {:.3g}{}",
        values_are_lengths_ ? std::string("the length field") : fmt::format("edges of {:.6g}", max_length_),
        max_triangles_, area_estimate(),
        area_estimate() > max_triangles_ ? ": use longer edges" : ": the mesh has triangles far longer than they are wide"));
}

// Each input triangle's pieces become consecutive, in the input's order (or along a Morton
// curve), and the new vertices follow in the order those triangles first use them (the input's
// vertices keep their indices, or are numbered in that order too).
// Pieces were appended at the end as they were split off: passes over a large refined mesh
// (MPS's LRPD and darts) jumped across memory. Feline at r = 0.005 (405k triangles): its LRPD
// takes about 20 % less time with the same instructions.
Refinement EdgeSplitter::numbered(RefineOrder order, std::vector<int>* input_rank) {
  // Freed before the copies below are made, which can then reuse the memory.
  queue_ = {};
  const bool spatial = order == RefineOrder::Spatial;
  std::vector<int> rank;
  if (spatial) {
    rank = morton_rank(mesh_);
    if (input_rank) *input_rank = rank;
  } else {
    rank.resize(mesh_.triangle_count());
    std::iota(rank.begin(), rank.end(), 0);
  }
  const int nt = static_cast<int>(triangles_.size());
  std::vector<int> new_triangle(nt), first_piece(mesh_.triangle_count() + 1, 0);
  for (int t = 0; t < nt; ++t) ++first_piece[rank[origin_[t]] + 1];
  std::partial_sum(first_piece.begin(), first_piece.end(), first_piece.begin());
  for (int t = 0; t < nt; ++t) new_triangle[t] = first_piece[rank[origin_[t]]]++;
  std::vector<int> old_triangle(nt);
  for (int t = 0; t < nt; ++t) old_triangle[new_triangle[t]] = t;
  const std::vector<int> new_vertex = vertex_numbers(old_triangle, spatial);
  std::vector<Vec3> ordered_positions(positions_.size());
  for (size_t v = 0; v < positions_.size(); ++v) ordered_positions[new_vertex[v]] = positions_[v];
  positions_ = {};
  if (vertex_values_) {
    std::vector<double>& values = *vertex_values_;
    std::vector<double> ordered(values.size());
    for (size_t v = 0; v < values.size(); ++v) ordered[new_vertex[v]] = values[v];
    values.swap(ordered);
  }
  Refinement r;
  r.positions = std::move(ordered_positions);
  renumber_triangles(old_triangle, new_triangle, new_vertex, r);
  r.edge_count = live_edges_;
  return r;
}

// The new number of each vertex: in the order the triangles, taken in their new order, first use
// them (the input's own vertices first, keeping their numbers, unless `spatial`).
std::vector<int> EdgeSplitter::vertex_numbers(const std::vector<int>& old_triangle, bool spatial) const {
  const int nv_input = mesh_.vertex_count();
  std::vector<int> new_vertex(positions_.size(), -1);
  int next_vertex = 0;
  if (!spatial) {
    std::iota(new_vertex.begin(), new_vertex.begin() + nv_input, 0);
    next_vertex = nv_input;
  }
  for (int t : old_triangle)
    for (int v : triangles_[t])
      if (new_vertex[v] < 0) new_vertex[v] = next_vertex++;
  return new_vertex;
}

// The triangles, their neighbours and components in the new numbering. The adjacency is in the
// edge records: the refinement of a valid mesh is valid by construction (only its rounded
// midpoints' triangles get the zero-area check again).
void EdgeSplitter::renumber_triangles(const std::vector<int>& old_triangle, const std::vector<int>& new_triangle,
                                      const std::vector<int>& new_vertex, Refinement& r) const {
  const int nt = static_cast<int>(old_triangle.size());
  r.triangles.resize(nt);
  r.neighbors.resize(nt);
  for (int t = 0; t < nt; ++t) {
    const int old = old_triangle[t];
    for (int e = 0; e < 3; ++e) {
      r.triangles[t][e] = new_vertex[triangles_[old][e]];
      const std::array<int, 2>& users = edges_[edge_of_triangle_[old][e]].users;
      const int across = users[0] == old ? users[1] : users[0];
      r.neighbors[t][e] = across < 0 ? -1 : new_triangle[across];
    }
  }
  // Splitting keeps each input triangle's pieces edge-connected: the components are the input's,
  // numbered again by first triangle (in the input's order they already are).
  r.components.resize(nt);
  std::vector<int> renumbered(mesh_.component_count(), -1);
  int next_component = 0;
  for (int t = 0; t < nt; ++t) {
    int& c = renumbered[mesh_.triangle_components()[origin_[old_triangle[t]]]];
    if (c < 0) c = next_component++;
    r.components[t] = c;
  }
}

// Splits every edge longer than max_length, or, when `values_are_lengths`, than the smaller of
// its ends' values (max_length is then not used); the result is numbered in `order`.
// `input_rank`, when given and the order is spatial, receives each input triangle's place on the
// Morton curve.
Refinement split_long_edges(const SurfaceMesh& mesh, double max_length, std::vector<double>* vertex_values,
                            bool values_are_lengths, RefineOrder order, std::vector<int>* input_rank = nullptr,
                            double max_triangles = std::numeric_limits<double>::infinity()) {
  EdgeSplitter splitter(mesh, max_length, vertex_values, values_are_lengths, max_triangles);
  splitter.split_all();
  return splitter.numbered(order, input_rank);
}

// The refined mesh's zero-area error, told in its context. Halving an edge exactly never makes a
// zero-area triangle, but a midpoint is rounded to doubles: far from the origin for its length, an
// edge is a few units in the last place long and its midpoint can land on a line through two other
// corners. The mesh's check then names a triangle the user never gave, so the message says where
// it came from and what to change.
[[noreturn]] void throw_refined_zero_area(const InputError& error, const SurfaceMesh& input, const std::string& split) {
  const double reach = input.bounding_box().reach();
  throw InputError(fmt::format("splitting {} made a zero-area triangle (refined mesh: {}): at coordinates up to "
                               "{:.3g} doubles are too coarse for edges that short; move the model nearer the origin or "
                               "split less finely",
                               split, error.what(), reach));
}

}  // namespace

SurfaceMesh refine_long_edges(const SurfaceMesh& mesh, double max_length, std::vector<double>* vertex_values,
                              RefineOrder order, double max_triangles) {
  if (!(max_length > 0))
    throw InputError(fmt::format("refinement length must be positive (got {})", max_length));
  if (vertex_values && static_cast<int>(vertex_values->size()) != mesh.vertex_count())
    throw std::invalid_argument("refine_long_edges: one value per vertex expected");
  // The splitting's edge records, queue and unordered arrays are gone before the mesh builds its
  // vertex lists, which can then reuse some of that memory.
  if (!(max_triangles >= mesh.triangle_count()))
    throw std::invalid_argument("refine_long_edges: max_triangles below the mesh's triangle count");
  Refinement r = split_long_edges(mesh, max_length, vertex_values, false, order, nullptr, max_triangles);
  try {
    return SurfaceMesh(std::move(r.positions), std::move(r.triangles), std::move(r.neighbors), r.edge_count,
                       std::move(r.components), mesh.component_count());
  } catch (const InputError& e) {
    throw_refined_zero_area(e, mesh, fmt::format("edges longer than {:.6g}", max_length));
  }
}

SurfaceMesh refine_to_length_field(const SurfaceMesh& mesh, std::vector<double>& vertex_lengths, RefineOrder order) {
  if (static_cast<int>(vertex_lengths.size()) != mesh.vertex_count())
    throw std::invalid_argument("refine_to_length_field: one length per vertex expected");
  for (double length : vertex_lengths)
    if (!(length > 0) || !std::isfinite(length))
      throw InputError(fmt::format("refinement lengths must be positive (got {})", length));
  const double shortest = *std::min_element(vertex_lengths.begin(), vertex_lengths.end());
  Refinement r = split_long_edges(mesh, 0, &vertex_lengths, true, order, nullptr, kMaxRefinedTriangles);
  try {
    return SurfaceMesh(std::move(r.positions), std::move(r.triangles), std::move(r.neighbors), r.edge_count,
                       std::move(r.components), mesh.component_count());
  } catch (const InputError& e) {
    throw_refined_zero_area(e, mesh, fmt::format("edges longer than the length field (down to {:.6g})", shortest));
  }
}

double expected_refined_triangle_count(const SurfaceMesh& mesh, double max_length) {
  if (!(max_length > 0) || mesh.max_edge_length() <= max_length) return mesh.triangle_count();
  return mesh.triangle_count() + kSplitAreaDivisor * mesh.area() / (max_length * max_length);
}

double suggested_refinement_length(const SurfaceMesh& mesh, int n) {
  if (mesh.triangle_count() >= 2.0 * n) return 0;  // (in doubles: 2 n overflows an int past 1.07e9)
  // Splitting to edges no longer than L leaves triangles of about L^2 / kSplitAreaDivisor in area
  // (edges between L/2 and L, not equilateral triangles of side L): 4n of them cover the area.
  return std::sqrt(kSplitAreaDivisor * mesh.area() / (4.0 * n));
}

double auto_refinement_limit(double expected) {
  return std::min(kMaxRefinedTriangles, std::max(8 * kRefinedTriangleMargin * expected, 1e5));
}

std::string thinnest_long_triangle(const SurfaceMesh& mesh, double max_length) {
  int thinnest = -1;
  double ratio = 0, longest = 0, width = 0;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    double edge = 0;
    for (int e = 0; e < 3; ++e) edge = std::max(edge, distance(mesh.position(tri[e]), mesh.position(tri[(e + 1) % 3])));
    if (!(edge > max_length)) continue;
    const double w = 2 * mesh.triangle_area(t) / edge;
    if (thinnest < 0 || edge / w > ratio) thinnest = t, ratio = edge / w, longest = edge, width = w;
  }
  if (thinnest < 0) return "";
  const Triangle& tri = mesh.triangle(thinnest);
  int tip = 0;  // the corner opposite the shortest edge
  double shortest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const double edge = distance(mesh.position(tri[(k + 1) % 3]), mesh.position(tri[(k + 2) % 3]));
    if (edge < shortest) shortest = edge, tip = k;
  }
  const Vec3& p = mesh.position(tri[tip]);
  return fmt::format("triangle {} (vertices {}, {}, {}) is {:.3g} long and {:.3g} wide; its corner {} is at ({:.6g}, "
                     "{:.6g}, {:.6g}), far from the others",
                     thinnest, tri[0], tri[1], tri[2], longest, width, tri[tip], p.x, p.y, p.z);
}

SurfaceMesh spatially_ordered(const SurfaceMesh& mesh, std::vector<int>* new_triangle) {
  std::vector<int> rank;
  Refinement r = split_long_edges(mesh, std::numeric_limits<double>::infinity(), nullptr, false, RefineOrder::Spatial, &rank);
  if (r.triangles.size() != static_cast<size_t>(mesh.triangle_count()))
    throw std::logic_error("spatially_ordered: a triangle was split");
  // No edge is split: each triangle is its own only piece, at its place on the curve.
  if (new_triangle) *new_triangle = std::move(rank);
  return SurfaceMesh(std::move(r.positions), std::move(r.triangles), std::move(r.neighbors), r.edge_count,
                     std::move(r.components), mesh.component_count());
}

}  // namespace lrvd
