// The samples of balance_offsets on both surfaces and their measured distances.
#include "remesh/fit_offsets_samples.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <tbb/parallel_for.h>

#include "mesh/closest_point.h"
#include "mesh/self_intersections.h"

namespace lrvd::fit_detail {

namespace {

// Barycentric lattice points of a triangle at level k, without its corners, each edge's points
// only from the triangle that has the edge's lower vertex first (so they come once on an oriented
// manifold), and the centroid when the lattice has edge points but no interior point (a triangle
// shorter than the spacing has its corners only).
void lattice(const Triangle& f, int k, std::vector<Vec3>& out) {
  for (int i = 0; i <= k; ++i)
    for (int j = 0; i + j <= k; ++j) {
      const int l = k - i - j;
      const int zeros = (i == 0) + (j == 0) + (l == 0);
      if (zeros >= 2) continue;
      if (zeros == 1) {
        // Corners of the edge: the two with a nonzero weight, in the triangle's order.
        const int missing = i == 0 ? 0 : j == 0 ? 1 : 2;
        if (f[(missing + 1) % 3] > f[(missing + 2) % 3]) continue;
      }
      out.push_back({i / double(k), j / double(k), l / double(k)});
    }
  if (k == 2) out.push_back({1 / 3.0, 1 / 3.0, 1 / 3.0});
}

// The lattice level for a spacing, even from 2 on (so that the edge midpoints are samples: a chord's
// distance to a bend is largest there), at least `lowest`.
int lattice_level(const Vec3& a, const Vec3& b, const Vec3& c, double spacing, int lowest) {
  const double longest = std::max({distance(a, b), distance(b, c), distance(c, a)});
  const int k = std::clamp(static_cast<int>(std::ceil(longest / spacing)), lowest, 16);
  return k == 1 ? 1 : k + k % 2;
}

Vec3 at(const std::vector<Vec3>& positions, const Triangle& f, const Vec3& b) {
  return b.x * positions[f[0]] + b.y * positions[f[1]] + b.z * positions[f[2]];
}

// Outward unit direction from `from` to `to` given the normal at `from`, and the signed length.
void signed_offset(const Vec3& to, const Vec3& from, const Vec3& normal, double& d, Vec3& direction) {
  const Vec3 u = to - from;
  const double length = norm(u);
  const double sign = dot(u, normal) >= 0 ? 1.0 : -1.0;
  d = sign * length;
  direction = length > 1e-12 * (norm(to) + norm(from)) ? (sign / length) * u : normal;
}

}  // namespace

OffsetSamples::OffsetSamples(const SurfaceMesh& mesh, DualMesh& dual, const OffsetOptions& options,
                             const ClosestPointIndex* mesh_index, const std::vector<int>* input_vertex_cell)
    : mesh_(mesh), dual_(dual), options_(options), proper_(proper_triangles(dual.positions, dual.triangles)) {
  if (!mesh_index) own_index_.emplace(mesh);
  mesh_index_ = mesh_index ? mesh_index : &*own_index_;
  for (int t = 0; t < static_cast<int>(dual_.triangles.size()); ++t)
    if (proper_[t]) proper_triangles_.push_back(dual_.triangles[t]), dual_triangle_.push_back(t);
  place_samples();
  if (input_vertex_cell) hint_input_vertices(*input_vertex_cell);
  on_boundary_.assign(dual.positions.size(), 0);
  std::vector<std::pair<int, int>> edges;
  for (const Triangle& f : dual.triangles)
    for (int e = 0; e < 3; ++e) edges.push_back({std::min(f[e], f[(e + 1) % 3]), std::max(f[e], f[(e + 1) % 3])});
  std::sort(edges.begin(), edges.end());
  for (size_t i = 0, j; i < edges.size(); i = j) {
    for (j = i + 1; j < edges.size() && edges[j] == edges[i];) ++j;
    if (j - i == 1) on_boundary_[edges[i].first] = on_boundary_[edges[i].second] = 1;
  }
  moved_.assign(dual.positions.size(), 1);
}

double OffsetSamples::measure(double floor) {
  const int nr = static_cast<int>(remesh_.size()), ni = static_cast<int>(input_points_.size());
  // Only the samples on triangles with a moved corner can have changed (an input sample's
  // distance to its old triangle is unchanged then, so its stale value is an upper bound).
  // Samples at the remesh's boundary are measured again whenever they moved: off an open input's
  // boundary, in the surface, the distance grows at once, which a value linearised from 0 (whose
  // direction is then the normal) does not show.
  auto moved = [&](const Sample& s) {
    if (s.triangle < 0) return true;
    const Triangle& f = dual_.triangles[s.triangle];
    return (moved_[f[0]] || moved_[f[1]] || moved_[f[2]]) &&
           (std::abs(s.d) >= floor || on_boundary_[f[0]] || on_boundary_[f[1]] || on_boundary_[f[2]]);
  };
  // The remesh's index only when an input sample is measured.
  std::optional<ClosestPointIndex> remesh_index;
  if (std::any_of(input_.begin(), input_.end(), moved)) remesh_index.emplace(dual_.positions, proper_triangles_);
  tbb::parallel_for(tbb::blocked_range<int>(0, nr + ni, 1024), [&](const tbb::blocked_range<int>& range) {
    // A sample's last answer, or else the answer of the sample before it (samples come in the
    // order of their triangles), starts the search: hints only prune it, the answer is the same.
    int last_on_mesh = -1, last_on_remesh = -1;
    for (int i = range.begin(); i < range.end(); ++i) {
      if (!moved(sample(i))) continue;
      if (i < nr) {
        Sample& s = remesh_[i];
        const Vec3 x = at(dual_.positions, dual_.triangles[s.triangle], s.barycentric);
        const ClosestPoint c = mesh_index_->query(x, s.hint >= 0 ? s.hint : last_on_mesh);
        s.hint = last_on_mesh = c.triangle;
        signed_offset(x, c.point, mesh_.triangle_normal(c.triangle), s.d, s.direction);
      } else {
        Sample& s = input_[i - nr];
        const ClosestPoint c = remesh_index->query(input_points_[i - nr], s.hint >= 0 ? s.hint : last_on_remesh);
        if (c.triangle < 0) {  // the remesh has no proper triangle to measure against: not measured
          s.triangle = -1, s.d = 0;
          continue;
        }
        s.hint = last_on_remesh = c.triangle;
        s.triangle = dual_triangle_[c.triangle];
        s.barycentric = c.barycentric;
        // The input point is outside the remesh when d < 0: the remesh must move out.
        signed_offset(input_points_[i - nr], c.point, triangle_normal(s.triangle), s.d, s.direction);
        s.d = -s.d;
      }
    }
  });
  double largest = 0;
  for (const std::vector<Sample>* list : {&remesh_, &input_})
    for (const Sample& s : *list) largest = std::max(largest, std::abs(s.d));
  std::fill(moved_.begin(), moved_.end(), 0);
  index_samples();
  return largest;
}

Vec3 OffsetSamples::triangle_normal(int t) const {
  const Triangle& f = dual_.triangles[t];
  return lrvd::triangle_normal(dual_.positions[f[0]], dual_.positions[f[1]], dual_.positions[f[2]]);
}

void OffsetSamples::place_samples() {
  const std::vector<Vec3>& x = dual_.positions;
  double length_sum = 0;
  int edges = 0;
  for (int t = 0; t < static_cast<int>(dual_.triangles.size()); ++t)
    if (proper_[t])
      for (int e = 0; e < 3; ++e, ++edges) length_sum += distance(x[dual_.triangles[t][e]], x[dual_.triangles[t][(e + 1) % 3]]);
  if (edges == 0) return;
  const double mean_edge = length_sum / edges, spacing = mean_edge / options_.samples_per_edge;
  // Remesh samples: each used vertex once (from one of its triangles), then the lattices.
  std::vector<char> placed(x.size(), 0);
  std::vector<Vec3> bary;
  for (int t = 0; t < static_cast<int>(dual_.triangles.size()); ++t) {
    if (!proper_[t]) continue;
    const Triangle& f = dual_.triangles[t];
    for (int k = 0; k < 3; ++k)
      if (!placed[f[k]]) {
        placed[f[k]] = 1;
        remesh_.push_back({t, {k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0}, 0, {}});
      }
    bary.clear();
    lattice(f, lattice_level(x[f[0]], x[f[1]], x[f[2]], spacing, 2), bary);
    for (const Vec3& b : bary) remesh_.push_back({t, b, 0, {}});
  }
  // Input samples: the vertices, then the lattices.
  input_points_ = mesh_.positions();
  input_source_.assign(input_points_.size(), -1);
  for (int t = 0; t < mesh_.triangle_count(); ++t) {
    const Triangle& f = mesh_.triangle(t);
    const std::vector<Vec3>& p = mesh_.positions();
    bary.clear();
    lattice(f, lattice_level(p[f[0]], p[f[1]], p[f[2]], mean_edge / options_.input_samples_per_edge, 1), bary);
    for (const Vec3& b : bary) input_points_.push_back(at(p, f, b)), input_source_.push_back(t);
  }
  input_.resize(input_points_.size());
}

void OffsetSamples::hint_input_vertices(const std::vector<int>& cell_of) {
  if (static_cast<int>(cell_of.size()) != mesh_.vertex_count()) return;
  // A proper triangle at each remesh vertex, as its index in proper_triangles_.
  std::vector<int> proper_at(dual_.positions.size(), -1);
  for (int k = 0; k < static_cast<int>(proper_triangles_.size()); ++k)
    for (int v : proper_triangles_[k])
      if (proper_at[v] < 0) proper_at[v] = k;
  for (int u = 0; u < mesh_.vertex_count(); ++u)
    if (cell_of[u] >= 0 && cell_of[u] < static_cast<int>(proper_at.size())) input_[u].hint = proper_at[cell_of[u]];
}

void OffsetSamples::index_samples() {
  const int n = static_cast<int>(dual_.positions.size());
  first_.assign(n + 1, 0);
  auto each = [&](auto&& visit) {
    int i = 0;  // the sample's index: remesh_ then input_
    for (const std::vector<Sample>* list : {&remesh_, &input_})
      for (const Sample& s : *list) {
        if (s.triangle < 0) {  // an input sample not measured
          ++i;
          continue;
        }
        const Triangle& f = dual_.triangles[s.triangle];
        const double w[3] = {s.barycentric.x, s.barycentric.y, s.barycentric.z};
        for (int k = 0; k < 3; ++k)
          if (w[k] > 0) visit(f[k], i, w[k]);
        ++i;
      }
  };
  each([&](int v, int, double) { ++first_[v + 1]; });
  for (int v = 0; v < n; ++v) first_[v + 1] += first_[v];
  entries_.resize(first_[n]);
  std::vector<int> next(first_.begin(), first_.end() - 1);
  each([&](int v, int i, double w) { entries_[next[v]++] = {i, w}; });
}

int OffsetSamples::refine_input(double threshold, int level) {
  const int nv = static_cast<int>(mesh_.positions().size());
  input_refined_.resize(mesh_.triangle_count(), 0);
  std::vector<int> triangles;
  for (size_t i = 0; i < input_.size(); ++i) {
    if (!(std::abs(input_[i].d) >= threshold)) continue;
    if (static_cast<int>(i) < nv) {
      for (const int* t = mesh_.vertex_triangles_begin(static_cast<int>(i)); t != mesh_.vertex_triangles_end(static_cast<int>(i)); ++t)
        triangles.push_back(*t);
    } else {
      triangles.push_back(input_source_[i]);
    }
  }
  const size_t before = input_points_.size();
  const std::vector<Vec3>& p = mesh_.positions();
  for (int t : triangles) {
    if (input_refined_[t]) continue;
    input_refined_[t] = 1;
    const Triangle& f = mesh_.triangle(t);
    for (int i = 0; i <= level; ++i)
      for (int j = 0; i + j <= level; ++j) {
        const int l = level - i - j;
        if ((i == 0) + (j == 0) + (l == 0) >= 2) continue;
        input_points_.push_back(at(p, f, {i / double(level), j / double(level), l / double(level)}));
        input_source_.push_back(t);
      }
  }
  input_.resize(input_points_.size());
  return static_cast<int>(input_points_.size() - before);
}

int OffsetSamples::refine_remesh(double threshold, int level) {
  std::vector<char> refine(dual_.triangles.size(), 0);
  for (const Sample& s : remesh_)
    if (std::abs(s.d) >= threshold) refine[s.triangle] = 1;
  const size_t before = remesh_.size();
  for (int t = 0; t < static_cast<int>(refine.size()); ++t) {
    if (!refine[t]) continue;
    for (int i = 0; i <= level; ++i)
      for (int j = 0; i + j <= level; ++j) {
        const int l = level - i - j;
        if ((i == 0) + (j == 0) + (l == 0) >= 2) continue;
        remesh_.push_back({t, {i / double(level), j / double(level), l / double(level)}, 0, {}});
      }
    for (int v : dual_.triangles[t]) moved_[v] = 1;
  }
  return static_cast<int>(remesh_.size() - before);
}

void OffsetSamples::reset(const std::vector<Vec3>& positions) {
  for (size_t v = 0; v < positions.size(); ++v)
    if (positions[v] != dual_.positions[v]) moved_[v] = 1;
  dual_.positions = positions;
}

}  // namespace lrvd::fit_detail
