// Self-intersections of a triangle soup: candidate pairs from CGAL's box intersection, decided by
// exact Epick triangle / segment tests that account for the vertices or edge a pair shares.
#include "mesh/self_intersections.h"

#include <algorithm>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include "predicates/predicates.h"

namespace lrvd {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

//! The box of a triangle, or of an edge of it; its id, which the box searches use to break ties,
//! is the triangle's index for a triangle's box and one past the triangles for an edge's.
class TriangleBox : public CGAL::Box_intersection_d::Box_d<double, 3, CGAL::Box_intersection_d::ID_NONE> {
 public:
  using Base = CGAL::Box_intersection_d::Box_d<double, 3, CGAL::Box_intersection_d::ID_NONE>;
  using ID = std::size_t;
  TriangleBox(const CGAL::Bbox_3& box, int triangle) : Base(box), triangle_(triangle), id_(triangle) {}
  TriangleBox(const CGAL::Bbox_3& box, int triangle, ID id) : Base(box), triangle_(triangle), id_(id) {}
  ID id() const { return id_; }
  int triangle() const { return triangle_; }

 private:
  int triangle_;
  ID id_;
};

//! Whether two non-degenerate triangles meet anywhere but in the vertices / edge they share.
//! Shared one vertex v: the intersection is convex and contains v, so it holds another point iff
//! the edge opposite v of one triangle meets the other. Shared edge: triangles in different planes
//! meet exactly in it; in one plane they overlap iff the opposite corners lie on the same side.
template <class Points>
bool intersect_illegitimately(const Triangle& f, const Triangle& g, const Points& p) {
  int shared = 0, fi[3], gi[3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (f[i] == g[j]) fi[shared] = i, gi[shared] = j, ++shared;
  const Kernel::Triangle_3 tf(p[f[0]], p[f[1]], p[f[2]]), tg(p[g[0]], p[g[1]], p[g[2]]);
  if (shared == 0) return CGAL::do_intersect(tf, tg);
  if (shared == 1) {
    // Around a vertex of high valence every pair of its triangles is a candidate (their boxes all
    // hold it); an opposite edge's box, which the edge lies in, seldom meets the other triangle's.
    const int i = fi[0], j = gi[0];
    const Kernel::Segment_3 ef(p[f[(i + 1) % 3]], p[f[(i + 2) % 3]]), eg(p[g[(j + 1) % 3]], p[g[(j + 2) % 3]]);
    return (CGAL::do_overlap(ef.bbox(), tg.bbox()) && CGAL::do_intersect(ef, tg)) ||
           (CGAL::do_overlap(eg.bbox(), tf.bbox()) && CGAL::do_intersect(eg, tf));
  }
  if (shared == 2) {
    const Point &u = p[f[fi[0]]], &w = p[f[fi[1]]];
    const Point& pf = p[f[3 - fi[0] - fi[1]]];
    const Point& pg = p[g[3 - gi[0] - gi[1]]];
    if (CGAL::orientation(u, w, pf, pg) != CGAL::COPLANAR) return false;
    return CGAL::coplanar_orientation(u, w, pf, pg) == CGAL::POSITIVE;
  }
  return false;  // the same three vertices: a duplicate, reported by `manifold`
}

// Corners of two triangles as Epick points, indexed by vertex id (at most six distinct ids).
struct SixPoints {
  int id[6];
  Point point[6];
  int count = 0;
  SixPoints(const std::vector<Vec3>& positions, const Triangle& f, const Triangle& g) {
    for (const Triangle* t : {&f, &g})
      for (int v : *t) {
        bool seen = false;
        for (int k = 0; k < count; ++k) seen = seen || id[k] == v;
        if (!seen) id[count] = v, point[count++] = Point(positions[v].x, positions[v].y, positions[v].z);
      }
  }
  const Point& operator[](int v) const {
    int k = 0;
    while (id[k] != v) ++k;
    return point[k];
  }
};

}  // namespace

bool triangles_cross(const std::vector<Vec3>& positions, const Triangle& f, const Triangle& g) {
  return intersect_illegitimately(f, g, SixPoints(positions, f, g));
}

std::vector<char> proper_triangles(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles) {
  std::vector<char> proper(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Triangle& f = triangles[t];
    proper[t] = f[0] != f[1] && f[1] != f[2] && f[0] != f[2] &&
                !predicates::collinear(positions[f[0]], positions[f[1]], positions[f[2]]);
  }
  return proper;
}

namespace {

using Boxes = std::vector<TriangleBox>;

CGAL::Bbox_3 triangle_bbox(const std::vector<Point>& points, const Triangle& f) {
  return points[f[0]].bbox() + points[f[1]].bbox() + points[f[2]].bbox();
}

// Decides each candidate pair as a box search meets it and keeps the crossing ones: only those are
// stored (round a vertex of high valence the candidates number in the hundreds of millions).
struct PairTest {
  const std::vector<Triangle>& triangles;
  const std::vector<Point>& points;
  std::vector<std::pair<int, int>>& pairs;
  void operator()(const TriangleBox& a, const TriangleBox& b) const {
    if (a.triangle() == b.triangle()) return;  // an edge's box and its own triangle's
    const int s = std::min(a.triangle(), b.triangle()), t = std::max(a.triangle(), b.triangle());
    if (intersect_illegitimately(triangles[s], triangles[t], points)) pairs.emplace_back(s, t);
  }
};

// The crossing pairs among the triangles round hubs (vertices of at least `hub_valence` tested
// triangles) without meeting every pair of a hub's fan, whose boxes all hold the hub:
// - a pair of one fan shares its hub, and crosses only if the edge of one opposite the hub meets
//   the other (sharing the hub alone), or the two share that edge's end (an edge from the hub,
//   folded over in one plane): either way that edge's box, which does not hold the hub, meets the
//   other's box, so candidates come from those edges against the fan's triangles;
// - a triangle with a hub is put in one fan (its first hub's); pairs of triangles in different fans
//   are met by a bipartite search for each two fans whose boxes meet or, when those are many, one
//   per bit of the fan numbers (two fans differ in some bit); a triangle without a hub meets the
//   fans' triangles in one more bipartite search;
// - triangles without a hub meet each other in the usual search.
// Each candidate gets the pair test; a pair met more than once is reported once.
void find_round_hubs(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                     const std::vector<char>& testable, const std::vector<int>& valence, int hub_valence,
                     const PairTest& test) {
  // The fan of each triangle with a hub: the number (from 0) of its first hub by index.
  std::vector<int> fan_of_vertex(points.size(), -1);
  int fans = 0;
  for (std::size_t v = 0; v < points.size(); ++v)
    if (valence[v] >= hub_valence) fan_of_vertex[v] = fans++;
  Boxes plain;
  std::vector<Boxes> fan(fans);
  std::vector<int> hub(fans);
  for (std::size_t v = 0; v < points.size(); ++v)
    if (fan_of_vertex[v] >= 0) hub[fan_of_vertex[v]] = static_cast<int>(v);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!testable.empty() && !testable[t]) continue;
    const Triangle& f = triangles[t];
    int first = -1;
    for (int v : f)
      if (fan_of_vertex[v] >= 0 && (first < 0 || v < hub[first])) first = fan_of_vertex[v];
    (first < 0 ? plain : fan[first]).emplace_back(triangle_bbox(points, f), static_cast<int>(t));
  }
  CGAL::box_self_intersection_d(plain.begin(), plain.end(), test);
  Boxes with_hub;  // the searches reorder their ranges: the fans' boxes are copied
  for (const Boxes& b : fan) with_hub.insert(with_hub.end(), b.begin(), b.end());
  CGAL::box_intersection_d(with_hub.begin(), with_hub.end(), plain.begin(), plain.end(), test);
  // Fans whose boxes meet: each such pair's triangles are searched against each other; when most
  // fans meet most others, one search per bit of the fan numbers instead.
  Boxes fan_boxes;
  for (int k = 0; k < fans; ++k) {
    if (fan[k].empty()) continue;  // a hub whose triangles all have a hub of lower index
    CGAL::Bbox_3 box = fan[k].front().bbox();
    for (const TriangleBox& t : fan[k]) box += t.bbox();
    fan_boxes.emplace_back(box, k);
  }
  std::vector<std::pair<int, int>> meeting;
  CGAL::box_self_intersection_d(fan_boxes.begin(), fan_boxes.end(), [&](const TriangleBox& a, const TriangleBox& b) {
    meeting.emplace_back(a.triangle(), b.triangle());
  });
  if (meeting.size() <= 4 * static_cast<std::size_t>(fans)) {
    for (const auto& [k, l] : meeting) {
      Boxes one = fan[k], other = fan[l];
      CGAL::box_intersection_d(one.begin(), one.end(), other.begin(), other.end(), test);
    }
  } else {
    // Two fans differ in several bits: their pairs are tested at the lowest only (tested once).
    std::vector<int> fan_of_triangle(triangles.size(), -1);
    for (int k = 0; k < fans; ++k)
      for (const TriangleBox& t : fan[k]) fan_of_triangle[t.triangle()] = k;
    for (int bit = 1; bit < fans; bit <<= 1) {
      Boxes zero, one;
      for (int k = 0; k < fans; ++k) {
        Boxes& side = k & bit ? one : zero;
        side.insert(side.end(), fan[k].begin(), fan[k].end());
      }
      CGAL::box_intersection_d(zero.begin(), zero.end(), one.begin(), one.end(), [&](const TriangleBox& a, const TriangleBox& b) {
        const int differ = fan_of_triangle[a.triangle()] ^ fan_of_triangle[b.triangle()];
        if ((differ & -differ) == bit) test(a, b);
      });
    }
  }
  for (int k = 0; k < fans; ++k) {
    // The edges of each triangle that do not end at the hub, as boxes named by their triangle.
    Boxes edges;
    for (const TriangleBox& box : fan[k]) {
      const Triangle& f = triangles[box.triangle()];
      for (int e = 0; e < 3; ++e) {
        const int a = f[e], b = f[(e + 1) % 3];
        if (a != hub[k] && b != hub[k])
          edges.emplace_back(points[a].bbox() + points[b].bbox(), box.triangle(), triangles.size() + edges.size());
      }
    }
    Boxes own = fan[k];
    CGAL::box_intersection_d(edges.begin(), edges.end(), own.begin(), own.end(), test);
  }
}

}  // namespace

std::vector<std::pair<int, int>> find_self_intersections(const std::vector<Vec3>& positions,
                                                         const std::vector<Triangle>& triangles,
                                                         const std::vector<char>& testable, int hub_valence) {
  std::vector<Point> points;
  points.reserve(positions.size());
  for (const Vec3& v : positions) points.emplace_back(v.x, v.y, v.z);
  std::vector<std::pair<int, int>> pairs;
  const PairTest test{triangles, points, pairs};
  std::vector<int> valence(points.size(), 0);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (testable.empty() || testable[t])
      for (int v : triangles[t]) ++valence[v];
  if (std::any_of(valence.begin(), valence.end(), [&](int k) { return k >= hub_valence; })) {
    find_round_hubs(points, triangles, testable, valence, hub_valence, test);
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
  }
  Boxes boxes;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (testable.empty() || testable[t]) boxes.emplace_back(triangle_bbox(points, triangles[t]), static_cast<int>(t));
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), test);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<std::pair<int, int>> intersecting_component_pairs(const SurfaceMesh& mesh) {
  std::vector<std::pair<int, int>> out;
  if (mesh.component_count() < 2) return out;
  const std::vector<int>& component = mesh.triangle_components();
  for (const auto& [s, t] : find_self_intersections(mesh.positions(), mesh.triangles()))
    if (component[s] != component[t]) out.emplace_back(std::min(component[s], component[t]), std::max(component[s], component[t]));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<int> soup_components(int vertex_count, const std::vector<Triangle>& triangles,
                                 const std::vector<char>& testable) {
  std::vector<int> parent(vertex_count);
  for (int v = 0; v < vertex_count; ++v) parent[v] = v;
  auto root = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (testable.empty() || testable[t])
      for (int c = 1; c < 3; ++c) {
        const int a = root(triangles[t][0]), b = root(triangles[t][c]);
        if (a != b) parent[a] = b;
      }
  std::vector<int> component(triangles.size(), -1);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (testable.empty() || testable[t]) component[t] = root(triangles[t][0]);
  return component;
}

}  // namespace lrvd
