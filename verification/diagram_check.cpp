// verify_diagram: the LRVD properties of paper §2.3 checked exactly. Per triangle: (3) equidistance
// and the local Voronoi property of every polygon vertex, (4) convex, counterclockwise polygons
// inside the triangle and pairwise interior-disjoint, (5) exact area sums; per sample: (1) it lies
// in its cell. (2) and (6) are decided along mesh edges (diagram_edges.cpp).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <optional>
#include <tuple>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/parallel_for.h>

#include "mesh/kd_tree.h"
#include "verification/diagram_geometry.h"

namespace lrvd {

namespace {

using namespace verify_detail;


// A symbolic vertex whose indices are in range and whose labels are distinct.
bool well_formed(const SymbolicVertex& q, int vertex_count, int sample_count) {
  // One unsigned comparison per index: a negative one wraps to a large value.
  auto vertex = [&](int v) { return static_cast<unsigned>(v) < static_cast<unsigned>(vertex_count); };
  auto sample = [&](int s) { return static_cast<unsigned>(s) < static_cast<unsigned>(sample_count); };
  if (q.type == SymbolicVertex::Type::A) return vertex(q.v[0]);
  if (q.type == SymbolicVertex::Type::B)
    return vertex(q.v[0]) && vertex(q.v[1]) && sample(q.label[0]) && sample(q.label[1]) && q.label[0] != q.label[1];
  return vertex(q.v[0]) && vertex(q.v[1]) && vertex(q.v[2]) && sample(q.label[0]) && sample(q.label[1]) &&
         sample(q.label[2]) && q.label[0] != q.label[1] && q.label[0] != q.label[2] && q.label[1] != q.label[2];
}

// Whether q is by definition a point of triangle `tri`: one of its corners, a point of one of its
// edges, or a point of its plane defined by this triangle.
bool defined_on_triangle(const SymbolicVertex& q, const Triangle& tri) {
  auto corner = [&](int v) { return v == tri[0] || v == tri[1] || v == tri[2]; };
  switch (q.type) {
    case SymbolicVertex::Type::A: return corner(q.v[0]);
    case SymbolicVertex::Type::B: return corner(q.v[0]) && corner(q.v[1]) && q.v[0] != q.v[1];
    case SymbolicVertex::Type::C: {
      if (q.v == tri) return true;  // the corners as the builder stores them, in the triangle's order
      std::array<int, 3> a = q.v, b = tri;
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      return a == b;
    }
  }
  return false;
}

// Diagram layout the checks index through; a failure here stops the verification.
std::string structure_error(const SurfaceMesh& mesh, const Samples& samples, const Diagram& d) {
  const int nt = mesh.triangle_count();
  if (d.sample_count != samples.size())
    return fmt::format("diagram has {} cells for {} samples", d.sample_count, samples.size());
  if (static_cast<int>(d.sites.size()) != d.sample_count)
    return fmt::format("diagram has {} sites for {} cells", d.sites.size(), d.sample_count);
  // The checks read the sites: they must be the samples given (a non-finite one would reach the
  // rationals, which cannot hold it).
  if (!samples.weights.empty() && samples.weights.size() != samples.positions.size())
    return fmt::format("{} weights for {} samples", samples.weights.size(), samples.positions.size());
  for (int i = 0; i < d.sample_count; ++i) {
    const Site& s = d.sites[i];
    const double w = is_power(d.kind) ? samples.weight(i) : 0.0;
    if (!(s.p == samples.positions[i]) || !(s.w == w) || s.id != i)
      return fmt::format("site {} is not sample {} (its position, weight or id differs)", i, i);
    if (!is_finite(s.p) || !std::isfinite(s.w)) return fmt::format("site {} is not finite", i);
  }
  if (static_cast<int>(d.triangle_offsets.size()) != nt + 1)
    return fmt::format("diagram has {} triangle offsets for {} triangles", d.triangle_offsets.size(), nt);
  if (d.triangle_offsets[0] != 0 || d.triangle_offsets[nt] != static_cast<int>(d.polygons.size()))
    return "triangle offsets do not span the polygon list";
  for (int t = 0; t < nt; ++t) {
    if (d.triangle_offsets[t + 1] < d.triangle_offsets[t]) return fmt::format("triangle {}: offsets decrease", t);
    for (int p = d.triangle_offsets[t]; p < d.triangle_offsets[t + 1]; ++p) {
      const CellPolygon& poly = d.polygons[p];
      if (poly.triangle != t) return fmt::format("polygon {} is listed under triangle {} but names triangle {}", p, t, poly.triangle);
      if (poly.first_vertex < 0 || poly.vertex_count < 0 ||
          static_cast<std::int64_t>(poly.first_vertex) + poly.vertex_count > static_cast<std::int64_t>(d.vertices.size()))
        return fmt::format("polygon {} in triangle {}: vertex range out of bounds", p, t);
    }
  }
  return {};
}

// What every worker of one verification reads: the inputs, the points of the distinct vertices
// and which polygons the geometric checks can use. area_sign is written per polygon, each by the
// worker of its triangle.
struct Checked {
  Checked(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram, const VerifyOptions& options)
      : mesh(mesh), samples(samples), d(diagram), options(options), context(diagram.context(mesh)),
        vertices{ExactVertices(context), {}} {}

  const SurfaceMesh& mesh;
  const Samples& samples;
  const Diagram& d;
  const VerifyOptions& options;
  SymbolicContext context;
  VertexIndex vertices;
  std::vector<int> mesh_vertex;  // exact vertex id of each mesh vertex
  std::vector<char> polygon_ok;
  std::vector<Sign> area_sign;
  std::vector<SiteTerms> terms;  // of every site, for (3)

  // Exact vertex ids of every distinct polygon vertex and mesh vertex (their enclosures made in
  // parallel); which polygons the geometric checks can use.
  void index_vertices() {
    const int n = d.sample_count;
    vertices.of_diagram_vertex.assign(d.vertices.size(), -1);
    vertices.exact.reserve(d.vertices.size() / 2 + mesh.vertex_count());  // most vertices are in two or more polygons
    // The mesh vertices first: a polygon corner that is one of them (equal as a symbolic vertex)
    // takes its id without a look-up.
    mesh_vertex.resize(mesh.vertex_count());
    for (int v = 0; v < mesh.vertex_count(); ++v) mesh_vertex[v] = vertices.exact.add(SymbolicVertex::mesh_vertex(v));
    for (size_t k = 0; k < d.vertices.size(); ++k) {
      const SymbolicVertex& q = d.vertices[k];
      if (!well_formed(q, mesh.vertex_count(), n)) continue;
      // Equal to SymbolicVertex::mesh_vertex(q.v[0]), field by field (no call, no memcmp).
      const bool corner = q.type == SymbolicVertex::Type::A && q.v[1] == -1 && q.v[2] == -1 && q.label[0] == -1 &&
                          q.label[1] == -1 && q.label[2] == -1;
      vertices.of_diagram_vertex[k] = corner ? mesh_vertex[q.v[0]] : vertices.exact.add(q);
    }
    vertices.exact.make_points();
    terms = site_terms(d.sites);
    polygon_ok.assign(d.polygons.size(), 0);
    area_sign.assign(d.polygons.size(), Sign::Zero);
    for (size_t p = 0; p < d.polygons.size(); ++p) {
      const CellPolygon& poly = d.polygons[p];
      bool ok = poly.cell >= 0 && poly.cell < n;
      for (int k = 0; ok && k < poly.vertex_count; ++k) {
        const int id = vertices.of_diagram_vertex[poly.first_vertex + k];
        ok = id >= 0 && vertices.exact[id].valid;
      }
      polygon_ok[p] = ok;
    }
  }
};

// The sites of the cells present in a triangle, for the equidistance check's vertices: a k-d tree
// (nanoflann) over their positions. A vertex q of cell i need not be compared with a site j that
// is strictly farther in power distance, π_j(q) > π_i(q): that comparison is Negative, which the
// check passes over. With c the centre of q's enclosure and h its half diagonal, π_j(q) <= π_i(q)
// needs |c - x_j| <= sqrt(U + w_max) + h, U >= π_i(q) a bound from |c - x_i| + h and w_max the
// largest weight present; a slack of 1e-6 of the lengths involved covers the rounding of these
// doubles and of the tree's distances many times over, so every site that may matter is found.
class Near {
 public:
  Near(const std::vector<Site>& sites, const std::vector<int>& present) : cloud_{{sites, present}}, tree_(3, cloud_) {
    for (int j : present) w_max_ = std::max(w_max_, sites[j].w);
    tree_.buildIndex();
  }
  //! The cells to compare q (of cell i's site `own`) with: those the bound keeps and q's own
  //! labels, in increasing order.
  void select(const ExactVertex& q, const Site& own, const SymbolicVertex& labels, std::vector<int>& out) const {
    Vec3 c;
    double h2 = 0;
    for (int a = 0; a < 3; ++a) {
      c[a] = 0.5 * (q.box[a].inf() + q.box[a].sup());
      const double half = 0.5 * (q.box[a].sup() - q.box[a].inf());
      h2 += half * half;
    }
    const double h = std::sqrt(h2), to_own = distance(c, own.p) + h;
    const double scale = to_own + h + std::sqrt(std::abs(own.w)) + std::sqrt(std::abs(w_max_));
    const double reach = std::sqrt(std::max(0.0, to_own * to_own - own.w + w_max_)) + h + 1e-6 * scale;
    const double query[3] = {c.x, c.y, c.z};
    found_.clear();
    tree_.radiusSearch(query, reach * reach, found_, nanoflann::SearchParams(32, 0, false));
    out.clear();
    for (const auto& [index, squared] : found_) out.push_back(cloud_.view.present[index]);
    for (int a = 0; a < labels.num_labels(); ++a) out.push_back(labels.label[a]);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

 private:
  struct Present {  // the sites of the cells present
    const std::vector<Site>& sites;
    const std::vector<int>& present;
    std::size_t size() const { return present.size(); }
    const Vec3& operator[](std::size_t k) const { return sites[present[k]].p; }
  };
  KdPoints<Present> cloud_;
  KdTree<Present> tree_;
  double w_max_ = 0;
  mutable std::vector<std::pair<unsigned, double>> found_;
};

// The checks of a range of triangles or samples, into its own results (merged in order by
// verify_diagram, so that the report does not depend on the threads).
class DiagramChecker {
 public:
  DiagramChecker(Checked& in, DiagramVerification& out)
      : mesh_(in.mesh), samples_(in.samples), d_(in.d), options_(in.options), out_(out), vertices_(in.vertices),
        mesh_vertex_(in.mesh_vertex), polygon_ok_(in.polygon_ok), area_sign_(in.area_sign), terms_(in.terms) {}

  void check_triangles(int begin, int end) {
    for (int t = begin; t < end; ++t) check_triangle(t);
  }

 private:
  const ExactVertex& vertex(const CellPolygon& poly, int k) const {
    return vertices_.exact[vertices_.of_diagram_vertex[poly.first_vertex + k]];
  }

  void check_triangle(int t) {
    const int begin = d_.triangle_offsets[t], end = d_.triangle_offsets[t + 1];
    const Triangle& tri = mesh_.triangle(t);
    for (int c = 0; c < 3; ++c) corner_[c] = &vertices_.exact[mesh_vertex_[tri[c]]];
    const Frame f = triangle_frame(mesh_, t, corner_);
    ++out_.coverage.checked;
    if (!f.valid) {
      out_.coverage.fail(fmt::format("triangle {}: degenerate, it has no 2D frame", t));
      return;
    }
    if (begin == end) {
      out_.coverage.fail(fmt::format("triangle {}: no polygon", t));
      return;
    }
    if (options_.exact_geometry) load_frame_vertices(tri, begin, end, f);
    bool areas_known = true, polygons_sound = true;
    for (int p = begin; p < end; ++p) {
      ++out_.disjoint.checked;
      if (!polygon_ok_[p]) {
        report_unusable(t, p);
        areas_known = false;
        continue;
      }
      if (!options_.exact_geometry) {  // (1) and (2) still need to know which polygons are flat
        points_.clear();
        for (int k = 0; k < d_.polygons[p].vertex_count; ++k) points_.push_back(&vertex(d_.polygons[p], k));
        area_sign_[p] = area_sign(points_, f);
        continue;
      }
      const std::string problem = polygon_problem(p, tri, f);
      if (!problem.empty()) {
        out_.disjoint.fail(fmt::format("triangle {}: polygon of cell {} {}", t, d_.polygons[p].cell, problem));
        area_sign_[p] = area_sign(points_, f);
        polygons_sound = false;
      }
    }
    if (!options_.exact_geometry) return;
    // Sound polygons whose edges add up to the triangle's boundary tile it: (5) and (4) pairwise
    // hold without arithmetic (bounded_by_triangle). Otherwise both are decided in full.
    const bool tiled = areas_known && polygons_sound && bounded_by_triangle(tri, begin, end);
    if (!areas_known)
      out_.coverage.fail(fmt::format("triangle {}: a polygon's area is unknown (malformed vertex)", t));
    else if (!tiled)
      check_area_sum(t, begin, end, f);
    if (!tiled) check_overlaps(t, begin, end, f);
    check_equidistance(t, begin, end);
  }

  // The triangle's corners and its usable polygons' vertices as FrameVertex, side by side:
  // frame_[first_[p - begin] + k] is vertex k of polygon p.
  void load_frame_vertices(const Triangle& tri, int begin, int end, const Frame& f) {
    for (int c = 0; c < 3; ++c)
      corner_frame_[c] = {corner_[c]->box[f.u], corner_[c]->box[f.v], corner_[c],
                          static_cast<std::uint8_t>((1 << c) | (1 << ((c + 2) % 3)))};
    frame_.clear();
    first_.clear();
    for (int p = begin; p < end; ++p) {
      first_.push_back(static_cast<int>(frame_.size()));
      if (!polygon_ok_[p]) continue;
      const CellPolygon& poly = d_.polygons[p];
      const SymbolicVertex* verts = d_.polygon_vertices(poly);
      for (int k = 0; k < poly.vertex_count; ++k) {
        const ExactVertex& x = vertex(poly, k);
        frame_.push_back({x.box[f.u], x.box[f.v], &x, edges_of(verts[k], tri)});
      }
    }
  }
  const FrameVertex* frame_vertices(int p) const { return frame_.data() + first_[p - d_.triangle_offsets[d_.polygons[p].triangle]]; }

  // A polygon the geometric checks cannot use: a cell that is no sample, or a vertex that is
  // malformed (indices out of range) or names no point (e.g. its edge is parallel to its bisector).
  void report_unusable(int t, int p) {
    const CellPolygon& poly = d_.polygons[p];
    if (poly.cell < 0 || poly.cell >= d_.sample_count) {
      out_.disjoint.fail(fmt::format("triangle {}: polygon {} names cell {}, which is no sample", t, p, poly.cell));
      return;
    }
    for (int k = 0; k < poly.vertex_count; ++k) {
      const SymbolicVertex& q = d_.vertices[poly.first_vertex + k];
      const int id = vertices_.of_diagram_vertex[poly.first_vertex + k];
      if (id >= 0 && vertices_.exact[id].valid) continue;
      const std::string what = id < 0 ? "is malformed" : "names no point";
      out_.disjoint.fail(fmt::format("triangle {}: polygon of cell {} has vertex {}, which {}", t, poly.cell, describe(q), what));
      if (id >= 0)  // a vertex that does not exist is equidistant from nothing
        out_.equidistant.fail(fmt::format("triangle {}: vertex {} of cell {} {}", t, describe(q), poly.cell, what));
      return;
    }
  }

  // (4) for one polygon: at least three distinct vertices, each a point of the triangle (by
  // definition and exactly inside it), convex and counterclockwise (every vertex on the closed left
  // side of every edge). Zero turns are allowed: at a degenerate input the unperturbed limit of a
  // polygon may have collinear or coincident vertices. Sets area_sign_[p] when there is no problem
  // (positive iff some turn is strictly left) and leaves the polygon's points in points_.
  std::string polygon_problem(int p, const Triangle& tri, const Frame& f) {
    const CellPolygon& poly = d_.polygons[p];
    const SymbolicVertex* verts = d_.polygon_vertices(poly);
    const FrameVertex* fv = frame_vertices(p);
    const int n = poly.vertex_count;
    points_.clear();
    for (int k = 0; k < n; ++k) points_.push_back(fv[k].x);
    if (n < 3) return fmt::format("has {} vertices", n);
    // One exact vertex per distinct symbolic vertex: equal points are equal vertices.
    for (int k = 0; k < n; ++k)
      for (int m = 0; m < k; ++m)
        if (fv[k].x == fv[m].x) return fmt::format("repeats vertex {}", describe(verts[k]));
    CGAL::Protect_FPU_rounding<true> upward;
    for (int k = 0; k < n; ++k) {
      const SymbolicVertex& q = verts[k];
      if (!defined_on_triangle(q, tri)) return fmt::format("has vertex {} of another triangle", describe(q));
      bool inside = true;
      if (q.type == SymbolicVertex::Type::B) {  // exactly on its edge's line: inside iff within the edge
        inside = within_edge(*points_[k]);
      } else if (q.type == SymbolicVertex::Type::C) {
        for (int c = 0; c < 3 && inside; ++c)
          inside = orient_upward(corner_frame_[c], corner_frame_[(c + 1) % 3], fv[k], f) != Sign::Negative;
      }
      if (!inside) return fmt::format("has vertex {} outside the triangle", describe(q));
    }
    if (strictly_convex(fv, n, f)) {
      area_sign_[p] = Sign::Positive;
      return {};
    }
    bool strictly_left = false;
    for (int k = 0; k < n; ++k) {
      const int k1 = (k + 1) % n;
      for (int m = 0; m < n; ++m) {
        // Three points of one mesh edge by definition are collinear.
        if (m == k || m == k1 || (fv[k].edges & fv[k1].edges & fv[m].edges)) continue;
        const Sign s = orient_upward(fv[k], fv[k1], fv[m], f);
        if (s == Sign::Negative)
          return fmt::format("is not convex and counterclockwise: {} is right of edge {} -> {}", describe(verts[m]),
                             describe(verts[k]), describe(verts[k1]));
        strictly_left = strictly_left || s == Sign::Positive;
      }
    }
    area_sign_[p] = strictly_left ? Sign::Positive : Sign::Zero;
    return {};
  }

  // Whether the interval filters alone show the polygon strictly convex and counterclockwise:
  // every turn strictly left, and its edges' directions turning once around (two changes of the
  // sign of their v component, each decided; a turn is less than a half turn, so the directions
  // cross v = 0 twice per round). Such a polygon has every vertex strictly left of every edge it
  // does not end, which is what polygon_problem checks; false leaves the decision to that check.
  // \pre the rounding mode is upward.
  static bool strictly_convex(const FrameVertex* fv, int n, const Frame& f) {
    int changes = 0;
    Sign previous = filtered_sign(fv[0].v - fv[n - 1].v);
    if (previous == Sign::Zero) return false;
    for (int k = 0; k < n; ++k) {
      const FrameVertex &a = fv[(k + n - 1) % n], &b = fv[k], &c = fv[(k + 1) % n];
      const Sign turn = filtered_sign((b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u));
      if (turn == Sign::Zero || (f.sign > 0) != (turn == Sign::Positive)) return false;
      const Sign direction = filtered_sign(c.v - b.v);
      if (direction == Sign::Zero) return false;
      changes += direction != previous;
      previous = direction;
    }
    return changes == 2;
  }

  // Whether the polygons' directed edges, as a 1-chain, are the triangle's boundary (a, b) +
  // (b, c) + (c, a): every edge off the mesh edges cancels with edges of the same two exact
  // vertices in the opposite direction, and along each mesh edge e = (tri[e], tri[e + 1]) the
  // edges' ends less their starts are 1 at tri[e + 1], -1 at tri[e] and 0 at every other vertex
  // (the edges along one line then add up to that segment). Decided on exact vertex ids alone: two
  // ids at one point (a degenerate input) make it false, never wrongly true. When it holds and the
  // polygons are sound (convex, counterclockwise, inside), the polygons tile the triangle: the sum
  // of their winding numbers is the triangle's, 1 inside and 0 outside, and each polygon of
  // positive area winds once around its interior, so no two interiors meet (4) and the areas add
  // up to the triangle's (5), which is what check_area_sum and check_overlaps would find.
  bool bounded_by_triangle(const Triangle& tri, int begin, int end) {
    forward_.clear();
    backward_.clear();
    for (auto& ids : from_) ids.clear();
    for (auto& ids : to_) ids.clear();
    for (int p = begin; p < end; ++p) {
      const CellPolygon& poly = d_.polygons[p];
      const int* ids = vertices_.of_diagram_vertex.data() + poly.first_vertex;
      const FrameVertex* fv = frame_vertices(p);
      for (int k = 0; k < poly.vertex_count; ++k) {
        const int k1 = k + 1 == poly.vertex_count ? 0 : k + 1;
        const int u = ids[k], w = ids[k1];
        switch (fv[k].edges & fv[k1].edges) {
          case 0:  // off the mesh edges: (lower id, higher id), by direction
            if (u < w) forward_.push_back(std::uint64_t(std::uint32_t(u)) << 32 | std::uint32_t(w));
            else backward_.push_back(std::uint64_t(std::uint32_t(w)) << 32 | std::uint32_t(u));
            break;
          case 1: from_[0].push_back(u), to_[0].push_back(w); break;
          case 2: from_[1].push_back(u), to_[1].push_back(w); break;
          case 4: from_[2].push_back(u), to_[2].push_back(w); break;
          default: return false;  // one vertex twice: no edge of the boundary
        }
      }
    }
    // Each pair of vertices as often in one direction as in the other.
    if (!same_multiset(forward_, backward_)) return false;
    // Along mesh edge e: the edges' ends and tri[e] are, as a multiset, their starts and tri[e + 1].
    for (int e = 0; e < 3; ++e) {
      from_[e].push_back(mesh_vertex_[tri[e == 2 ? 0 : e + 1]]);
      to_[e].push_back(mesh_vertex_[tri[e]]);
      if (!same_multiset(from_[e], to_[e])) return false;
    }
    return true;
  }

  // Whether a and b hold the same values as often (b reordered; a sorted when they are long).
  template <class T>
  static bool same_multiset(std::vector<T>& a, std::vector<T>& b) {
    if (a.size() != b.size()) return false;
    if (a.size() > 32) {
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      return a == b;
    }
    std::uint32_t used = 0;
    for (const T& x : a) {
      std::size_t k = 0;
      while (k < b.size() && ((used >> k & 1) || b[k] != x)) ++k;
      if (k == b.size()) return false;
      used |= std::uint32_t{1} << k;
    }
    return true;
  }

  // Parameter of a vertex of mesh edge (from, to) along it: 0 at from, 1 at to.
  Q parameter_along(const SymbolicVertex& q, int id, int from) const {
    return EdgePosition::of(id, q, vertices_.exact[id], from).exact();
  }

  // (5) The polygons' areas sum to the triangle's, exactly. The sum of the shoelace formulas with
  // the origin at corner a is the sum over directed polygon edges (u, w) of cross(u - a, w - a):
  // an edge used in both directions cancels exactly; an edge along a mesh edge through a adds 0;
  // an edge along (b, c) with parameters s_u, s_w from b adds (s_w - s_u) cross(b - a, c - b), and
  // cross(b - a, c - b) is twice the triangle's area. Any other edge left over is summed in full.
  // The edges along (b, c) add sum_v n_v s_v, n_v the times v ends such an edge less the times it
  // starts one: when only c is left with n_c = 1 (besides b, at s = 0), that is 1 without arithmetic.
  void check_area_sum(int t, int begin, int end, const Frame& f) {
    const Triangle& tri = mesh_.triangle(t);
    edges_.clear();
    for (int p = begin; p < end; ++p) {
      const CellPolygon& poly = d_.polygons[p];
      const int* ids = vertices_.of_diagram_vertex.data() + poly.first_vertex;
      const FrameVertex* fv = frame_vertices(p);
      for (int k = 0; k < poly.vertex_count; ++k) {
        const int k1 = (k + 1) % poly.vertex_count;
        const int u = poly.first_vertex + k, w = poly.first_vertex + k1;
        const std::uint8_t edges = fv[k].edges & fv[k1].edges;
        if (ids[k] < ids[k1]) edges_.push_back({ids[k], ids[k1], u, w, 1, edges});
        else edges_.push_back({ids[k1], ids[k], w, u, -1, edges});
      }
    }
    std::sort(edges_.begin(), edges_.end(), [](const DirectedEdge& x, const DirectedEdge& y) {
      return std::tie(x.from, x.to) < std::tie(y.from, y.to);
    });
    std::optional<Q> rest;  // the edges left over, summed in full (made only when there is one)
    along_bc_.clear();  // (exact vertex id, index into Diagram::vertices, +-count)
    for (size_t k = 0; k < edges_.size();) {
      size_t m = k;
      int count = 0;
      for (; m < edges_.size() && edges_[m].from == edges_[k].from && edges_[m].to == edges_[k].to; ++m)
        count += edges_[m].direction;
      const DirectedEdge& e = edges_[k];
      k = m;
      if (count == 0) continue;
      if (e.edges & 0b101) continue;  // along (a, b) or (c, a)
      if (e.edges & 0b010) {          // along (b, c)
        along_bc_.push_back({e.to, e.to_vertex, count});
        along_bc_.push_back({e.from, e.from_vertex, -count});
        continue;
      }
      points_ = {corner_[0], &vertices_.exact[e.from], &vertices_.exact[e.to]};
      if (!rest) rest.emplace(0);
      *rest += Q(count) * twice_area(points_, f);
    }
    std::sort(along_bc_.begin(), along_bc_.end());
    int n_c = 0;             // n_v at corner c
    bool elsewhere = false;  // a non-zero n_v at a vertex other than the corners b and c
    for (size_t k = 0; k < along_bc_.size();) {
      int n = 0;
      size_t m = k;
      for (; m < along_bc_.size() && along_bc_[m][0] == along_bc_[k][0]; ++m) n += along_bc_[m][2];
      along_bc_[k][2] = n;  // the first entry of each vertex carries its total
      for (size_t j = k + 1; j < m; ++j) along_bc_[j][2] = 0;
      const SymbolicVertex& v = d_.vertices[along_bc_[k][1]];
      const bool corner = v.type == SymbolicVertex::Type::A;
      if (corner && v.v[0] == tri[2]) n_c = n;
      else if (n != 0 && !(corner && v.v[0] == tri[1])) elsewhere = true;
      k = m;
    }
    // With s_b = 0 and s_c = 1: sum = n_c * area + rest = area.
    if ((!rest || CGAL::is_zero(*rest)) && n_c == 1 && !elsewhere) return;
    Q along_bc(0);
    for (const auto& [id, vertex, n] : along_bc_)
      if (n != 0) along_bc += Q(n) * parameter_along(d_.vertices[vertex], id, tri[1]);
    points_.assign(corner_.begin(), corner_.end());
    const Q triangle = twice_area(points_, f);
    const Q ratio = rest ? along_bc + *rest / triangle : along_bc;
    if (ratio != Q(1))
      out_.coverage.fail(fmt::format("triangle {}: polygon areas sum to {:.6g} of the triangle, not 1", t,
                                     CGAL::to_double(ratio)));
  }

  // (4) pairwise: two convex polygons with interiors are interior-disjoint iff the line of an edge
  // of one of them has the other on its closed outer side.
  //
  // Many polygons in one triangle (samples crowding a triangle the mesh was not refined for) would
  // make that quadratic: then only pairs whose boxes in the frame meet are tested, each box the
  // union of its vertices' enclosures (ExactVertex::box), so that boxes apart in u or v hold
  // polygons apart. A sweep along u finds those pairs; they are tested in the same order as all.
  void check_overlaps(int t, int begin, int end, const Frame& f) {
    CGAL::Protect_FPU_rounding<true> upward;
    auto test = [&](int p, int q) {
      if (separated(p, q, f) || separated(q, p, f)) return;
      out_.disjoint.fail(fmt::format("triangle {}: polygons of cells {} and {} overlap", t, d_.polygons[p].cell,
                                     d_.polygons[q].cell));
    };
    candidates_.clear();
    for (int p = begin; p < end; ++p)
      if (polygon_ok_[p] && area_sign_[p] == Sign::Positive) candidates_.push_back(p);
    boxes_.clear();
    for (int p : candidates_) {
      const FrameVertex* fv = frame_vertices(p);
      FrameBox box{p, fv[0].u.inf(), fv[0].u.sup(), fv[0].v.inf(), fv[0].v.sup()};
      for (int k = 1; k < d_.polygons[p].vertex_count; ++k) {
        box.u_lo = std::min(box.u_lo, fv[k].u.inf());
        box.u_hi = std::max(box.u_hi, fv[k].u.sup());
        box.v_lo = std::min(box.v_lo, fv[k].v.inf());
        box.v_hi = std::max(box.v_hi, fv[k].v.sup());
      }
      boxes_.push_back(box);
    }
    if (candidates_.size() <= kAllPairsUpTo) {
      for (std::size_t a = 0; a < candidates_.size(); ++a)
        for (std::size_t b = a + 1; b < candidates_.size(); ++b)
          if (!boxes_[a].apart(boxes_[b])) test(candidates_[a], candidates_[b]);
      return;
    }
    std::sort(boxes_.begin(), boxes_.end(), [](const FrameBox& a, const FrameBox& b) {
      return std::tie(a.u_lo, a.polygon) < std::tie(b.u_lo, b.polygon);
    });
    pairs_.clear();
    for (std::size_t a = 0; a < boxes_.size(); ++a)
      for (std::size_t b = a + 1; b < boxes_.size() && !(boxes_[a].u_hi < boxes_[b].u_lo); ++b)
        if (!(boxes_[a].v_hi < boxes_[b].v_lo || boxes_[b].v_hi < boxes_[a].v_lo))
          pairs_.push_back({std::min(boxes_[a].polygon, boxes_[b].polygon), std::max(boxes_[a].polygon, boxes_[b].polygon)});
    std::sort(pairs_.begin(), pairs_.end());
    for (const auto& [p, q] : pairs_) test(p, q);
  }

  // \pre the rounding mode is upward.
  bool separated(int p, int q, const Frame& f) const {
    const CellPolygon &pp = d_.polygons[p], &qq = d_.polygons[q];
    const FrameVertex* pv = frame_vertices(p);
    const FrameVertex* qv = frame_vertices(q);
    // q on the closed outer side of the line of p's edge k, and not all on it: q has positive area,
    // so a line through two distinct points has some vertex of q strictly outside; an edge whose
    // ends coincide in the exact geometry (a degenerate input's limit) has no line and separates
    // nothing, though every orientation against it is zero.
    auto outside = [&](int k) {
      const int k1 = (k + 1) % pp.vertex_count;
      bool strictly = false;
      for (int m = 0; m < qq.vertex_count; ++m) {
        // A shared vertex, or a third point of a mesh edge the polygon edge runs along, is on the line.
        if (qv[m].x == pv[k].x || qv[m].x == pv[k1].x || (pv[k].edges & pv[k1].edges & qv[m].edges)) continue;
        const Sign s = orient_upward(pv[k], pv[k1], qv[m], f);
        if (s == Sign::Positive) return false;
        strictly = strictly || s == Sign::Negative;
      }
      return strictly;
    };
    // Neighbours share an edge, the likeliest to separate them: tried first (the verdict, whether
    // some edge does, is the same in any order).
    int shared = -1;
    for (int k = 0; k < pp.vertex_count && shared < 0; ++k)
      for (int m = 0; m < qq.vertex_count; ++m)
        if (qv[m].x == pv[k].x && qv[(m + qq.vertex_count - 1) % qq.vertex_count].x == pv[(k + 1) % pp.vertex_count].x) {
          shared = k;
          break;
        }
    if (shared >= 0 && outside(shared)) return true;
    for (int k = 0; k < pp.vertex_count; ++k)
      if (k != shared && outside(k)) return true;
    return false;
  }

  // (3) Every vertex q of cell i's polygon is at least as close (power distance, exact) to x_i as
  // to every cell with a polygon in the triangle, and lies on as many bisectors of i with those
  // cells as its type says (B: one, C: two). The cells come from the polygons, not from q's labels,
  // so a vertex with wrong labels is caught. q is equidistant from its own labels by construction:
  // its exact point is the solution of their bisector equations (exact_position, whose equations
  // tests/test_symbolic_vertex.cpp checks exactly), so those pairs are counted without arithmetic.
  void check_equidistance(int t, int begin, int end) {
    present_.clear();
    for (int p = begin; p < end; ++p)
      if (polygon_ok_[p]) present_.push_back(d_.polygons[p].cell);
    if (!std::is_sorted(present_.begin(), present_.end())) std::sort(present_.begin(), present_.end());
    present_.erase(std::unique(present_.begin(), present_.end()), present_.end());
    // Many cells in the triangle: each vertex is compared only with the cells whose sites a
    // certified bound does not rule out (Near), the others being strictly farther from it.
    std::optional<Near> near;
    if (present_.size() > kAllPairsUpTo) near.emplace(d_.sites, present_);
    for (int p = begin; p < end; ++p) {
      if (!polygon_ok_[p]) continue;
      const CellPolygon& poly = d_.polygons[p];
      const int i = poly.cell;
      for (int k = 0; k < poly.vertex_count; ++k) {
        ++out_.equidistant.checked;
        const int id = vertices_.of_diagram_vertex[poly.first_vertex + k];
        const SymbolicVertex& q = d_.vertices[poly.first_vertex + k];
        const ExactVertex& x = vertices_.exact[id];
        int equidistant = 0, closer = -1;  // closer: the first cell strictly closer to q than x_i
        if (near) near->select(x, d_.sites[i], q, compared_);
        {
          CGAL::Protect_FPU_rounding<true> upward;
          std::optional<Interval> e_i;  // d_i(q) - d_j(q) = e_i(q) - e_j(q)
          for (int j : near ? compared_ : present_) {
            if (j == i) continue;
            Sign s = Sign::Zero;
            if (!(q.has_label(i) && q.has_label(j))) {
              if (!e_i) e_i = terms_[i].e(x);
              s = filtered_sign(*e_i - terms_[j].e(x));
              if (s == Sign::Zero) s = compare_power_distance_exact(x, d_.sites[i], d_.sites[j]);
            }
            if (s == Sign::Zero) ++equidistant;
            if (s == Sign::Positive && closer < 0) closer = j;
          }
        }
        std::string problem;
        if (closer >= 0) problem = fmt::format("is closer to x_{} than to x_{}", closer, i);
        if (problem.empty() && equidistant + 1 < q.num_labels())
          problem = fmt::format("is equidistant from x_{} and {} other cell(s) of the triangle, not {}", i, equidistant,
                                q.num_labels() - 1);
        if (!problem.empty())
          out_.equidistant.fail(fmt::format("triangle {}: vertex {} of cell {} {}", t, describe(q), i, problem));
      }
    }
  }

 public:
  // (1) x_i, at its barycentric coordinates taken as exact rationals, lies in the closed polygon of
  // cell i in its triangle.
  void check_samples(int begin, int end) {
    for (int i = begin; i < end; ++i) {
      ++out_.sample_in_cell.checked;
      const int t = i < static_cast<int>(samples_.triangles.size()) ? samples_.triangles[i] : -1;
      if (t < 0 || t >= mesh_.triangle_count() || i >= static_cast<int>(samples_.barycentric.size())) {
        out_.sample_in_cell.fail(fmt::format("sample {}: not located on a triangle", i));
        continue;
      }
      const Triangle& tri = mesh_.triangle(t);
      const Vec3& b = samples_.barycentric[i];
      // Finite and not negative, and not all zero: their exact sum is then positive.
      const bool located = std::isfinite(b.x) && std::isfinite(b.y) && std::isfinite(b.z) && b.x >= 0 && b.y >= 0 &&
                           b.z >= 0 && (b.x > 0 || b.y > 0 || b.z > 0);
      if (!located) {
        out_.sample_in_cell.fail(fmt::format("sample {}: barycentric ({}, {}, {}) is outside its triangle {}", i, b.x, b.y, b.z, t));
        continue;
      }
      const ExactVertex point = ExactVertex::at_barycentric(tri, b, vertices_.exact.context());
      for (int c = 0; c < 3; ++c) corner_[c] = &vertices_.exact[mesh_vertex_[tri[c]]];
      const Frame f = triangle_frame(mesh_, t, corner_);
      bool has_polygon = false, inside = false;
      int holder = -1;
      // First the cell's own polygons where the diagram's order (by cell within a triangle) puts
      // them; when none holds the sample (or the order is broken), every polygon, as below.
      const int first = d_.triangle_offsets[t], last = d_.triangle_offsets[t + 1];
      if (f.valid && 0 <= first && first <= last && last <= static_cast<int>(d_.polygons.size())) {
        int from = first, to = last;  // the first polygon of a cell >= i
        while (from < to) {
          const int mid = from + (to - from) / 2;
          if (d_.polygons[mid].cell < i) from = mid + 1; else to = mid;
        }
        for (int p = from; p < last && d_.polygons[p].cell == i && !inside; ++p)
          inside = polygon_ok_[p] && contains_point(p, point, f);
      }
      for (int p = first; p < last && !inside; ++p) {
        if (!polygon_ok_[p] || !f.valid) continue;
        const bool own = d_.polygons[p].cell == i;
        has_polygon = has_polygon || own;
        const bool contains = contains_point(p, point, f);
        if (contains && own) inside = true;
        if (contains && !own && holder < 0) holder = d_.polygons[p].cell;
      }
      out_.rational_points += point.has_rationals();
      if (inside) continue;
      if (!has_polygon)
        out_.sample_in_cell.fail(fmt::format("sample {}: cell {} has no polygon in the sample's triangle {}", i, i, t));
      else
        out_.sample_in_cell.fail(fmt::format("sample {}: outside its cell's polygon in triangle {}{}", i, t,
                                             holder >= 0 ? fmt::format(" (it lies in cell {}'s)", holder) : ""));
    }
  }

 private:
  // Exact point-in-closed-convex-polygon in the frame. A polygon of zero area (a degenerate
  // input's limit) contains the points of its segment.
  bool contains_point(int p, const ExactVertex& x, const Frame& f) {
    const CellPolygon& poly = d_.polygons[p];
    points_.clear();
    for (int k = 0; k < poly.vertex_count; ++k) points_.push_back(&vertex(poly, k));
    if (points_.size() < 3) return false;
    const bool flat = area_sign_[p] != Sign::Positive;  // known from the triangle pass
    for (size_t k = 0; k < points_.size(); ++k) {
      const Sign s = orient(*points_[k], *points_[(k + 1) % points_.size()], x, f);
      if (s == Sign::Negative || (flat && s != Sign::Zero)) return false;
    }
    if (!flat) return true;
    for (int axis : {f.u, f.v}) {
      bool below = false, above = false;  // some vertex <= x, some >= x along the axis
      for (const ExactVertex* p : points_) {
        below = below || coordinate(p->p(), axis) <= coordinate(x.p(), axis);
        above = above || coordinate(p->p(), axis) >= coordinate(x.p(), axis);
      }
      if (!below || !above) return false;
    }
    return true;
  }

  const SurfaceMesh& mesh_;
  const Samples& samples_;
  const Diagram& d_;
  const VerifyOptions& options_;
  DiagramVerification& out_;
  const VertexIndex& vertices_;
  const std::vector<int>& mesh_vertex_;
  const std::vector<char>& polygon_ok_;
  std::vector<Sign>& area_sign_;
  const std::vector<SiteTerms>& terms_;
  std::vector<const ExactVertex*> points_;
  std::vector<FrameVertex> frame_;  // the triangle's polygons' vertices (load_frame_vertices)
  std::vector<int> first_;          // where each polygon of the triangle starts in frame_
  std::array<FrameVertex, 3> corner_frame_;
  struct DirectedEdge {
    int from, to;                // exact vertex ids, from < to
    int from_vertex, to_vertex;  // indices into Diagram::vertices
    int direction;               // +1 if a polygon runs from -> to, -1 if to -> from
    std::uint8_t edges;          // the triangle's edges both ends lie on by definition
  };
  std::vector<DirectedEdge> edges_;
  std::vector<std::array<int, 3>> along_bc_;
  // bounded_by_triangle: the edges off the mesh edges, by direction; the starts and ends along each.
  std::vector<std::uint64_t> forward_, backward_;
  std::array<std::vector<int>, 3> from_, to_;
  std::vector<int> present_;
  std::array<const ExactVertex*, 3> corner_{};
  // check_overlaps: the polygons to compare; above kAllPairsUpTo of them, their boxes in the frame.
  static constexpr std::size_t kAllPairsUpTo = 16;
  struct FrameBox {
    int polygon;
    double u_lo, u_hi, v_lo, v_hi;
    bool apart(const FrameBox& o) const { return u_hi < o.u_lo || o.u_hi < u_lo || v_hi < o.v_lo || o.v_hi < v_lo; }
  };
  std::vector<int> candidates_;
  std::vector<FrameBox> boxes_;
  std::vector<int> compared_;  // check_equidistance: the cells a vertex is compared with
  std::vector<std::pair<int, int>> pairs_;
};

// Runs `check(begin, end, results)` over [0, count) in fixed chunks, in parallel, and merges the
// chunks' results in order.
template <class Check>
void in_chunks(int count, int chunk, DiagramVerification& out, Check check) {
  const int chunks = (count + chunk - 1) / chunk;
  std::vector<DiagramVerification> parts(chunks);
  tbb::parallel_for(0, chunks, [&](int c) { check(c * chunk, std::min(count, (c + 1) * chunk), parts[c]); });
  for (const DiagramVerification& part : parts)
    for (auto member : {&DiagramVerification::sample_in_cell, &DiagramVerification::connected,
                        &DiagramVerification::equidistant, &DiagramVerification::disjoint,
                        &DiagramVerification::coverage, &DiagramVerification::conforming})
      merge_into(out.*member, part.*member);
  for (const DiagramVerification& part : parts) out.rational_points += part.rational_points;
}

void check_all(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram, const VerifyOptions& options,
               DiagramVerification& out) {
  Checked in(mesh, samples, diagram, options);
  in.index_vertices();
  in_chunks(mesh.triangle_count(), kCheckChunk, out, [&](int begin, int end, DiagramVerification& part) {
    DiagramChecker(in, part).check_triangles(begin, end);
  });
  in_chunks(samples.size(), kCheckChunk, out, [&](int begin, int end, DiagramVerification& part) {
    DiagramChecker(in, part).check_samples(begin, end);
  });
  std::vector<char> piece(diagram.polygons.size());
  for (size_t p = 0; p < piece.size(); ++p) piece[p] = in.polygon_ok[p] && in.area_sign[p] == Sign::Positive;
  check_edges(mesh, samples, diagram, in.polygon_ok, piece, in.vertices, out);
  out.distinct_vertices = static_cast<std::int64_t>(in.vertices.exact.size());
  for (int id = 0; id < static_cast<int>(in.vertices.exact.size()); ++id) {
    const ExactVertex& x = in.vertices.exact[id];
    out.rational_points += x.has_rationals();
    // (3) counts a vertex's own labels as equidistant by construction (check_equidistance). Where
    // a check made its rational point anyway, at ties, the construction is checked too, for free.
    if (!x.has_point()) continue;
    const SymbolicVertex& q = in.vertices.exact.symbolic(id);
    for (int k = 1; k < q.num_labels(); ++k)
      if (compare_power_distance(x, diagram.sites[q.label[0]], diagram.sites[q.label[k]]) != Sign::Zero) {
        out.equidistant.fail(fmt::format("vertex {} is not equidistant from its cells", describe(q)));
        break;
      }
  }
}

}  // namespace

DiagramVerification verify_diagram(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram,
                                   const VerifyOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  DiagramVerification out;
  out.sample_in_cell.promised = !is_power(diagram.kind);
  out.connected.promised = is_localized(diagram.kind);
  const std::string broken = structure_error(mesh, samples, diagram);
  if (!broken.empty()) {
    for (PropertyResult* p : {&out.sample_in_cell, &out.connected, &out.equidistant, &out.disjoint, &out.coverage,
                              &out.conforming})
      p->fail("diagram is malformed: " + broken);
  } else {
    check_all(mesh, samples, diagram, options, out);
  }
  out.passed = true;
  for (const PropertyResult* p : {&out.sample_in_cell, &out.connected, &out.equidistant, &out.disjoint, &out.coverage,
                                  &out.conforming})
    if (p->promised && !p->passed) out.passed = false;
  out.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace lrvd
