// Verification of a remesh: combinatorics from a sorted edge list (manifoldness, boundary,
// orientation, per-component Euler characteristic), exact geometry through CGAL (collinear corners,
// self-intersections from box_intersection_d candidates and exact Epick triangle tests).
#include "verification/remesh_check.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <numeric>
#include <tuple>

#include <fmt/format.h>

#include "mesh/closest_point.h"
#include "mesh/self_intersections.h"
#include "predicates/predicates.h"

namespace lrvd {

namespace {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

//! One side of an edge: triangle t traverses the edge (lo, hi) from lo to hi when `forward`.
struct HalfEdge {
  int lo, hi, triangle;
  bool forward;
};

//! What the checks share: which triangles take part, and the edges grouped by their two vertices.
struct Combinatorics {
  std::vector<char> usable;            //!< indices in range and three distinct vertices
  std::vector<HalfEdge> half_edges;    //!< sorted by (lo, hi, triangle)
  std::vector<std::size_t> edge_begin;  //!< start of each edge's run in half_edges, plus the end
  std::size_t edge_size(std::size_t e) const { return edge_begin[e + 1] - edge_begin[e]; }
  std::size_t edge_count() const { return edge_begin.size() - 1; }
};

std::string triangle_text(int t, const Triangle& f) { return fmt::format("triangle {} ({}, {}, {})", t, f[0], f[1], f[2]); }

void check_vertex_count(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                        int expected, RemeshVerification& r, Combinatorics& c) {
  PropertyResult& p = r.vertex_count;
  const int n = static_cast<int>(positions.size());
  p.checked = n;
  if (expected >= 0 && n != expected) p.fail(fmt::format("the remesh has {} vertices, {} were requested", n, expected));
  std::vector<char> used(n, 0);
  c.usable.assign(triangles.size(), 1);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int v : triangles[t]) {
      if (v < 0 || v >= n) {
        p.fail(fmt::format("triangle {} refers to vertex {}, but the remesh has {} vertices", t, v, n));
        c.usable[t] = 0;
      } else {
        used[v] = 1;
      }
    }
  for (int v = 0; v < n; ++v)
    if (!used[v]) p.fail(fmt::format("vertex {} is used by no triangle", v));
}

//! Triangles repeating a vertex, duplicate triangles, edges in more than two triangles, vertices
//! whose triangles form several fans. Also builds the edge list the other checks read.
void check_manifold(int vertex_count, const std::vector<Triangle>& triangles, RemeshVerification& r,
                    Combinatorics& c) {
  PropertyResult& p = r.manifold;
  const int m = static_cast<int>(triangles.size());
  for (int t = 0; t < m; ++t) {
    const Triangle& f = triangles[t];
    if (!c.usable[t] || (f[0] != f[1] && f[1] != f[2] && f[2] != f[0])) continue;
    p.fail(fmt::format("{} repeats a vertex", triangle_text(t, f)));
    c.usable[t] = 0;
  }

  std::vector<std::pair<Triangle, int>> sorted;
  for (int t = 0; t < m; ++t)
    if (c.usable[t]) {
      Triangle key = triangles[t];
      std::sort(key.begin(), key.end());
      sorted.push_back({key, t});
    }
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 1; i < sorted.size(); ++i)
    if (sorted[i].first == sorted[i - 1].first)
      p.fail(fmt::format("triangles {} and {} have the same vertices ({}, {}, {})", sorted[i - 1].second,
                         sorted[i].second, sorted[i].first[0], sorted[i].first[1], sorted[i].first[2]));

  for (int t = 0; t < m; ++t) {
    if (!c.usable[t]) continue;
    for (int e = 0; e < 3; ++e) {
      const int a = triangles[t][e], b = triangles[t][(e + 1) % 3];
      c.half_edges.push_back({std::min(a, b), std::max(a, b), t, a < b});
    }
  }
  std::sort(c.half_edges.begin(), c.half_edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.lo, x.hi, x.triangle) < std::tie(y.lo, y.hi, y.triangle);
  });
  for (std::size_t i = 0; i < c.half_edges.size(); ++i)
    if (i == 0 || c.half_edges[i].lo != c.half_edges[i - 1].lo || c.half_edges[i].hi != c.half_edges[i - 1].hi)
      c.edge_begin.push_back(i);
  c.edge_begin.push_back(c.half_edges.size());
  for (std::size_t e = 0; e < c.edge_count(); ++e)
    if (c.edge_size(e) > 2) {
      const HalfEdge& h = c.half_edges[c.edge_begin[e]];
      p.fail(fmt::format("edge ({}, {}) has {} triangles", h.lo, h.hi, c.edge_size(e)));
    }

  // Fans: around v, two triangles are joined when they share an edge (v, x); one class per fan.
  std::vector<int> offsets(vertex_count + 1, 0), incident;
  for (int t = 0; t < m; ++t)
    if (c.usable[t])
      for (int v : triangles[t]) ++offsets[v + 1];
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  incident.resize(offsets.back());
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  for (int t = 0; t < m; ++t)
    if (c.usable[t])
      for (int v : triangles[t]) incident[fill[v]++] = t;
  std::vector<std::pair<int, int>> around;  // (other vertex x of edge (v, x), local triangle index)
  for (int v = 0; v < vertex_count; ++v) {
    const int k = offsets[v + 1] - offsets[v];
    if (k < 2) continue;
    around.clear();
    for (int i = 0; i < k; ++i) {
      const Triangle& f = triangles[incident[offsets[v] + i]];
      for (int x : f)
        if (x != v) around.push_back({x, i});
    }
    std::sort(around.begin(), around.end());
    UnionFind fans(k);
    for (std::size_t j = 1; j < around.size(); ++j)
      if (around[j].first == around[j - 1].first) fans.unite(around[j].second, around[j - 1].second);
    int count = 0;
    for (int i = 0; i < k; ++i) count += fans.find(i) == i;
    if (count > 1) p.fail(fmt::format("vertex {} has {} separate triangle fans", v, count));
  }
  p.checked = static_cast<std::int64_t>(triangles.size() + c.edge_count()) + vertex_count;
}

void check_boundary_and_orientation(const SurfaceMesh& input, RemeshVerification& r, const Combinatorics& c) {
  r.closed.promised = input.is_closed();
  r.closed.checked = r.oriented.checked = 0;
  for (std::size_t e = 0; e < c.edge_count(); ++e) {
    const HalfEdge& h = c.half_edges[c.edge_begin[e]];
    const std::size_t size = c.edge_size(e);
    if (r.closed.promised) ++r.closed.checked;
    if (size == 1 && r.closed.promised)
      r.closed.fail(fmt::format("edge ({}, {}) has only triangle {} (a hole)", h.lo, h.hi, h.triangle));
    if (size != 2) continue;
    ++r.oriented.checked;
    const HalfEdge& g = c.half_edges[c.edge_begin[e] + 1];
    if (h.forward == g.forward)
      r.oriented.fail(fmt::format("edge ({}, {}) is traversed from {} to {} by both triangles {} and {}", h.lo, h.hi,
                                  h.forward ? h.lo : h.hi, h.forward ? h.hi : h.lo, h.triangle, g.triangle));
  }
}

//! Components (triangles joined across edges, so a non-manifold vertex does not join two sheets),
//! their Euler characteristic V - E + F (a vertex counts once in every component it touches) and
//! boundary loops; compared with the input's.
void check_topology(const SurfaceMesh& input, int vertex_count, const std::vector<Triangle>& triangles,
                    RemeshVerification& r, const Combinatorics& c) {
  const int m = static_cast<int>(triangles.size());
  UnionFind joined(m);
  for (std::size_t e = 0; e < c.edge_count(); ++e)
    for (std::size_t i = c.edge_begin[e] + 1; i < c.edge_begin[e + 1]; ++i)
      joined.unite(c.half_edges[c.edge_begin[e]].triangle, c.half_edges[i].triangle);
  std::vector<int> component(m, -1), label(m, -1);
  int components = 0;
  for (int t = 0; t < m; ++t)
    if (c.usable[t]) {
      int& root_label = label[joined.find(t)];
      if (root_label < 0) root_label = components++;
      component[t] = root_label;
    }
  std::vector<long long> chi(components, 0);
  std::vector<int> loops(components, 0);
  for (int t = 0; t < m; ++t)
    if (c.usable[t]) ++chi[component[t]];
  for (std::size_t e = 0; e < c.edge_count(); ++e) --chi[component[c.half_edges[c.edge_begin[e]].triangle]];
  std::vector<std::pair<int, int>> vertex_component;
  for (int t = 0; t < m; ++t)
    if (c.usable[t])
      for (int v : triangles[t]) vertex_component.push_back({v, component[t]});
  std::sort(vertex_component.begin(), vertex_component.end());
  vertex_component.erase(std::unique(vertex_component.begin(), vertex_component.end()), vertex_component.end());
  for (const auto& vc : vertex_component) ++chi[vc.second];

  // Boundary loops: cycles of edges with one triangle (disjoint cycles when the output is manifold).
  UnionFind loop_of(vertex_count);
  for (std::size_t e = 0; e < c.edge_count(); ++e)
    if (c.edge_size(e) == 1) loop_of.unite(c.half_edges[c.edge_begin[e]].lo, c.half_edges[c.edge_begin[e]].hi);
  std::vector<int> loop_component(vertex_count, -1);
  for (std::size_t e = 0; e < c.edge_count(); ++e)
    if (c.edge_size(e) == 1) {
      const HalfEdge& h = c.half_edges[c.edge_begin[e]];
      int& owner = loop_component[loop_of.find(h.lo)];
      if (owner < 0) ++loops[owner = component[h.triangle]];
    }
  r.boundary_loops = std::accumulate(loops.begin(), loops.end(), 0);
  r.input_boundary_loops = static_cast<int>(input.boundary_loops().size());
  r.components = components;
  r.euler_characteristic = static_cast<int>(std::accumulate(chi.begin(), chi.end(), 0LL));
  r.genus = 0;
  for (int k = 0; k < components; ++k) r.genus += static_cast<int>((2 - chi[k] - loops[k]) / 2);
  if (!r.manifold.passed) r.genus = -1;

  // A closed input's holes are the `closed` property's business: compare each component with its
  // boundary loops capped by disks (χ + b, i.e. the genus), so that a hole fails `closed` alone.
  const bool cap = input.is_closed();
  std::vector<long long> output_keys(components), input_keys;
  for (int k = 0; k < components; ++k) output_keys[k] = chi[k] + (cap ? loops[k] : 0);
  for (int x : input.component_euler_characteristics()) input_keys.push_back(x);
  std::sort(output_keys.begin(), output_keys.end());
  std::sort(input_keys.begin(), input_keys.end());
  PropertyResult& p = r.topology;
  p.checked = components;
  auto list = [](const std::vector<long long>& keys) { return fmt::format("{{{}}}", fmt::join(keys, ", ")); };
  if (components != input.component_count())
    p.fail(fmt::format("the remesh has {} connected components, the input {}", components, input.component_count()));
  if (output_keys != input_keys)
    p.fail(fmt::format("Euler characteristics per component{} are {}, the input's {}", cap && r.boundary_loops > 0 ? " (holes capped)" : "",
                       list(output_keys), list(input_keys)));
}

// Geometry: exact collinearity and self-intersections.

std::vector<char> check_non_degenerate(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                                       const std::vector<char>& usable, PropertyResult& p) {
  std::vector<char> finite(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    finite[v] = is_finite(positions[v]);
    if (!finite[v]) p.fail(fmt::format("vertex {} has a non-finite coordinate", v));
  }
  std::vector<char> testable(triangles.size(), 0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!usable[t]) continue;  // out-of-range or repeated indices: reported by vertex_count / manifold
    const Triangle& f = triangles[t];
    if (!finite[f[0]] || !finite[f[1]] || !finite[f[2]]) continue;
    ++p.checked;
    if (predicates::collinear(positions[f[0]], positions[f[1]], positions[f[2]]))
      p.fail(fmt::format("{} has collinear corners", triangle_text(static_cast<int>(t), f)));
    else
      testable[t] = 1;
  }
  return testable;
}

// Counts the pairs of intersecting output triangles. Where two of the input's own components cut
// through each other, a pair from the two output components that lie on them is the input's
// intersection carried over: counted in `inherited`, not as a violation. Each output component lies
// on the input component that most of its vertices are closest to. Pairs within one output
// component, or between output components whose input components do not meet, always count.
int count_self_intersections(const SurfaceMesh& input, const std::vector<Vec3>& positions,
                             const std::vector<Triangle>& triangles, const std::vector<char>& testable,
                             PropertyResult& p, int& inherited) {
  p.checked = std::count(testable.begin(), testable.end(), 1);
  const auto pairs = find_self_intersections(positions, triangles, testable);
  std::vector<int> component;  // of each output triangle, and the input component it lies on
  std::vector<std::pair<int, int>> input_pairs;
  std::map<int, int> lies_on;
  if (!pairs.empty()) input_pairs = intersecting_component_pairs(input);
  if (!input_pairs.empty()) {
    component = soup_components(static_cast<int>(positions.size()), triangles, testable);
    std::map<int, std::map<int, int>> votes;  // output component -> input component -> vertices
    for (const auto& [s, t] : pairs)
      if (component[s] != component[t]) {
        votes[component[s]];
        votes[component[t]];
      }
    const ClosestPointIndex index(input);
    std::vector<char> seen(positions.size(), 0);
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      if (component[t] < 0 || !votes.count(component[t])) continue;
      for (int v : triangles[t]) {
        if (seen[v]) continue;
        seen[v] = 1;
        ++votes[component[t]][input.triangle_components()[index.query(positions[v]).triangle]];
      }
    }
    for (const auto& [c, count] : votes)
      lies_on[c] = std::max_element(count.begin(), count.end(), [](const auto& a, const auto& b) {
                     return a.second < b.second;
                   })->first;
  }
  int counted = 0;
  inherited = 0;
  for (const auto& [s, t] : pairs) {
    if (!component.empty() && component[s] != component[t]) {
      const int a = lies_on[component[s]], b = lies_on[component[t]];
      if (std::binary_search(input_pairs.begin(), input_pairs.end(), std::make_pair(std::min(a, b), std::max(a, b)))) {
        ++inherited;
        continue;
      }
    }
    ++counted;
    p.fail(fmt::format("{} and {} intersect", triangle_text(s, triangles[s]), triangle_text(t, triangles[t])));
  }
  return counted;
}

}  // namespace

RemeshVerification verify_remesh(const SurfaceMesh& input, const std::vector<Vec3>& positions,
                                 const std::vector<Triangle>& triangles, int expected_vertices) {
  const auto start = std::chrono::steady_clock::now();
  RemeshVerification r;
  Combinatorics c;
  const int n = static_cast<int>(positions.size());
  check_vertex_count(positions, triangles, expected_vertices, r, c);
  check_manifold(n, triangles, r, c);
  check_boundary_and_orientation(input, r, c);
  check_topology(input, n, triangles, r, c);
  const std::vector<char> testable = check_non_degenerate(positions, triangles, c.usable, r.non_degenerate);
  r.self_intersecting_pairs = count_self_intersections(input, positions, triangles, testable,
                                                       r.no_self_intersection, r.inherited_intersecting_pairs);

  for (const PropertyResult* p : {&r.vertex_count, &r.manifold, &r.closed, &r.oriented, &r.topology,
                                  &r.non_degenerate, &r.no_self_intersection})
    if (!p->passed && p->promised) r.passed = false;
  r.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}


nlohmann::json RemeshVerification::to_json() const {
  return {{"passed", passed},
          {"time_s", time_s},
          {"components", components},
          {"euler_characteristic", euler_characteristic},
          {"genus", genus},
          {"boundary_loops", boundary_loops},
          {"input_boundary_loops", input_boundary_loops},
          {"self_intersecting_pairs", self_intersecting_pairs},
          {"inherited_intersecting_pairs", inherited_intersecting_pairs},
          {"properties",
           {{"vertex_count", vertex_count.to_json()},
            {"manifold", manifold.to_json()},
            {"closed", closed.to_json()},
            {"oriented", oriented.to_json()},
            {"topology", topology.to_json()},
            {"non_degenerate", non_degenerate.to_json()},
            {"no_self_intersection", no_self_intersection.to_json()}}}};
}

std::string RemeshVerification::summary() const {
  return vertex_count.summary_line("vertex_count") + manifold.summary_line("manifold") +
         closed.summary_line("closed") + oriented.summary_line("oriented") + topology.summary_line("topology") +
         non_degenerate.summary_line("non_degenerate") + no_self_intersection.summary_line("no_self_intersection");
}


}  // namespace lrvd
