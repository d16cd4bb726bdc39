// Untangling crossing triangles of the remesh by single-vertex moves decided with exact crossing tests.
#include "remesh/untangle.h"

#include <algorithm>
#include <set>

#include "metrics/quality.h"
#include "metrics/self_intersections.h"
#include "predicates/predicates.h"

namespace lrvd {

namespace {

struct Box {
  Vec3 lo, hi;
  void add(const Vec3& p) {
    for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], p[c]), hi[c] = std::max(hi[c], p[c]);
  }
  bool overlaps(const Box& o) const {
    for (int c = 0; c < 3; ++c)
      if (lo[c] > o.hi[c] || o.lo[c] > hi[c]) return false;
    return true;
  }
  Box grown(double r) const { return {lo - Vec3{r, r, r}, hi + Vec3{r, r, r}}; }
};

Box box_of(const std::vector<Vec3>& p, const Triangle& f) {
  Box b{p[f[0]], p[f[0]]};
  b.add(p[f[1]]);
  b.add(p[f[2]]);
  return b;
}

Vec3 unit(const Vec3& v) {
  const double l = norm(v);
  return l > 0 ? v / l : Vec3{0, 0, 0};
}

}  // namespace

UntangleResult untangle_crossings(const SurfaceMesh& mesh, const Samples& samples, DualMesh& dual,
                                  bool ignore_between_components, const UntangleOptions& options) {
  UntangleResult result;
  std::vector<Vec3>& p = dual.positions;
  const std::vector<Triangle>& tris = dual.triangles;
  const int n = static_cast<int>(p.size()), nt = static_cast<int>(tris.size());
  const std::vector<char> proper = proper_triangles(p, tris);
  const std::vector<int> component = ignore_between_components ? soup_components(n, tris, proper) : std::vector<int>();
  auto counted = [&](int s, int t) { return component.empty() || component[s] == component[t]; };
  auto crossing_pairs = [&] {
    std::vector<std::pair<int, int>> out;
    for (const auto& st : find_self_intersections(p, tris, proper))
      if (counted(st.first, st.second)) out.push_back(st);
    return out;
  };
  std::vector<std::pair<int, int>> pairs = crossing_pairs();
  result.crossings_before = result.crossings_after = static_cast<int>(pairs.size());
  result.remaining = pairs;
  if (pairs.empty()) return result;

  // The floor, as in fit_to_surface: no triangle below the mesh's worst Q and smallest angle (30°
  // at most), or below its own value if it was worse already; no triangle turns over.
  const std::vector<Vec3> original = p;
  std::vector<std::vector<int>> incident(n);
  std::vector<double> q_before(nt), angle_before(nt);
  std::vector<Vec3> normal_before(nt);
  double q_floor = 1, angle_floor = options.max_angle_floor;
  for (int t = 0; t < nt; ++t) {
    const Triangle& f = tris[t];
    q_before[t] = triangle_quality(p[f[0]], p[f[1]], p[f[2]]);
    angle_before[t] = triangle_min_angle(p[f[0]], p[f[1]], p[f[2]]);
    normal_before[t] = cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]);
    q_floor = std::min(q_floor, q_before[t]);
    angle_floor = std::min(angle_floor, angle_before[t]);
    for (int v : f) incident[v].push_back(t);
  }
  auto acceptable = [&](int v) {
    for (int t : incident[v]) {
      const Triangle& f = tris[t];
      const Vec3 &a = p[f[0]], &b = p[f[1]], &c = p[f[2]];
      if (triangle_quality(a, b, c) < std::min(q_before[t], q_floor)) return false;
      if (triangle_min_angle(a, b, c) < std::min(angle_before[t], angle_floor)) return false;
      if (!(dot(cross(b - a, c - a), normal_before[t]) > 0)) return false;
      if (proper[t] && predicates::collinear(a, b, c)) return false;
    }
    return true;
  };
  // Mean edge length around each vertex, before any move: the scale of its moves.
  std::vector<double> scale(n, 0);
  for (int v = 0; v < n; ++v) {
    int count = 0;
    for (int t : incident[v])
      for (int w : tris[t])
        if (w != v) scale[v] += distance(original[v], original[w]), ++count;
    if (count > 0) scale[v] /= count;
  }
  std::vector<Box> box(nt);
  for (int t = 0; t < nt; ++t) box[t] = box_of(p, tris[t]);
  // Crossing pairs with a triangle of v (pairs of two of v's triangles once), among `near`.
  auto local_crossings = [&](int v, const std::vector<int>& near) {
    int count = 0;
    for (int s : incident[v]) {
      if (!proper[s]) continue;
      const Box bs = box_of(p, tris[s]);
      for (int t : near) {
        if (t == s || !counted(s, t) || !bs.overlaps(box_of(p, tris[t]))) continue;
        const bool t_incident = std::find(tris[t].begin(), tris[t].end(), v) != tris[t].end();
        if (t_incident && t < s) continue;
        count += triangles_cross(p, tris[s], tris[t]);
      }
    }
    return count;
  };

  for (int pass = 0; pass < options.passes && !pairs.empty(); ++pass) {
    std::set<int> involved;
    for (const auto& [s, t] : pairs)
      for (int u : {s, t}) involved.insert(tris[u].begin(), tris[u].end());
    bool any = false;
    for (int v : involved) {
      if (incident[v].empty() || scale[v] <= 0) continue;
      const double reach = options.max_move * scale[v];
      // Triangles that a move of v within reach can meet.
      Box around = box[incident[v][0]];
      for (int t : incident[v]) around.add(box[t].lo), around.add(box[t].hi);
      around = around.grown(2 * reach);
      std::vector<int> near;
      for (int t = 0; t < nt; ++t)
        if (proper[t] && box[t].overlaps(around)) near.push_back(t);
      const Vec3 from = p[v];
      const int current = local_crossings(v, near);
      if (current == 0) continue;
      // Candidate moves: along the input's normal under the sample, along the remesh's vertex
      // normal (both ways), and towards the centroid of the neighbours.
      Vec3 ring{0, 0, 0}, vertex_normal{0, 0, 0};
      int ring_count = 0;
      for (int t : incident[v]) {
        const Triangle& f = tris[t];
        vertex_normal += cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]);
        for (int w : f)
          if (w != v) ring += p[w], ++ring_count;
      }
      ring = ring / ring_count;
      std::vector<Vec3> candidates;
      const Vec3 directions[] = {unit(mesh.triangle_normal(samples.triangles[v])), unit(vertex_normal)};
      for (const Vec3& d : directions)
        for (double f : {1.0 / 8, 1.0 / 4, 1.0 / 2, 1.0})
          for (double sign : {1.0, -1.0}) candidates.push_back(from + (sign * f * reach) * d);
      for (double f : {0.25, 0.5, 1.0}) candidates.push_back(from + f * (ring - from));
      int best = current;
      Vec3 best_position = from;
      double best_move = 0;
      for (const Vec3& c : candidates) {
        if (distance(c, original[v]) > reach) continue;
        p[v] = c;
        if (acceptable(v)) {
          const int count = local_crossings(v, near);
          const double move = distance(c, from);
          if (count < best || (count == best && best < current && move < best_move))
            best = count, best_position = c, best_move = move;
        }
        p[v] = from;
      }
      if (best < current) {
        p[v] = best_position;
        for (int t : incident[v]) box[t] = box_of(p, tris[t]);
        any = true;
      }
    }
    pairs = crossing_pairs();
    if (!any) break;
  }
  result.crossings_after = static_cast<int>(pairs.size());
  result.remaining = pairs;
  for (int v = 0; v < n; ++v)
    if (p[v] != original[v]) {
      ++result.moved;
      result.max_displacement = std::max(result.max_displacement, distance(p[v], original[v]));
    }
  return result;
}

}  // namespace lrvd
