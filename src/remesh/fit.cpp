// Quadric fitting of the remesh vertices under a quality floor (see fit.h).
#include "remesh/fit.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <set>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "common/error.h"
#include "diagram/clip.h"
#include "mesh/self_intersections.h"
#include "metrics/quality.h"

namespace lrvd {

namespace {

// Area-weighted squared distance to the planes of the triangles under each cell, as A x = b.
struct CellQuadric {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
};

std::vector<CellQuadric> cell_quadrics(const Diagram& diagram, const SurfaceMesh& mesh) {
  std::vector<CellQuadric> quadric(diagram.sample_count);
  std::vector<double> cell_area(diagram.sample_count, 0.0);
  // Boundary segments inside each cell: a polygon's side along a mesh edge with no neighbour.
  struct Segment {
    int cell, triangle;
    Vec3 a, b;
  };
  std::vector<Segment> segments;
  const bool open = !mesh.is_closed();
  const SymbolicContext ctx = diagram.context(mesh);
  for (const CellPolygon& poly : diagram.polygons) {
    const SymbolicVertex* v = diagram.polygon_vertices(poly);
    const Vec3 origin = position(v[0], ctx);
    double area = 0;
    Vec3 previous = position(v[1], ctx) - origin;
    for (int k = 2; k < poly.vertex_count; ++k) {
      const Vec3 current = position(v[k], ctx) - origin;
      area += 0.5 * norm(cross(previous, current));
      previous = current;
    }
    if (!(area > 0)) continue;
    const Vec3 normal = mesh.triangle_normal(poly.triangle);
    const Eigen::Vector3d n(normal.x, normal.y, normal.z);
    const double offset = dot(normal, mesh.position(mesh.triangle(poly.triangle)[0]));
    quadric[poly.cell].a += area * n * n.transpose();
    quadric[poly.cell].b += area * offset * n;
    cell_area[poly.cell] += area;
    if (!open) continue;
    const Triangle& tri = mesh.triangle(poly.triangle);
    for (int k = 0; k < poly.vertex_count; ++k) {
      const int l = (k + 1) % poly.vertex_count;
      const unsigned shared = edge_mask(v[k], tri) & edge_mask(v[l], tri);
      for (int e = 0; e < 3; ++e)
        if ((shared >> e & 1u) && mesh.neighbor(poly.triangle, e) < 0)
          segments.push_back({poly.cell, poly.triangle, position(v[k], ctx), position(v[l], ctx)});
    }
  }
  // Each boundary segment adds the plane through it at right angles to its triangle, weighted by
  // its length times the cell's size (an area, as the surface planes' weights are): a cell on the
  // boundary pulls its vertex onto the boundary as well as onto the surface.
  for (const Segment& s : segments) {
    const Vec3 along = s.b - s.a;
    const double length = norm(along);
    if (!(length > 0)) continue;
    Vec3 side = cross(mesh.triangle_normal(s.triangle), along);
    const double side_length = norm(side);
    if (!(side_length > 0)) continue;
    side = side / side_length;
    const Eigen::Vector3d n(side.x, side.y, side.z);
    const double weight = length * std::sqrt(cell_area[s.cell]);
    quadric[s.cell].a += weight * n * n.transpose();
    quadric[s.cell].b += weight * dot(side, s.a) * n;
  }
  return quadric;
}

// The minimiser of the quadric nearest to x0 within the directions the planes constrain.
Vec3 quadric_target(const CellQuadric& q, const Vec3& x0, double rank_threshold) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(q.a);
  const Eigen::Vector3d& lambda = eigen.eigenvalues();  // increasing
  if (!(lambda[2] > 0)) return x0;
  const Eigen::Vector3d start(x0.x, x0.y, x0.z);
  const Eigen::Vector3d residual = q.b - q.a * start;
  Eigen::Vector3d step = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k)
    if (lambda[k] > rank_threshold * lambda[2])
      step += eigen.eigenvectors().col(k).dot(residual) / lambda[k] * eigen.eigenvectors().col(k);
  return {x0.x + step[0], x0.y + step[1], x0.z + step[2]};
}

// Per input vertex, the cell that holds it (-1 if none): where the balancing's first search for the
// vertex's closest point on the remesh starts.
std::vector<int> input_vertex_cells(const Diagram& diagram, const SurfaceMesh& mesh) {
  std::vector<int> cell(mesh.vertex_count(), -1);
  for (const CellPolygon& poly : diagram.polygons) {
    const SymbolicVertex* v = diagram.polygon_vertices(poly);
    for (int k = 0; k < poly.vertex_count; ++k)
      if (v[k].type == SymbolicVertex::Type::A) cell[v[k].v[0]] = poly.cell;
  }
  return cell;
}

std::set<std::pair<int, int>> crossing_pairs(const DualMesh& dual) {
  const auto pairs = find_self_intersections(dual.positions, dual.triangles, proper_triangles(dual.positions, dual.triangles));
  return {pairs.begin(), pairs.end()};
}

// The quality floor of a state: no triangle below the state's worst Q, or below its own Q where it
// was worse than that already; none below the state's smallest angle (at most `max_angle`), or —
// `per_triangle_angle` — none below `max_angle` that was above it and none below its own smallest
// angle otherwise; and none turned over.
class QualityFloor {
 public:
  QualityFloor(const DualMesh& state, double max_angle, bool per_triangle_angle, double keep_quality = 0)
      : triangles_(state.triangles) {
    const int nt = static_cast<int>(triangles_.size());
    q_.resize(nt), angle_.resize(nt), normal_.resize(nt);
    double q_floor = 1, angle_floor = max_angle;
    for (int t = 0; t < nt; ++t) {
      const Triangle& f = triangles_[t];
      const Vec3 &a = state.positions[f[0]], &b = state.positions[f[1]], &c = state.positions[f[2]];
      q_[t] = triangle_quality(a, b, c);
      angle_[t] = triangle_min_angle(a, b, c);
      normal_[t] = cross(b - a, c - a);
      q_floor = std::min(q_floor, q_[t]);
      angle_floor = std::min(angle_floor, angle_[t]);
    }
    if (per_triangle_angle) angle_floor = max_angle;
    cos_.resize(nt), sin_.resize(nt);
    for (int t = 0; t < nt; ++t) {
      q_[t] = std::max(std::min(q_[t], q_floor), keep_quality * q_[t]), angle_[t] = std::min(angle_[t], angle_floor);
      cos_[t] = std::cos(angle_[t] * kRadiansPerDegree), sin_[t] = std::sin(angle_[t] * kRadiansPerDegree);
    }
  }

  bool holds(int t, const std::vector<Vec3>& positions) const {
    const Triangle& f = triangles_[t];
    const Vec3 &a = positions[f[0]], &b = positions[f[1]], &c = positions[f[2]];
    return !(triangle_quality(a, b, c) < q_[t]) && !angle_below(t, a, b, c) && dot(cross(b - a, c - a), normal_[t]) > 0;
  }

 private:
  static constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180;

  // triangle_min_angle(a, b, c) < angle_[t], decided without the arc tangents where the answer is
  // clear: a corner angle atan2(y, x), y = |u × v|, x = u · v (as corner_angle computes them) is
  // below φ exactly when y cos φ - x sin φ < 0. Only where that is within 1e-9 (|x| + y) of 0 (an
  // angle within about 1e-9 radians of φ: far more than the rounding of either way) do the degree
  // values decide, so the answer is always that of comparing them.
  bool angle_below(int t, const Vec3& a, const Vec3& b, const Vec3& c) const {
    bool clear = true;
    auto corner = [&](const Vec3& u, const Vec3& v) {
      const double x = dot(u, v), y = norm(cross(u, v));
      const double side = y * cos_[t] - x * sin_[t], margin = 1e-9 * (std::abs(x) + y);
      if (!(side > margin)) clear = false;  // below, too close to tell, or not finite
      return side < -margin;                // clearly below
    };
    if (corner(b - a, c - a) || corner(c - b, a - b) || corner(a - c, b - c)) return true;
    return clear ? false : triangle_min_angle(a, b, c) < angle_[t];
  }

  const std::vector<Triangle>& triangles_;
  std::vector<double> q_, angle_;
  std::vector<double> cos_, sin_;  // of angle_
  std::vector<Vec3> normal_;
};

// Puts vertices back to `fallback` (a state that meets `floor` and has no crossing outside
// `allowed`) until the same holds for `dual`: the corners of every new crossing, then the moved
// corners of every triangle below the floor next to a vertex put back. Returns the vertices put back;
// `crossings` are then the crossing pairs of `dual`.
int settle(DualMesh& dual, const std::vector<Vec3>& fallback, const QualityFloor& floor,
           const std::set<std::pair<int, int>>& allowed, const std::vector<std::vector<int>>& incident,
           std::set<std::pair<int, int>>& crossings) {
  int reverted = 0;
  for (int round = 0; round < 32; ++round) {
    std::vector<int> back;
    crossings = crossing_pairs(dual);
    for (const auto& pair : crossings)
      if (!allowed.count(pair))
        for (int t : {pair.first, pair.second})
          for (int v : dual.triangles[t])
            if (dual.positions[v] != fallback[v]) dual.positions[v] = fallback[v], back.push_back(v);
    if (back.empty()) return reverted;
    for (size_t i = 0; i < back.size(); ++i)
      for (int t : incident[back[i]])
        if (!floor.holds(t, dual.positions))
          for (int v : dual.triangles[t])
            if (dual.positions[v] != fallback[v]) dual.positions[v] = fallback[v], back.push_back(v);
    reverted += static_cast<int>(back.size());
  }
  // Not settled after eight rounds: the fallback state, unless the last round settled it.
  crossings = crossing_pairs(dual);
  if (std::any_of(crossings.begin(), crossings.end(), [&](const auto& pair) { return !allowed.count(pair); })) {
    for (size_t v = 0; v < fallback.size(); ++v) reverted += dual.positions[v] != fallback[v];
    dual.positions = fallback;
    crossings = crossing_pairs(dual);
  }
  return reverted;
}

// The state relax_worst_triangles' rounds share: the dual, its adjacency, the vertices that stay
// (on its boundary) and the triangle of `mesh` under each vertex.
class WorstTriangleRelaxation {
 public:
  WorstTriangleRelaxation(const SurfaceMesh& mesh, const ClosestPointIndex& index, const Samples& samples,
                          DualMesh& dual)
      : mesh_(mesh), index_(index), dual_(dual), n_(static_cast<int>(dual.positions.size())),
        nt_(static_cast<int>(dual.triangles.size())), component_(mesh.triangle_components()),
        on_triangle_(samples.triangles), incident_(n_), ring_(n_), fixed_(n_, 0), by_quality_(nt_) {
    index_dual();
  }

  // Each vertex of the `worst` triangles of lowest Q, the worst first, moved towards its ring.
  void round(int worst_triangles) {
    for (int t = 0; t < nt_; ++t) by_quality_[t] = {quality(t), t};
    const size_t worst = std::min<size_t>(worst_triangles, by_quality_.size());
    std::partial_sort(by_quality_.begin(), by_quality_.begin() + worst, by_quality_.end());
    vertices_.clear();
    for (size_t k = 0; k < worst; ++k)
      for (int v : dual_.triangles[by_quality_[k].second])
        if (std::find(vertices_.begin(), vertices_.end(), v) == vertices_.end()) vertices_.push_back(v);
    for (int v : vertices_)
      if (!fixed_[v] && !ring_[v].empty() && on_triangle_[v] >= 0) move_towards_ring(v);
  }

 private:
  void index_dual();
  void move_towards_ring(int v);
  double quality(int t) const {
    const Triangle& f = dual_.triangles[t];
    return triangle_quality(dual_.positions[f[0]], dual_.positions[f[1]], dual_.positions[f[2]]);
  }
  Vec3 normal(int t) const {
    const Triangle& f = dual_.triangles[t];
    return cross(dual_.positions[f[1]] - dual_.positions[f[0]], dual_.positions[f[2]] - dual_.positions[f[0]]);
  }

  const SurfaceMesh& mesh_;
  const ClosestPointIndex& index_;
  DualMesh& dual_;
  const int n_, nt_;
  const std::vector<int>& component_;
  std::vector<int> on_triangle_;  // the triangle of `mesh` under each vertex
  std::vector<std::vector<int>> incident_, ring_;
  std::vector<char> fixed_;
  std::vector<std::pair<double, int>> by_quality_;
  std::vector<int> vertices_;
  std::vector<Vec3> normals_;
};

// Each vertex's triangles and ring; vertices on an edge of one triangle (the dual's boundary) stay
// where they are.
void WorstTriangleRelaxation::index_dual() {
  std::vector<std::pair<int, int>> edges;
  for (int t = 0; t < nt_; ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = dual_.triangles[t][e], b = dual_.triangles[t][(e + 1) % 3];
      incident_[a].push_back(t);
      ring_[a].push_back(b);
      ring_[b].push_back(a);
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  for (size_t i = 0, j; i < edges.size(); i = j) {
    for (j = i + 1; j < edges.size() && edges[j] == edges[i];) ++j;
    if (j - i == 1) fixed_[edges[i].first] = fixed_[edges[i].second] = 1;
  }
  for (std::vector<int>& r : ring_) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
}

// The vertex towards the mean of its ring, then onto its own component of the surface, by the
// first of the whole step, a half, a quarter or an eighth that raises the lowest Q of its
// triangles, turns none over and lands on a triangle facing the way its previous one did.
void WorstTriangleRelaxation::move_towards_ring(int v) {
  double lowest = 1;
  normals_.clear();
  for (int t : incident_[v]) lowest = std::min(lowest, quality(t)), normals_.push_back(normal(t));
  Vec3 mean{0, 0, 0};
  for (int u : ring_[v]) mean = mean + dual_.positions[u];
  mean = mean / static_cast<double>(ring_[v].size());
  const Vec3 from = dual_.positions[v];
  const int own = component_[on_triangle_[v]];
  for (double step : {1.0, 0.5, 0.25, 0.125}) {
    const Vec3 p = from + step * (mean - from);
    ClosestPoint c = index_.query(p, on_triangle_[v]);
    if (c.triangle >= 0 && component_[c.triangle] != own) c = index_.query_within(p, component_.data(), own, on_triangle_[v]);
    if (c.triangle < 0 || dot(mesh_.triangle_normal(c.triangle), mesh_.triangle_normal(on_triangle_[v])) <= 0) continue;
    dual_.positions[v] = c.point;
    double now = 1;
    bool turned = false;
    for (size_t k = 0; k < incident_[v].size(); ++k) {
      now = std::min(now, quality(incident_[v][k]));
      turned = turned || !(dot(normal(incident_[v][k]), normals_[k]) > 0);
    }
    if (!turned && now > lowest) {
      on_triangle_[v] = c.triangle;
      break;
    }
    dual_.positions[v] = from;
  }
}

// Triangles that cross and did not in `original` (whose crossings are `known`, if given): their
// corners go back until none is left. Returns the vertices put back; `crossings` receives the
// crossing pairs left.
int revert_new_crossings(DualMesh& dual, const std::vector<Vec3>& original,
                         const std::vector<std::pair<int, int>>* known, std::vector<std::pair<int, int>>& crossings) {
  std::vector<std::pair<int, int>> found;
  if (!known) found = find_self_intersections(original, dual.triangles, proper_triangles(original, dual.triangles));
  const std::vector<std::pair<int, int>>& listed = known ? *known : found;
  const std::set<std::pair<int, int>> before(listed.begin(), listed.end());
  int reverted = 0;
  for (;;) {
    const auto now = find_self_intersections(dual.positions, dual.triangles, proper_triangles(dual.positions, dual.triangles));
    std::vector<int> back;
    for (const auto& pair : now)
      if (!before.count(pair))
        for (int t : {pair.first, pair.second})
          for (int v : dual.triangles[t])
            if (dual.positions[v] != original[v]) back.push_back(v);
    if (back.empty()) {
      crossings = now;
      return reverted;
    }
    std::sort(back.begin(), back.end());
    back.erase(std::unique(back.begin(), back.end()), back.end());
    for (int v : back) dual.positions[v] = original[v];
    reverted += static_cast<int>(back.size());
  }
}

}  // namespace

RelaxResult relax_worst_triangles(const SurfaceMesh& mesh, const ClosestPointIndex& index, const Samples& samples,
                                  DualMesh& dual, const RelaxOptions& options,
                                  const std::vector<std::pair<int, int>>* crossings) {
  if (options.rounds < 0 || options.worst_triangles < 0)
    throw InputError(fmt::format("relaxing the worst triangles: rounds ({}) and worst_triangles ({}) may not be negative",
                                 options.rounds, options.worst_triangles));
  if (samples.size() != static_cast<int>(dual.positions.size()))
    throw std::logic_error("relax_worst_triangles: one sample per dual vertex is needed");
  RelaxResult result;
  const std::vector<Vec3> original = dual.positions;
  WorstTriangleRelaxation relaxation(mesh, index, samples, dual);
  for (int round = 0; round < options.rounds; ++round) relaxation.round(options.worst_triangles);
  result.reverted = revert_new_crossings(dual, original, crossings, result.crossings);
  for (size_t v = 0; v < original.size(); ++v) result.moved += dual.positions[v] != original[v];
  return result;
}

FitResult fit_to_surface(const Diagram& diagram, const SurfaceMesh& mesh, DualMesh& dual, const FitOptions& options,
                         const ClosestPointIndex* mesh_index, const std::vector<std::pair<int, int>>* crossings) {
  FitResult result;
  const int n = static_cast<int>(dual.positions.size());
  const int nt = static_cast<int>(dual.triangles.size());
  if (n == 0 || nt == 0) return result;
  const std::vector<Vec3> original = dual.positions;
  std::vector<std::vector<int>> incident(n);
  for (int t = 0; t < nt; ++t)
    for (int v : dual.triangles[t]) incident[v].push_back(t);
  const std::set<std::pair<int, int>> allowed =
      crossings ? std::set<std::pair<int, int>>(crossings->begin(), crossings->end()) : crossing_pairs(dual);
  std::set<std::pair<int, int>> crossings_now;

  // Step 1, the quadric fit under the CVT's floor.
  const QualityFloor cvt_floor(dual, options.max_angle_floor, false);
  std::function<bool(int)> acceptable = [&](int v) {
    for (int t : incident[v])
      if (!cvt_floor.holds(t, dual.positions)) return false;
    return true;
  };
  const std::vector<CellQuadric> quadric = cell_quadrics(diagram, mesh);
  std::vector<Vec3> target(n);
  for (int v = 0; v < n; ++v) target[v] = quadric_target(quadric[v], original[v], options.rank_threshold);
  // The longest moves first (tips of the surface), each taken whole or in eighths.
  std::vector<int> order(n);
  for (int v = 0; v < n; ++v) order[v] = v;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return distance(target[a], original[a]) > distance(target[b], original[b]);
  });
  for (int pass = 0; pass < options.passes; ++pass)
    for (int v : order) {
      if (incident[v].empty()) continue;
      const Vec3 from = dual.positions[v];
      for (double step : {1.0, 0.875, 0.75, 0.625, 0.5, 0.375, 0.25, 0.125}) {
        dual.positions[v] = from + step * (target[v] - from);
        if (acceptable(v)) break;
        dual.positions[v] = from;
      }
    }
  // Moving vertices must not make triangles cross.
  result.reverted = settle(dual, original, cvt_floor, allowed, incident, crossings_now);

  // Step 2, balancing the two-sided distance under the floor of step 1's result (so the worst
  // triangle stays what step 1 made it), with the angle floor per triangle: its sideways steps
  // would otherwise take many triangles down to the smallest angle where that is below 30°.
  if (options.balance) {
    const std::vector<Vec3> quadric_fitted = dual.positions;
    const QualityFloor fitted_floor(dual, options.max_angle_floor, true, options.keep_quality);
    acceptable = [&](int v) {
      for (int t : incident[v])
        if (!fitted_floor.holds(t, dual.positions)) return false;
      return true;
    };
    // The focus rounds' floor: the worst Q of the state they start from (or a triangle's own Q, if
    // lower), so they never lower the worst triangle of the rounds before them either.
    std::unique_ptr<QualityFloor> focus_floor;
    auto make_focus_floor = [&]() -> std::function<bool(int)> {
      focus_floor = std::make_unique<QualityFloor>(dual, options.max_angle_floor, true);
      return [&](int v) {
        for (int t : incident[v])
          if (!focus_floor->holds(t, dual.positions)) return false;
        return true;
      };
    };
    const std::vector<int> input_cells = input_vertex_cells(diagram, mesh);
    result.offsets =
        balance_offsets(mesh, dual, incident, acceptable, options.offsets, make_focus_floor, mesh_index, &input_cells);
    // The floor that settling keeps: the focus rounds' where they ran (step 1's result meets it).
    result.reverted += settle(dual, quadric_fitted, focus_floor ? *focus_floor : fitted_floor, allowed, incident, crossings_now);
  }
  result.crossings.assign(crossings_now.begin(), crossings_now.end());
  for (int v = 0; v < n; ++v)
    if (dual.positions[v] != original[v]) {
      ++result.moved;
      result.max_displacement = std::max(result.max_displacement, distance(dual.positions[v], original[v]));
    }
  return result;
}

}  // namespace lrvd
