// Untangling crossing triangles of the remesh by vertex moves and edge flips decided with exact crossing tests.
#include "remesh/untangle.h"

#include <algorithm>
#include <map>
#include <set>

#include "mesh/self_intersections.h"
#include "metrics/quality.h"
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

}  // namespace

InputCrossings::InputCrossings(const SurfaceMesh& mesh) : mesh_(&mesh), pairs_(intersecting_component_pairs(mesh)) {}

int InputCrossings::component(const Samples& samples, const Triangle& t) const {
  const std::vector<int>& of = mesh_->triangle_components();
  const int c = of[samples.triangles[t[0]]];
  return of[samples.triangles[t[1]]] == c && of[samples.triangles[t[2]]] == c ? c : -1;
}

bool InputCrossings::inherited(const Samples& samples, const Triangle& s, const Triangle& t) const {
  if (pairs_.empty()) return false;
  const int a = component(samples, s), b = component(samples, t);
  return a >= 0 && b >= 0 && a != b && std::binary_search(pairs_.begin(), pairs_.end(), std::pair{std::min(a, b), std::max(a, b)});
}

UntangleResult untangle_crossings(const SurfaceMesh& mesh, const Samples& samples, DualMesh& dual,
                                  const InputCrossings& inherited, const UntangleOptions& options,
                                  const std::vector<std::pair<int, int>>* crossings) {
  UntangleResult result;
  std::vector<Vec3>& p = dual.positions;
  std::vector<Triangle>& tris = dual.triangles;
  const int n = static_cast<int>(p.size()), nt = static_cast<int>(tris.size());
  std::vector<char> proper = proper_triangles(p, tris);
  auto counted = [&](int s, int t) { return !inherited.inherited(samples, tris[s], tris[t]); };
  auto counted_only = [&](const std::vector<std::pair<int, int>>& all) {
    std::vector<std::pair<int, int>> out;
    for (const auto& st : all)
      if (counted(st.first, st.second)) out.push_back(st);
    return out;
  };
  auto crossing_pairs = [&] { return counted_only(find_self_intersections(p, tris, proper)); };
  std::vector<std::pair<int, int>> pairs = crossings ? counted_only(*crossings) : crossing_pairs();
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
  std::vector<double> reach(n, 0);
  for (int v = 0; v < n; ++v) {
    int count = 0;
    for (int t : incident[v])
      for (int w : tris[t])
        if (w != v) reach[v] += distance(original[v], original[w]), ++count;
    if (count > 0) reach[v] = options.max_move * reach[v] / count;
  }

  std::vector<Box> box(nt);
  for (int t = 0; t < nt; ++t) box[t] = box_of(p, tris[t]);
  std::vector<char> moving(nt, 0);  // triangles with a vertex in the group being moved

  // Moves the vertices `group` together by each displacement in turn (one per vertex, or one for
  // all) and keeps the one that leaves the fewest crossing pairs with their triangles, if fewer
  // than now (the nearest among equals). Each vertex stays within its reach of where it started and
  // every triangle keeps the floor.
  auto try_moves = [&](const std::vector<int>& group, const std::vector<Vec3>& displacements) {
    std::vector<int> moved_triangles;
    double group_reach = 0;
    for (int v : group) {
      group_reach = std::max(group_reach, reach[v]);
      for (int t : incident[v])
        if (!moving[t]) moving[t] = 1, moved_triangles.push_back(t);
    }
    if (moved_triangles.empty() || group_reach <= 0) return false;
    Box around = box[moved_triangles[0]];
    for (int t : moved_triangles) around.add(box[t].lo), around.add(box[t].hi);
    around = around.grown(2 * group_reach);
    std::vector<int> near;
    for (int t = 0; t < nt; ++t)
      if (proper[t] && box[t].overlaps(around)) near.push_back(t);
    // Crossing pairs with a moved triangle (pairs of two moved triangles once).
    auto local_crossings = [&] {
      int count = 0;
      for (int s : moved_triangles) {
        if (!proper[s]) continue;
        const Box bs = box_of(p, tris[s]);
        for (int t : near) {
          if (t == s || !counted(s, t) || (moving[t] && t < s) || !bs.overlaps(box_of(p, tris[t]))) continue;
          count += triangles_cross(p, tris[s], tris[t]);
        }
      }
      return count;
    };
    const int current = local_crossings();
    bool improved = false;
    if (current > 0) {
      std::vector<Vec3> from;
      for (int v : group) from.push_back(p[v]);
      int best = current;
      Vec3 best_displacement{0, 0, 0};
      double best_move = 0;
      for (const Vec3& d : displacements) {
        bool ok = true;
        for (size_t k = 0; k < group.size() && ok; ++k) {
          p[group[k]] = from[k] + d;
          ok = distance(p[group[k]], original[group[k]]) <= reach[group[k]];
        }
        for (size_t k = 0; k < group.size() && ok; ++k) ok = acceptable(group[k]);
        if (ok) {
          const int count = local_crossings();
          const double move = norm(d);
          if (count < best || (count == best && best < current && move < best_move))
            best = count, best_displacement = d, best_move = move;
        }
        for (size_t k = 0; k < group.size(); ++k) p[group[k]] = from[k];
      }
      if (best < current) {
        for (size_t k = 0; k < group.size(); ++k) p[group[k]] = from[k] + best_displacement;
        for (int t : moved_triangles) box[t] = box_of(p, tris[t]);
        improved = true;
      }
    }
    for (int t : moved_triangles) moving[t] = 0;
    return improved;
  };
  auto face_normal = [&](int t) {
    const Triangle& f = tris[t];
    return unit(cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]));
  };
  // Displacements of length f * r (f = 1/8 ... 1) along each direction, both ways.
  auto along = [](const std::vector<Vec3>& directions, double r, std::vector<Vec3>& out) {
    for (const Vec3& d : directions)
      for (double f : {1.0 / 8, 1.0 / 4, 1.0 / 2, 1.0})
        for (double sign : {1.0, -1.0}) out.push_back((sign * f * r) * d);
  };
  const std::vector<Vec3> axes = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  // The triangles on each edge, for flips.
  std::map<std::pair<int, int>, std::vector<int>> edge_triangles;
  auto edge_key = [](int a, int b) { return std::pair{std::min(a, b), std::max(a, b)}; };
  for (int t = 0; t < nt; ++t)
    for (int e = 0; e < 3; ++e) edge_triangles[edge_key(tris[t][e], tris[t][(e + 1) % 3])].push_back(t);
  // Crossing pairs of the triangles `ts` with the proper triangles near them (pairs within ts once).
  auto crossings_of = [&](const std::vector<int>& ts) {
    Box around = box_of(p, tris[ts[0]]);
    for (int t : ts) around.add(box_of(p, tris[t]).lo), around.add(box_of(p, tris[t]).hi);
    for (int t : ts) moving[t] = 1;
    int count = 0;
    for (int t = 0; t < nt; ++t) {
      if (!proper[t] || !box[t].overlaps(around)) continue;
      for (int s : ts) {
        if (t == s || !proper[s] || !counted(s, t) || (moving[t] && t < s) || !box_of(p, tris[s]).overlaps(box[t])) continue;
        count += triangles_cross(p, tris[s], tris[t]);
      }
    }
    for (int t : ts) moving[t] = 0;
    return count;
  };
  // Flips edge e of triangle g: (a, b, c) and (b, a, d) become (a, d, c) and (b, c, d), if the
  // edge (c, d) is new, the new triangles are proper, keep the floor and face the way the old ones
  // did, and the crossing count of the two drops.
  auto flip = [&](int g, int e) {
    const int a = tris[g][e], b = tris[g][(e + 1) % 3], c = tris[g][(e + 2) % 3];
    const auto& on_edge = edge_triangles[edge_key(a, b)];
    if (on_edge.size() != 2) return false;
    const int h = on_edge[0] == g ? on_edge[1] : on_edge[0];
    int d = -1;
    for (int k = 0; k < 3; ++k)
      if (tris[h][k] == b && tris[h][(k + 1) % 3] == a) d = tris[h][(k + 2) % 3];
    if (d < 0 || d == c || edge_triangles.count(edge_key(c, d))) return false;
    const Triangle new_g{a, d, c}, new_h{b, c, d};
    const Vec3 facing = normal_before[g] / norm(normal_before[g]) + normal_before[h] / norm(normal_before[h]);
    for (const Triangle& f : {new_g, new_h}) {
      const Vec3 &x = p[f[0]], &y = p[f[1]], &z = p[f[2]];
      if (predicates::collinear(x, y, z) || !(dot(cross(y - x, z - x), facing) > 0)) return false;
      if (triangle_quality(x, y, z) < q_floor || triangle_min_angle(x, y, z) < angle_floor) return false;
    }
    if (!proper[g] || !proper[h]) return false;
    const int before = crossings_of({g, h});
    if (before == 0) return false;
    const Triangle old_g = tris[g], old_h = tris[h];
    tris[g] = new_g, tris[h] = new_h;
    box[g] = box_of(p, new_g), box[h] = box_of(p, new_h);
    if (crossings_of({g, h}) >= before) {
      tris[g] = old_g, tris[h] = old_h;
      box[g] = box_of(p, old_g), box[h] = box_of(p, old_h);
      return false;
    }
    edge_triangles.erase(edge_key(a, b));
    edge_triangles[edge_key(c, d)] = {g, h};
    for (int& t : edge_triangles[edge_key(a, d)]) t = t == h ? g : t;
    for (int& t : edge_triangles[edge_key(b, c)]) t = t == g ? h : t;
    incident[a].erase(std::find(incident[a].begin(), incident[a].end(), h));
    incident[b].erase(std::find(incident[b].begin(), incident[b].end(), g));
    incident[c].push_back(h), incident[d].push_back(g);
    for (int t : {g, h}) {
      const Triangle& f = tris[t];
      q_before[t] = triangle_quality(p[f[0]], p[f[1]], p[f[2]]);
      angle_before[t] = triangle_min_angle(p[f[0]], p[f[1]], p[f[2]]);
      normal_before[t] = cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]);
    }
    ++result.flipped;
    return true;
  };

  for (int pass = 0; pass < options.passes && !pairs.empty(); ++pass) {
    bool any = false;
    // Single vertices of crossing triangles: along the input's normal under the sample, the
    // remesh's vertex normal, the normals of the triangles they cross and the axes, and towards the
    // centroid of the neighbours.
    std::map<int, std::set<int>> crossed;  // vertex -> triangles that its triangles cross
    for (const auto& [s, t] : pairs) {
      for (int v : tris[s]) crossed[v].insert(t);
      for (int v : tris[t]) crossed[v].insert(s);
    }
    for (const auto& [v, others] : crossed) {
      if (incident[v].empty() || reach[v] <= 0) continue;
      Vec3 ring{0, 0, 0}, vertex_normal{0, 0, 0};
      int ring_count = 0;
      for (int t : incident[v]) {
        const Triangle& f = tris[t];
        vertex_normal += cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]);
        for (int w : f)
          if (w != v) ring += p[w], ++ring_count;
      }
      ring = ring / ring_count;
      std::vector<Vec3> directions = {unit(mesh.triangle_normal(samples.triangles[v])), unit(vertex_normal)};
      if (options.more_directions) {
        for (int t : others) directions.push_back(face_normal(t));
        directions.insert(directions.end(), axes.begin(), axes.end());
      }
      std::vector<Vec3> displacements;
      along(directions, reach[v], displacements);
      for (double f : {0.25, 0.5, 1.0}) displacements.push_back(f * (ring - p[v]));
      any |= try_moves({v}, displacements);
    }
    pairs = crossing_pairs();
    // Two or three vertices together: a crossing triangle, or one of its edges, translated along
    // the normal of the triangle it crosses, its own normal or the axes.
    if (options.group_moves)
      for (const auto& [s, t] : pairs) {  // the state the single moves left: group moves keep the triangles
        for (const auto& [g, h] : {std::pair{s, t}, std::pair{t, s}}) {
          const Triangle& f = tris[g];
          double r = reach[f[0]];
          for (int v : f) r = std::min(r, reach[v]);
          std::vector<Vec3> directions = {face_normal(h), face_normal(g)};
          directions.insert(directions.end(), axes.begin(), axes.end());
          std::vector<Vec3> displacements;
          along(directions, r, displacements);
          bool done = try_moves({f[0], f[1], f[2]}, displacements);
          for (int e = 0; e < 3 && !done; ++e) done = try_moves({f[e], f[(e + 1) % 3]}, displacements);
          any |= done;
        }
      }
    // Edge flips: an edge of a crossing triangle is replaced by the other diagonal of its two
    // triangles when the crossing count drops (the connectivity is tangled, not the positions).
    if (options.flip_edges)
      for (const auto& [s, t] : crossing_pairs())
        for (int g : {s, t})
          for (int e = 0; e < 3; ++e)
            if (flip(g, e)) {
              any = true;
              break;
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
