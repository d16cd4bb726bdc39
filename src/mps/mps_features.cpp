// Feature-first sampling (mps_features.h): the feature lines and their corners, then one sample at
// each corner, the sharpest first, and samples spread evenly along each line between corners.
#include "mps/mps_features.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace lrvd::mps_detail {

namespace {

// Along a line between corners the samples are spread evenly at kFeatureSpacing times the local
// radius: two neighbours on a line less than √2 r apart meet at their midpoint whatever sample
// lies off the line (one at least r from both is farther from it), so each feature sample's cell
// reaches its neighbours' along the line and the LRRT follows it. A cut the sampler refuses slides
// on by kFeatureSlideStep radii, up to kFeatureSlide.
constexpr double kFeatureSpacing = 1.2;
constexpr double kFeatureSlide = 0.5, kFeatureSlideStep = 0.05;  // in radii

}  // namespace

FeatureLines find_feature_lines(const SurfaceMesh& mesh, double angle_deg, const Vec3* normals) {
  const double cos_limit = std::cos(angle_deg * M_PI / 180.0);
  FeatureLines f;
  // As the sampler's DiskIndex computes them: a triangle without area has a NaN normal, and its
  // edges are features (no comparison with NaN holds).
  std::vector<Vec3> computed;
  if (!normals) {
    computed.resize(mesh.triangle_count());
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      const Triangle& tri = mesh.triangle(t);
      const Vec3 n = cross(mesh.position(tri[1]) - mesh.position(tri[0]), mesh.position(tri[2]) - mesh.position(tri[0]));
      computed[t] = n / norm(n);
    }
    normals = computed.data();
  }
  const Vec3* normal = normals;
  f.at_vertex.assign(mesh.vertex_count(), {});
  for (int t = 0; t < mesh.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int n = mesh.neighbor(t, e);
      if (n >= 0 && (n < t || dot(normal[t], normal[n]) >= cos_limit)) continue;
      const Triangle& tri = mesh.triangle(t);
      const int a = tri[e], b = tri[(e + 1) % 3];
      f.at_vertex[a].push_back(static_cast<int>(f.edges.size()));
      f.at_vertex[b].push_back(static_cast<int>(f.edges.size()));
      f.edges.push_back({t, e, a, b});
      f.boundary_edges += n < 0;
    }
  f.corner.assign(mesh.vertex_count(), 0);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (f.at_vertex[v].empty()) continue;
    double c = 1;
    if (f.at_vertex[v].size() == 2) {
      Vec3 dir[2];
      for (int k = 0; k < 2; ++k) {
        const FeatureLines::Edge& g = f.edges[f.at_vertex[v][k]];
        const Vec3 d = mesh.position(g.a == v ? g.b : g.a) - mesh.position(v);
        dir[k] = d / norm(d);
      }
      c = dot(dir[0], dir[1]);
      if (c <= -cos_limit) continue;  // nearly straight on
    }
    f.corner[v] = 1;
    f.corners.push_back({-c, v});
  }
  std::sort(f.corners.begin(), f.corners.end());
  return f;
}

namespace {

//! The sampler that places samples on the feature lines: one at each corner, the sharpest first,
//! then along each line from corner to corner.
class FeatureSampling {
 public:
  FeatureSampling(const SurfaceMesh& mesh, Sampler& sampler, double angle_deg,
                  const std::vector<std::pair<Vec3, double>>& exclusions)
      : m_(mesh),
        sampler_(sampler),
        f_(find_feature_lines(mesh, angle_deg, &sampler.disks().normal(0))),
        exclusions_(exclusions) {}

  int run() {
    if (f_.edges.empty()) return 0;
    const int before = sampler_.disks().size();
    for (const auto& [c, v] : f_.corners) {
      const int k = f_.at_vertex[v][0];
      insert_on(k, f_.edges[k].a == v ? 0.0 : 1.0);
    }
    // The lines: from each corner along each of its edges to the next corner, then the closed
    // loops without one.
    used_.assign(f_.edges.size(), 0);
    for (const auto& [c, v] : f_.corners)
      for (int k : f_.at_vertex[v])
        if (!used_[k]) walk(v, k);
    for (int k = 0; k < static_cast<int>(f_.edges.size()); ++k)
      if (!used_[k]) walk(f_.edges[k].a, k);
    return sampler_.disks().size() - before;
  }

 private:
  using Edge = FeatureLines::Edge;

  //! A sample at the point of edge k at `u` from its end a to its end b (exactly on the edge: its
  //! region grows on both sides, Sampler::region_of).
  bool insert_on(int k, double u) {
    const Edge& g = f_.edges[k];
    Vec3 bary;
    bary[g.e] = 1 - u;
    bary[(g.e + 1) % 3] = u;
    const Vec3 p = (1 - u) * m_.position(g.a) + u * m_.position(g.b);
    // The boundary's samples are never left out: an open mesh's LRRT needs its corners and lines.
    if (m_.neighbor(g.t, g.e) >= 0)
      for (const auto& [centre, radius] : exclusions_)
        if (squared_distance(p, centre) < radius * radius) return false;
    return sampler_.try_insert(p, g.t, bary);
  }

  //! Samples along the line that starts at vertex v with edge k and runs to the next corner (or
  //! back to v).
  void walk(int v, int k) {
    const int end = collect_line(v, k);
    measure_line();
    spread_along_line(!f_.corner[end]);  // closed: a loop back to its first vertex, which is no corner
  }

  //! line_ = the edges from vertex v on, starting with edge k, up to a corner or the end of the
  //! line; returns the vertex it stops at.
  int collect_line(int v, int k) {
    line_.clear();
    while (!used_[k]) {
      used_[k] = 1;
      const bool reverse = f_.edges[k].b == v;
      line_.push_back({k, reverse});
      v = reverse ? f_.edges[k].a : f_.edges[k].b;
      if (f_.corner[v] || f_.at_vertex[v].size() != 2) break;
      k = f_.at_vertex[v][0] == k ? f_.at_vertex[v][1] : f_.at_vertex[v][0];
    }
    return v;
  }

  //! Length in radii of each edge of the line (span_) and of the line (total_): the integral of
  //! 1/r, r linear along the edge.
  void measure_line() {
    span_.resize(line_.size());
    total_ = 0;
    for (size_t i = 0; i < line_.size(); ++i) {
      const Edge& g = f_.edges[line_[i].first];
      const double r0 = sampler_.radius_at(g.a), r1 = sampler_.radius_at(g.b);
      const double length = distance(m_.position(g.a), m_.position(g.b));
      span_[i] = std::abs(r1 - r0) > 1e-12 * r0 ? length * std::log(r1 / r0) / (r1 - r0) : length / r0;
      total_ += span_[i];
    }
  }

  //! A sample at the point `at` radii along the line, by the integral of measure_line() inverted
  //! in its edge.
  bool insert_at(double at) {
    size_t i = 0;
    double start = 0;  // radii walked before edge i
    while (i + 1 < line_.size() && start + span_[i] < at) start += span_[i++];
    const Edge& g = f_.edges[line_[i].first];
    const bool reverse = line_[i].second;
    const double x = std::clamp(at - start, 0.0, span_[i]);
    const double r0 = sampler_.radius_at(reverse ? g.b : g.a), r1 = sampler_.radius_at(reverse ? g.a : g.b);
    const double length = distance(m_.position(g.a), m_.position(g.b));
    if (!(span_[i] > 0)) return insert_on(line_[i].first, reverse ? 1.0 : 0.0);  // an edge of length 0
    double f = x / span_[i];  // fraction of the edge, from its walked start
    if (std::abs(r1 - r0) > 1e-12 * r0) f = r0 * std::expm1(x * (r1 - r0) / length) / (r1 - r0);
    f = std::clamp(f, 0.0, 1.0);
    return insert_on(line_[i].first, reverse ? 1 - f : f);
  }

  //! One sample after the other, each at an even share of what is left of the line; one refused
  //! (too close to a sample of another line at a sharp corner) slides on by small steps.
  void spread_along_line(bool closed) {
    double at = 0;
    if (closed) insert_at(0);
    for (;;) {
      const double left = total_ - at;
      const long pieces = std::lround(left / kFeatureSpacing);
      if (pieces <= 1) break;
      const double target = at + left / static_cast<double>(pieces);
      at = target;
      for (double slide = 0; slide <= kFeatureSlide; slide += kFeatureSlideStep)
        if (insert_at(target + slide)) {
          at = target + slide;
          break;
        }
    }
  }

  const SurfaceMesh& m_;
  Sampler& sampler_;
  const FeatureLines f_;
  const std::vector<std::pair<Vec3, double>>& exclusions_;  // no feature sample inside these balls
  std::vector<char> used_;                       // per edge: on a line already walked
  std::vector<std::pair<int, bool>> line_;       // edges, and whether each is walked from b to a
  std::vector<double> span_;                     // per edge of line_: its length in radii
  double total_ = 0;                             // of line_, in radii
};

}  // namespace

int sample_features(const SurfaceMesh& mesh, Sampler& sampler, double angle_deg,
                    const std::vector<std::pair<Vec3, double>>& exclusions) {
  return FeatureSampling(mesh, sampler, angle_deg, exclusions).run();
}

}  // namespace lrvd::mps_detail
