// Exact geometry for the diagram verification: cached rational vertex positions, the triangle's 2D
// frame, filtered exact orientation, areas and power-distance comparisons.
#include "verification/diagram_geometry.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace lrvd::verify_detail {

namespace {

Interval enclose(const Q& x) { return Interval(CGAL::to_interval(x)); }

Sign sign_of(const Q& x) { return static_cast<Sign>(static_cast<int>(CGAL::sign(x))); }

// Interval filter: the sign when the interval excludes zero, Zero meaning "undecided".
Sign filtered_sign(const Interval& x) {
  if (x.inf() > 0) return Sign::Positive;
  if (x.sup() < 0) return Sign::Negative;
  return Sign::Zero;
}

}  // namespace

const Q& coordinate(const ExactPoint& p, int axis) { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); }

ExactVertex make_exact_vertex(const ExactPoint& p) {
  ExactVertex e;
  e.valid = true;
  e.p = p;
  for (int c = 0; c < 3; ++c) e.box[c] = enclose(coordinate(p, c));
  return e;
}

int ExactVertices::index(const SymbolicVertex& q) {
  auto [it, inserted] = index_.emplace(q, static_cast<int>(points_.size()));
  if (!inserted) return it->second;
  ExactVertex e;
  try {
    e = make_exact_vertex(exact_position(q, ctx_));
    if (q.type == SymbolicVertex::Type::B) {
      // The point lies exactly on the line of its edge: one coordinate gives the parameter.
      const Vec3& a = ctx_.vertices[q.v[0]];
      const Vec3& b = ctx_.vertices[q.v[1]];
      int axis = 0;
      for (int c = 1; c < 3; ++c)
        if (std::fabs(b[c] - a[c]) > std::fabs(b[axis] - a[axis])) axis = c;
      e.edge_parameter = (coordinate(e.p, axis) - Q(a[axis])) / (Q(b[axis]) - Q(a[axis]));
    }
  } catch (const std::domain_error&) {
    e = ExactVertex{};  // invalid: reported by the checks that meet it
  }
  points_.push_back(std::move(e));
  symbolic_.push_back(q);
  return it->second;
}

Frame triangle_frame(const SurfaceMesh& mesh, int t, const std::array<const ExactVertex*, 3>& corners) {
  const Triangle& tri = mesh.triangle(t);
  Frame f;
  const int drop = predicates::projection_axis(mesh.position(tri[0]), mesh.position(tri[1]), mesh.position(tri[2]));
  if (drop < 0) return f;
  f.u = (drop + 1) % 3;
  f.v = (drop + 2) % 3;
  const Sign s = orient(*corners[0], *corners[1], *corners[2], f);  // with sign = +1: the plain projected orientation
  if (s == Sign::Zero) return f;
  f.sign = s == Sign::Positive ? 1 : -1;
  f.valid = true;
  return f;
}

Sign orient(const ExactVertex& a, const ExactVertex& b, const ExactVertex& c, const Frame& f) {
  const int u = f.u, v = f.v;
  Sign s;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    s = filtered_sign((b.box[u] - a.box[u]) * (c.box[v] - a.box[v]) - (b.box[v] - a.box[v]) * (c.box[u] - a.box[u]));
  }
  if (s == Sign::Zero) {
    const Q& ax = coordinate(a.p, u);
    const Q& ay = coordinate(a.p, v);
    const Q det = (coordinate(b.p, u) - ax) * (coordinate(c.p, v) - ay) -
                  (coordinate(b.p, v) - ay) * (coordinate(c.p, u) - ax);
    s = sign_of(det);
  }
  return f.sign > 0 ? s : -s;
}

Q twice_area(const std::vector<const ExactVertex*>& polygon, const Frame& f) {
  Q sum(0);
  const size_t n = polygon.size();
  if (n < 3) return sum;
  // Relative to the first vertex: same value, smaller products.
  const Q& ox = coordinate(polygon[0]->p, f.u);
  const Q& oy = coordinate(polygon[0]->p, f.v);
  for (size_t k = 1; k + 1 < n; ++k) {
    const ExactPoint& p = polygon[k]->p;
    const ExactPoint& q = polygon[k + 1]->p;
    sum += (coordinate(p, f.u) - ox) * (coordinate(q, f.v) - oy) - (coordinate(q, f.u) - ox) * (coordinate(p, f.v) - oy);
  }
  return f.sign > 0 ? sum : -sum;
}

Sign compare_power_distance(const ExactVertex& q, const Site& a, const Site& b) {
  // d_a(q) - d_b(q) = 2 q.(p_b - p_a) + (|p_a|^2 - w_a) - (|p_b|^2 - w_b): affine in q.
  {
    CGAL::Protect_FPU_rounding<true> upward;
    Interval value(0);
    for (int c = 0; c < 3; ++c) value += 2 * q.box[c] * (Interval(b.p[c]) - Interval(a.p[c]));
    for (int c = 0; c < 3; ++c) value += Interval(a.p[c]) * Interval(a.p[c]) - Interval(b.p[c]) * Interval(b.p[c]);
    value += Interval(b.w) - Interval(a.w);
    const Sign s = filtered_sign(value);
    if (s != Sign::Zero) return s;
  }
  Q exact(0);
  for (int c = 0; c < 3; ++c) {
    const Q pa(a.p[c]), pb(b.p[c]);
    exact += Q(2) * coordinate(q.p, c) * (pb - pa) + pa * pa - pb * pb;
  }
  exact += Q(b.w) - Q(a.w);
  return sign_of(exact);
}

std::string describe(const SymbolicVertex& q) {
  switch (q.type) {
    case SymbolicVertex::Type::A: return fmt::format("A({})", q.v[0]);
    case SymbolicVertex::Type::B: return fmt::format("B(edge {}-{}, cells {}|{})", q.v[0], q.v[1], q.label[0], q.label[1]);
    case SymbolicVertex::Type::C:
      return fmt::format("C(triangle {}-{}-{}, cells {}|{}|{})", q.v[0], q.v[1], q.v[2], q.label[0], q.label[1],
                         q.label[2]);
  }
  return "?";
}

}  // namespace lrvd::verify_detail
