// Untangling crossing triangles of the remesh by vertex moves and edge flips decided with exact crossing tests.
#include "remesh/untangle.h"

#include <algorithm>
#include <limits>
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

using Pairs = std::vector<std::pair<int, int>>;

// Displacements of length f * r (f = 1/8 ... 1) along each direction, both ways.
void add_along(const std::vector<Vec3>& directions, double r, std::vector<Vec3>& out) {
  for (const Vec3& d : directions)
    for (double f : {1.0 / 8, 1.0 / 4, 1.0 / 2, 1.0})
      for (double sign : {1.0, -1.0}) out.push_back((sign * f * r) * d);
}

const std::vector<Vec3> kAxes = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

// The state untangle_crossings' steps share: the dual being changed, the floor every change keeps,
// each vertex's reach, the triangles' boxes and the triangles on each edge. The public function
// runs the sweeps of `run`: single vertices, groups, flips.
class Untangler {
 public:
  Untangler(const SurfaceMesh& mesh, const Samples& samples, DualMesh& dual, const InputCrossings& inherited,
            const UntangleOptions& options)
      : mesh_(mesh), samples_(samples), p_(dual.positions), tris_(dual.triangles), inherited_(inherited),
        options_(options), n_(static_cast<int>(p_.size())), nt_(static_cast<int>(tris_.size())),
        proper_(proper_triangles(p_, tris_)) {}

  UntangleResult run(const Pairs* crossings);

 private:
  // Whether the crossing of triangles s and t counts: not one the input has too.
  bool counted(int s, int t) const { return !inherited_.inherited(samples_, tris_[s], tris_[t]); }
  Pairs counted_only(const Pairs& all) const {
    Pairs out;
    for (const auto& st : all)
      if (counted(st.first, st.second)) out.push_back(st);
    return out;
  }
  Pairs crossing_pairs() const { return counted_only(find_self_intersections(p_, tris_, proper_)); }

  void record_floor();
  void measure_reach();
  void index_edges();
  bool acceptable(int v) const;
  Vec3 face_normal(int t) const {
    const Triangle& f = tris_[t];
    return unit(cross(p_[f[1]] - p_[f[0]], p_[f[2]] - p_[f[0]]));
  }

  bool move_single_vertices(const Pairs& pairs);
  bool move_groups(const Pairs& pairs);
  bool flip_crossing_edges();
  bool try_moves(const std::vector<int>& group, const std::vector<Vec3>& displacements);
  int local_crossings(const std::vector<int>& moved_triangles, const std::vector<std::vector<int>>& near,
                      int limit = std::numeric_limits<int>::max()) const;
  int crossings_of(const std::vector<int>& ts);
  bool flip(int g, int e);

  static std::pair<int, int> edge_key(int a, int b) { return std::pair{std::min(a, b), std::max(a, b)}; }

  const SurfaceMesh& mesh_;
  const Samples& samples_;
  std::vector<Vec3>& p_;
  std::vector<Triangle>& tris_;
  const InputCrossings& inherited_;
  const UntangleOptions& options_;
  const int n_, nt_;
  std::vector<char> proper_;
  UntangleResult result_;
  std::vector<Vec3> original_;  // the positions before any move
  std::vector<std::vector<int>> incident_;
  // The floor, per triangle and for the mesh; updated for the two triangles of a flip.
  std::vector<double> q_before_, angle_before_;
  std::vector<Vec3> normal_before_;
  double q_floor_ = 1, angle_floor_ = 0;
  std::vector<double> reach_;
  std::vector<Box> box_;
  std::vector<char> moving_;  // triangles with a vertex in the group being moved
  std::map<std::pair<int, int>, std::vector<int>> edge_triangles_;
};

UntangleResult Untangler::run(const Pairs* crossings) {
  Pairs pairs = crossings ? counted_only(*crossings) : crossing_pairs();
  result_.crossings_before = result_.crossings_after = static_cast<int>(pairs.size());
  result_.remaining = pairs;
  if (pairs.empty()) return result_;
  original_ = p_;
  record_floor();
  measure_reach();
  box_.resize(nt_);
  for (int t = 0; t < nt_; ++t) box_[t] = box_of(p_, tris_[t]);
  moving_.assign(nt_, 0);
  index_edges();

  for (int pass = 0; pass < options_.passes && !pairs.empty(); ++pass) {
    bool any = move_single_vertices(pairs);
    pairs = crossing_pairs();
    if (options_.group_moves) any |= move_groups(pairs);  // the state the single moves left
    if (options_.flip_edges) any |= flip_crossing_edges();
    pairs = crossing_pairs();
    if (!any) break;
  }
  result_.crossings_after = static_cast<int>(pairs.size());
  result_.remaining = pairs;
  for (int v = 0; v < n_; ++v)
    if (p_[v] != original_[v]) {
      ++result_.moved;
      result_.max_displacement = std::max(result_.max_displacement, distance(p_[v], original_[v]));
    }
  return result_;
}

// The floor, as in fit_to_surface: no triangle below the mesh's worst Q and smallest angle (30°
// at most), or below its own value if it was worse already; no triangle turns over.
void Untangler::record_floor() {
  incident_.assign(n_, {});
  q_before_.resize(nt_), angle_before_.resize(nt_), normal_before_.resize(nt_);
  q_floor_ = 1, angle_floor_ = options_.max_angle_floor;
  for (int t = 0; t < nt_; ++t) {
    const Triangle& f = tris_[t];
    q_before_[t] = triangle_quality(p_[f[0]], p_[f[1]], p_[f[2]]);
    angle_before_[t] = triangle_min_angle(p_[f[0]], p_[f[1]], p_[f[2]]);
    normal_before_[t] = cross(p_[f[1]] - p_[f[0]], p_[f[2]] - p_[f[0]]);
    q_floor_ = std::min(q_floor_, q_before_[t]);
    angle_floor_ = std::min(angle_floor_, angle_before_[t]);
    for (int v : f) incident_[v].push_back(t);
  }
}

// Mean edge length around each vertex, before any move: the scale of its moves.
void Untangler::measure_reach() {
  reach_.assign(n_, 0);
  for (int v = 0; v < n_; ++v) {
    int count = 0;
    for (int t : incident_[v])
      for (int w : tris_[t])
        if (w != v) reach_[v] += distance(original_[v], original_[w]), ++count;
    if (count > 0) reach_[v] = options_.max_move * reach_[v] / count;
  }
}

// The triangles on each edge, for flips.
void Untangler::index_edges() {
  for (int t = 0; t < nt_; ++t)
    for (int e = 0; e < 3; ++e) edge_triangles_[edge_key(tris_[t][e], tris_[t][(e + 1) % 3])].push_back(t);
}

bool Untangler::acceptable(int v) const {
  for (int t : incident_[v]) {
    const Triangle& f = tris_[t];
    const Vec3 &a = p_[f[0]], &b = p_[f[1]], &c = p_[f[2]];
    if (triangle_quality(a, b, c) < std::min(q_before_[t], q_floor_)) return false;
    if (triangle_min_angle(a, b, c) < std::min(angle_before_[t], angle_floor_)) return false;
    if (!(dot(cross(b - a, c - a), normal_before_[t]) > 0)) return false;
    if (proper_[t] && predicates::collinear(a, b, c)) return false;
  }
  return true;
}

// Single vertices of crossing triangles: along the input's normal under the sample, the remesh's
// vertex normal, the normals of the triangles they cross and the axes, and towards the centroid of
// the neighbours.
bool Untangler::move_single_vertices(const Pairs& pairs) {
  bool any = false;
  std::map<int, std::set<int>> crossed;  // vertex -> triangles that its triangles cross
  for (const auto& [s, t] : pairs) {
    for (int v : tris_[s]) crossed[v].insert(t);
    for (int v : tris_[t]) crossed[v].insert(s);
  }
  for (const auto& [v, others] : crossed) {
    if (incident_[v].empty() || reach_[v] <= 0) continue;
    Vec3 ring{0, 0, 0}, vertex_normal{0, 0, 0};
    int ring_count = 0;
    for (int t : incident_[v]) {
      const Triangle& f = tris_[t];
      vertex_normal += cross(p_[f[1]] - p_[f[0]], p_[f[2]] - p_[f[0]]);
      for (int w : f)
        if (w != v) ring += p_[w], ++ring_count;
    }
    ring = ring / ring_count;
    std::vector<Vec3> directions = {unit(mesh_.triangle_normal(samples_.triangles[v])), unit(vertex_normal)};
    if (options_.more_directions) {
      for (int t : others) directions.push_back(face_normal(t));
      directions.insert(directions.end(), kAxes.begin(), kAxes.end());
    }
    std::vector<Vec3> displacements;
    add_along(directions, reach_[v], displacements);
    for (double f : {0.25, 0.5, 1.0}) displacements.push_back(f * (ring - p_[v]));
    any |= try_moves({v}, displacements);
  }
  return any;
}

// Two or three vertices together: a crossing triangle, or one of its edges, translated along the
// normal of the triangle it crosses, its own normal or the axes.
bool Untangler::move_groups(const Pairs& pairs) {
  bool any = false;
  for (const auto& [s, t] : pairs) {
    for (const auto& [g, h] : {std::pair{s, t}, std::pair{t, s}}) {
      const Triangle& f = tris_[g];
      double r = reach_[f[0]];
      for (int v : f) r = std::min(r, reach_[v]);
      std::vector<Vec3> directions = {face_normal(h), face_normal(g)};
      directions.insert(directions.end(), kAxes.begin(), kAxes.end());
      std::vector<Vec3> displacements;
      add_along(directions, r, displacements);
      bool done = try_moves({f[0], f[1], f[2]}, displacements);
      for (int e = 0; e < 3 && !done; ++e) done = try_moves({f[e], f[(e + 1) % 3]}, displacements);
      any |= done;
    }
  }
  return any;
}

// Edge flips: an edge of a crossing triangle is replaced by the other diagonal of its two
// triangles when the crossing count drops (the connectivity is tangled, not the positions).
bool Untangler::flip_crossing_edges() {
  bool any = false;
  for (const auto& [s, t] : crossing_pairs())
    for (int g : {s, t})
      for (int e = 0; e < 3; ++e)
        if (flip(g, e)) {
          any = true;
          break;
        }
  return any;
}

// Moves the vertices `group` together by each displacement in turn (one per vertex, or one for
// all) and keeps the one that leaves the fewest crossing pairs with their triangles, if fewer
// than now (the nearest among equals). Each vertex stays within its reach of where it started and
// every triangle keeps the floor.
bool Untangler::try_moves(const std::vector<int>& group, const std::vector<Vec3>& displacements) {
  std::vector<int> moved_triangles;
  double group_reach = 0;
  for (int v : group) {
    group_reach = std::max(group_reach, reach_[v]);
    for (int t : incident_[v])
      if (!moving_[t]) moving_[t] = 1, moved_triangles.push_back(t);
  }
  if (moved_triangles.empty() || group_reach <= 0) return false;
  // Every vertex stays within its reach of where it started, so within twice the reach of where
  // it is: the triangles each moved one can meet in any trial, once (pairs of two moved
  // triangles from the one of larger index).
  std::vector<std::vector<int>> near(moved_triangles.size());
  for (size_t i = 0; i < moved_triangles.size(); ++i) {
    const int s = moved_triangles[i];
    if (!proper_[s]) continue;
    const Box around = box_[s].grown(2 * group_reach);
    for (int t = 0; t < nt_; ++t) {
      if (t == s || !proper_[t] || (moving_[t] && t < s) || !counted(s, t)) continue;
      if (moving_[t] || box_[t].overlaps(around)) near[i].push_back(t);
    }
  }
  const int current = local_crossings(moved_triangles, near);
  bool improved = false;
  if (current > 0) {
    std::vector<Vec3> from;
    for (int v : group) from.push_back(p_[v]);
    // Shortest first (in their order among equals): a later trial wins only with fewer crossings,
    // so counting stops at the best so far, and the trials at the first that leaves none.
    std::vector<std::pair<double, int>> by_length;
    for (size_t k = 0; k < displacements.size(); ++k) by_length.push_back({norm(displacements[k]), static_cast<int>(k)});
    std::stable_sort(by_length.begin(), by_length.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    int best = current;
    Vec3 best_displacement{0, 0, 0};
    for (const auto& [length, index] : by_length) {
      const Vec3& d = displacements[index];
      bool ok = true;
      for (size_t k = 0; k < group.size() && ok; ++k) {
        p_[group[k]] = from[k] + d;
        ok = distance(p_[group[k]], original_[group[k]]) <= reach_[group[k]];
      }
      for (size_t k = 0; k < group.size() && ok; ++k) ok = acceptable(group[k]);
      if (ok) {
        const int count = local_crossings(moved_triangles, near, best);
        if (count < best) best = count, best_displacement = d;
      }
      for (size_t k = 0; k < group.size(); ++k) p_[group[k]] = from[k];
      if (best == 0) break;
    }
    if (best < current) {
      for (size_t k = 0; k < group.size(); ++k) p_[group[k]] = from[k] + best_displacement;
      for (int t : moved_triangles) box_[t] = box_of(p_, tris_[t]);
      improved = true;
    }
  }
  for (int t : moved_triangles) moving_[t] = 0;
  return improved;
}

// Crossing pairs of each moved triangle with the triangles try_moves listed for it; the count
// stops at `limit`.
int Untangler::local_crossings(const std::vector<int>& moved_triangles, const std::vector<std::vector<int>>& near,
                               int limit) const {
  int count = 0;
  for (size_t i = 0; i < moved_triangles.size(); ++i) {
    if (near[i].empty()) continue;
    const int s = moved_triangles[i];
    const Box bs = box_of(p_, tris_[s]);
    for (int t : near[i])
      if (bs.overlaps(moving_[t] ? box_of(p_, tris_[t]) : box_[t]) && triangles_cross(p_, tris_[s], tris_[t]))
        if (++count >= limit) return count;
  }
  return count;
}

// Crossing pairs of the triangles `ts` with the proper triangles near them (pairs within ts once).
int Untangler::crossings_of(const std::vector<int>& ts) {
  Box around = box_of(p_, tris_[ts[0]]);
  for (int t : ts) around.add(box_of(p_, tris_[t]).lo), around.add(box_of(p_, tris_[t]).hi);
  for (int t : ts) moving_[t] = 1;
  int count = 0;
  for (int t = 0; t < nt_; ++t) {
    if (!proper_[t] || !box_[t].overlaps(around)) continue;
    for (int s : ts) {
      if (t == s || !proper_[s] || !counted(s, t) || (moving_[t] && t < s) || !box_of(p_, tris_[s]).overlaps(box_[t]))
        continue;
      count += triangles_cross(p_, tris_[s], tris_[t]);
    }
  }
  for (int t : ts) moving_[t] = 0;
  return count;
}

// Flips edge e of triangle g: (a, b, c) and (b, a, d) become (a, d, c) and (b, c, d), if the
// edge (c, d) is new, the new triangles are proper, keep the floor and face the way the old ones
// did, and the crossing count of the two drops.
bool Untangler::flip(int g, int e) {
  const int a = tris_[g][e], b = tris_[g][(e + 1) % 3], c = tris_[g][(e + 2) % 3];
  const auto& on_edge = edge_triangles_[edge_key(a, b)];
  if (on_edge.size() != 2) return false;
  const int h = on_edge[0] == g ? on_edge[1] : on_edge[0];
  int d = -1;
  for (int k = 0; k < 3; ++k)
    if (tris_[h][k] == b && tris_[h][(k + 1) % 3] == a) d = tris_[h][(k + 2) % 3];
  if (d < 0 || d == c || edge_triangles_.count(edge_key(c, d))) return false;
  const Triangle new_g{a, d, c}, new_h{b, c, d};
  const Vec3 facing = normal_before_[g] / norm(normal_before_[g]) + normal_before_[h] / norm(normal_before_[h]);
  for (const Triangle& f : {new_g, new_h}) {
    const Vec3 &x = p_[f[0]], &y = p_[f[1]], &z = p_[f[2]];
    if (predicates::collinear(x, y, z) || !(dot(cross(y - x, z - x), facing) > 0)) return false;
    if (triangle_quality(x, y, z) < q_floor_ || triangle_min_angle(x, y, z) < angle_floor_) return false;
  }
  if (!proper_[g] || !proper_[h]) return false;
  const int before = crossings_of({g, h});
  if (before == 0) return false;
  const Triangle old_g = tris_[g], old_h = tris_[h];
  tris_[g] = new_g, tris_[h] = new_h;
  box_[g] = box_of(p_, new_g), box_[h] = box_of(p_, new_h);
  if (crossings_of({g, h}) >= before) {
    tris_[g] = old_g, tris_[h] = old_h;
    box_[g] = box_of(p_, old_g), box_[h] = box_of(p_, old_h);
    return false;
  }
  edge_triangles_.erase(edge_key(a, b));
  edge_triangles_[edge_key(c, d)] = {g, h};
  for (int& t : edge_triangles_[edge_key(a, d)]) t = t == h ? g : t;
  for (int& t : edge_triangles_[edge_key(b, c)]) t = t == g ? h : t;
  incident_[a].erase(std::find(incident_[a].begin(), incident_[a].end(), h));
  incident_[b].erase(std::find(incident_[b].begin(), incident_[b].end(), g));
  incident_[c].push_back(h), incident_[d].push_back(g);
  for (int t : {g, h}) {
    const Triangle& f = tris_[t];
    q_before_[t] = triangle_quality(p_[f[0]], p_[f[1]], p_[f[2]]);
    angle_before_[t] = triangle_min_angle(p_[f[0]], p_[f[1]], p_[f[2]]);
    normal_before_[t] = cross(p_[f[1]] - p_[f[0]], p_[f[2]] - p_[f[0]]);
  }
  ++result_.flipped;
  return true;
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
  return Untangler(mesh, samples, dual, inherited, options).run(crossings);
}

}  // namespace lrvd
