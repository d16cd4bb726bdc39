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

//! The feature lines of a mesh, as edges and the corners where lines meet or turn, and the
//! sampler that places samples on them.
class FeatureSampling {
 public:
  FeatureSampling(const SurfaceMesh& mesh, Sampler& sampler, double angle_deg)
      : m_(mesh), sampler_(sampler), cos_limit_(std::cos(angle_deg * M_PI / 180.0)) {}

  int run() {
    find_edges();
    if (edges_.empty()) return 0;
    const int before = sampler_.disks().size();
    find_corners();
    for (const auto& [c, v] : corners_) insert_on(at_vertex_[v][0], edges_[at_vertex_[v][0]].a == v ? 0.0 : 1.0);
    // The lines: from each corner along each of its edges to the next corner, then the closed
    // loops without one.
    used_.assign(edges_.size(), 0);
    for (const auto& [c, v] : corners_)
      for (int k : at_vertex_[v])
        if (!used_[k]) walk(v, k);
    for (int k = 0; k < static_cast<int>(edges_.size()); ++k)
      if (!used_[k]) walk(edges_[k].a, k);
    return sampler_.disks().size() - before;
  }

 private:
  struct Edge {
    int t, e, a, b;  // triangle, its edge e from corner a to corner b
  };

  //! Boundary edges and edges whose triangles' normals are more than the feature angle apart.
  void find_edges() {
    const DiskIndex& disks = sampler_.disks();
    at_vertex_.assign(m_.vertex_count(), {});
    for (int t = 0; t < m_.triangle_count(); ++t)
      for (int e = 0; e < 3; ++e) {
        const int n = m_.neighbor(t, e);
        if (n >= 0 && (n < t || dot(disks.normal(t), disks.normal(n)) >= cos_limit_)) continue;
        const Triangle& tri = m_.triangle(t);
        const int a = tri[e], b = tri[(e + 1) % 3];
        at_vertex_[a].push_back(static_cast<int>(edges_.size()));
        at_vertex_[b].push_back(static_cast<int>(edges_.size()));
        edges_.push_back({t, e, a, b});
      }
  }

  //! Corners, the sharpest first: a vertex with other than two feature edges, or with two that
  //! turn by more than the feature angle.
  void find_corners() {
    corner_.assign(m_.vertex_count(), 0);
    for (int v = 0; v < m_.vertex_count(); ++v) {
      if (at_vertex_[v].empty()) continue;
      double c = 1;
      if (at_vertex_[v].size() == 2) {
        Vec3 dir[2];
        for (int k = 0; k < 2; ++k) {
          const Edge& g = edges_[at_vertex_[v][k]];
          const Vec3 d = m_.position(g.a == v ? g.b : g.a) - m_.position(v);
          dir[k] = d / norm(d);
        }
        c = dot(dir[0], dir[1]);
        if (c <= -cos_limit_) continue;  // nearly straight on
      }
      corner_[v] = 1;
      corners_.push_back({-c, v});
    }
    std::sort(corners_.begin(), corners_.end());
  }

  //! A sample at the point of edge k at `u` from its end a to its end b (exactly on the edge: its
  //! region grows on both sides, Sampler::region_of).
  bool insert_on(int k, double u) {
    const Edge& g = edges_[k];
    Vec3 bary;
    bary[g.e] = 1 - u;
    bary[(g.e + 1) % 3] = u;
    return sampler_.try_insert((1 - u) * m_.position(g.a) + u * m_.position(g.b), g.t, bary);
  }

  //! Samples along the line that starts at vertex v with edge k and runs to the next corner (or
  //! back to v).
  void walk(int v, int k) {
    const int end = collect_line(v, k);
    measure_line();
    spread_along_line(!corner_[end]);  // closed: a loop back to its first vertex, which is no corner
  }

  //! line_ = the edges from vertex v on, starting with edge k, up to a corner or the end of the
  //! line; returns the vertex it stops at.
  int collect_line(int v, int k) {
    line_.clear();
    while (!used_[k]) {
      used_[k] = 1;
      const bool reverse = edges_[k].b == v;
      line_.push_back({k, reverse});
      v = reverse ? edges_[k].a : edges_[k].b;
      if (corner_[v] || at_vertex_[v].size() != 2) break;
      k = at_vertex_[v][0] == k ? at_vertex_[v][1] : at_vertex_[v][0];
    }
    return v;
  }

  //! Length in radii of each edge of the line (span_) and of the line (total_): the integral of
  //! 1/r, r linear along the edge.
  void measure_line() {
    span_.resize(line_.size());
    total_ = 0;
    for (size_t i = 0; i < line_.size(); ++i) {
      const Edge& g = edges_[line_[i].first];
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
    const Edge& g = edges_[line_[i].first];
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
  double cos_limit_;
  std::vector<Edge> edges_;
  std::vector<std::vector<int>> at_vertex_;  // the feature edges at each vertex
  std::vector<char> corner_;
  std::vector<std::pair<double, int>> corners_;  // (minus the cosine of the angle between the two edges, vertex)
  std::vector<char> used_;                       // per edge: on a line already walked
  std::vector<std::pair<int, bool>> line_;       // edges, and whether each is walked from b to a
  std::vector<double> span_;                     // per edge of line_: its length in radii
  double total_ = 0;                             // of line_, in radii
};

}  // namespace

int sample_features(const SurfaceMesh& mesh, Sampler& sampler, double angle_deg) {
  return FeatureSampling(mesh, sampler, angle_deg).run();
}

}  // namespace lrvd::mps_detail
