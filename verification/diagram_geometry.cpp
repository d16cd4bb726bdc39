// Exact geometry for the diagram verification: the points' interval enclosures and their rational
// positions made on first use, the triangle's 2D frame, filtered exact orientation, areas,
// power-distance and edge-parameter comparisons.
#include "verification/diagram_geometry.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace lrvd::verify_detail {

namespace {

Interval enclose(const Q& x) { return Interval(CGAL::to_interval(x)); }

Sign sign_of(const Q& x) { return static_cast<Sign>(static_cast<int>(CGAL::sign(x))); }

}  // namespace

const Q& coordinate(const ExactPoint& p, int axis) { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); }

RationalPoint& RationalStore::entry(const SymbolicVertex& q) const {
  if (auto it = map_.find(q); it != map_.end()) return it->second;
  return map_.emplace(std::piecewise_construct, std::forward_as_tuple(q), std::forward_as_tuple()).first->second;
}

const RationalPoint* RationalStore::find(const SymbolicVertex& q) const {
  const auto it = map_.find(q);
  return it == map_.end() ? nullptr : &it->second;
}

ExactVertex ExactVertex::of(const SymbolicVertex& q, const SymbolicContext& ctx, const RationalStore* store) {
  ExactVertex e;
  e.reset(q, ctx, store);
  if (const std::optional<PositionEnclosure> enclosure = enclose_position(q, ctx)) {
    e.box = enclosure->box;
    e.parameter_box = enclosure->parameter;
    e.valid = true;
  } else {
    e.enclose_from_rationals();
  }
  return e;
}

void ExactVertex::reset(const SymbolicVertex& q, const SymbolicContext& ctx, const RationalStore* store) {
  valid = false;
  box = {Interval(0), Interval(0), Interval(0)};
  parameter_box = Interval(0);
  source_ = Source::Symbolic;
  q_ = q;
  barycentric_ = nullptr;
  ctx_ = &ctx;
  store_ = store;
  shared_ = nullptr;
  if (own_) own_ = Lazy<RationalPoint>();
}

void ExactVertex::enclose_from_rationals() {
  try {
    p();
  } catch (const std::domain_error&) {
    valid = false;  // reported by the checks that meet it
    return;
  }
  for (int c = 0; c < 3; ++c) box[c] = enclose(coordinate(p(), c));
  if (q_.type == SymbolicVertex::Type::B) parameter_box = enclose(edge_parameter());
  valid = true;
}

ExactVertex ExactVertex::at_barycentric(const std::array<int, 3>& corners, const Vec3& b, const SymbolicContext& ctx) {
  ExactVertex e;
  e.source_ = Source::Barycentric;
  e.q_.v = corners;
  e.barycentric_ = &b;
  e.ctx_ = &ctx;
  CGAL::Protect_FPU_rounding<true> upward;
  const Interval sum = Interval(b.x) + Interval(b.y) + Interval(b.z);
  e.box = {Interval(0), Interval(0), Interval(0)};
  for (int c = 0; c < 3; ++c) {
    const Interval w = Interval(b[c]) / sum;
    const Vec3& x = ctx.vertices[corners[c]];
    for (int axis = 0; axis < 3; ++axis) e.box[axis] += w * Interval(x[axis]);
  }
  e.valid = true;
  return e;
}

const RationalPoint* ExactVertex::rationals() const {
  if (!store_) return &own_.get([] { return RationalPoint{}; });
  if (!shared_) shared_ = &store_->entry(q_);
  return shared_;
}

const RationalPoint* ExactVertex::rationals_if_made() const {
  if (!store_) return own_ ? &own_.get([] { return RationalPoint{}; }) : nullptr;
  return shared_ ? shared_ : store_->find(q_);
}

const ExactPoint& ExactVertex::p() const {
  auto make = [&] {
    if (!ctx_ || !ctx_->vertices) throw std::logic_error("ExactVertex::p: a point that names no vertex");
    if (source_ == Source::Symbolic) return exact_position(q_, *ctx_);
    const Q b[3] = {Q(barycentric_->x), Q(barycentric_->y), Q(barycentric_->z)};
    const Q sum = b[0] + b[1] + b[2];
    ExactPoint x{Q(0), Q(0), Q(0)};
    for (int c = 0; c < 3; ++c) {
      const ExactPoint corner = to_exact(ctx_->vertices[q_.v[c]]);
      x.x += b[c] * corner.x / sum;
      x.y += b[c] * corner.y / sum;
      x.z += b[c] * corner.z / sum;
    }
    return x;
  };
  return rationals()->point.get(make);
}

const Q& ExactVertex::edge_parameter() const {
  auto make = [&] {
    if (!ctx_ || !ctx_->vertices) throw std::logic_error("ExactVertex::edge_parameter: a point that names no vertex");
    return exact_edge_parameter(q_, *ctx_);
  };
  return rationals()->parameter.get(make);
}

bool ExactVertex::has_rationals() const {
  const RationalPoint* e = rationals_if_made();
  return e && e->made();
}

bool ExactVertex::has_point() const {
  const RationalPoint* e = rationals_if_made();
  return e && static_cast<bool>(e->point);
}

int ExactVertices::index(const SymbolicVertex& q) {
  const int id = add(q);
  make_points();
  return id;
}

int ExactVertices::add(const SymbolicVertex& q) { return symbolic_.insert(q); }

ExactVertices::~ExactVertices() {
  std::destroy_n(points_, size_);
  std::allocator<ExactVertex>().deallocate(points_, capacity_);
}

void ExactVertices::make_points() {
  const std::size_t from = size_, to = symbolic_.size();
  if (from == to) return;
  if (to > capacity_) {
    const std::size_t capacity = std::max(to, 2 * capacity_);
    ExactVertex* points = std::allocator<ExactVertex>().allocate(capacity);
    std::uninitialized_move_n(points_, size_, points);
    std::destroy_n(points_, size_);
    std::allocator<ExactVertex>().deallocate(points_, capacity_);
    points_ = points;
    capacity_ = capacity;
  }
  auto make = [&](std::size_t k) { new (points_ + k) ExactVertex(ExactVertex::of(symbolic_[k], ctx_)); };
  if (to - from < 1024) {
    for (std::size_t k = from; k < to; ++k) make(k);
  } else {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(from, to, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k != r.end(); ++k) make(k);
    });
  }
  size_ = to;
}

Frame triangle_frame(const SurfaceMesh& mesh, int t, const std::array<const ExactVertex*, 3>& corners) {
  // The axes in decreasing order of the normal's doubles (a guess, ties in axis order); the
  // first whose exact projected orientation is not zero is dropped.
  const Triangle& tri = mesh.triangle(t);
  const Vec3& a = mesh.position(tri[0]);
  const Vec3 n = cross(mesh.position(tri[1]) - a, mesh.position(tri[2]) - a);
  double key[3];
  for (int axis = 0; axis < 3; ++axis) key[axis] = std::isnan(n[axis]) ? 0.0 : std::fabs(n[axis]);
  std::array<int, 3> order{0, 1, 2};  // an insertion sort: stable
  for (int i = 1; i < 3; ++i)
    for (int j = i; j > 0 && key[order[j]] > key[order[j - 1]]; --j) std::swap(order[j], order[j - 1]);
  for (int drop : order) {
    Frame f;
    f.u = (drop + 1) % 3;
    f.v = (drop + 2) % 3;
    const Sign s = orient(*corners[0], *corners[1], *corners[2], f);  // with sign = +1: the plain projected orientation
    if (s == Sign::Zero) continue;
    f.sign = s == Sign::Positive ? 1 : -1;
    f.valid = true;
    return f;
  }
  return Frame{};
}

Sign orient(const ExactVertex& a, const ExactVertex& b, const ExactVertex& c, const Frame& f) {
  const int u = f.u, v = f.v;
  Sign s;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    s = filtered_sign((b.box[u] - a.box[u]) * (c.box[v] - a.box[v]) - (b.box[v] - a.box[v]) * (c.box[u] - a.box[u]));
  }
  if (s == Sign::Zero) return orient_exact(a, b, c, f);
  return f.sign > 0 ? s : -s;
}

Sign orient_exact(const ExactVertex& a, const ExactVertex& b, const ExactVertex& c, const Frame& f) {
  const int u = f.u, v = f.v;
  const Q& ax = coordinate(a.p(), u);
  const Q& ay = coordinate(a.p(), v);
  const Q det = (coordinate(b.p(), u) - ax) * (coordinate(c.p(), v) - ay) -
                (coordinate(b.p(), v) - ay) * (coordinate(c.p(), u) - ax);
  const Sign s = sign_of(det);
  return f.sign > 0 ? s : -s;
}

std::uint8_t edges_of(const SymbolicVertex& q, const Triangle& tri) {
  // As SymbolicVertex::on_mesh_edge(tri[e], tri[e + 1]) for each e: a corner is on the two edges
  // through it, a type B vertex on the edge it names.
  if (q.type == SymbolicVertex::Type::C) return 0;
  auto corner = [&](int v) { return v == tri[0] ? 0 : (v == tri[1] ? 1 : (v == tri[2] ? 2 : -1)); };
  const int a = corner(q.v[0]);
  if (a < 0) return 0;
  if (q.type == SymbolicVertex::Type::A) return static_cast<std::uint8_t>((1 << a) | (1 << ((a + 2) % 3)));
  const int b = corner(q.v[1]);
  if (b < 0 || a == b || q.v[0] > q.v[1]) return 0;  // edge e runs from corner e to corner e + 1
  return static_cast<std::uint8_t>(1 << (b == (a + 1) % 3 ? a : b));
}

Q twice_area(const std::vector<const ExactVertex*>& polygon, const Frame& f) {
  Q sum(0);
  const size_t n = polygon.size();
  if (n < 3) return sum;
  // Relative to the first vertex: same value, smaller products.
  const Q& ox = coordinate(polygon[0]->p(), f.u);
  const Q& oy = coordinate(polygon[0]->p(), f.v);
  for (size_t k = 1; k + 1 < n; ++k) {
    const ExactPoint& p = polygon[k]->p();
    const ExactPoint& q = polygon[k + 1]->p();
    sum += (coordinate(p, f.u) - ox) * (coordinate(q, f.v) - oy) - (coordinate(q, f.u) - ox) * (coordinate(p, f.v) - oy);
  }
  return f.sign > 0 ? sum : -sum;
}

Sign area_sign(const std::vector<const ExactVertex*>& polygon, const Frame& f) {
  const size_t n = polygon.size();
  if (n < 3) return Sign::Zero;
  Sign s;
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const Interval& ox = polygon[0]->box[f.u];
    const Interval& oy = polygon[0]->box[f.v];
    Interval sum(0);
    for (size_t k = 1; k + 1 < n; ++k) {
      const ExactVertex& p = *polygon[k];
      const ExactVertex& q = *polygon[k + 1];
      sum += (p.box[f.u] - ox) * (q.box[f.v] - oy) - (q.box[f.u] - ox) * (p.box[f.v] - oy);
    }
    s = filtered_sign(sum);
  }
  if (s == Sign::Zero) return sign_of(twice_area(polygon, f));
  return f.sign > 0 ? s : -s;
}

bool within_edge(const ExactVertex& b) {
  const Interval& s = b.parameter_box;
  if (s.inf() >= 0 && s.sup() <= 1) return true;
  if (s.inf() > 1 || s.sup() < 0) return false;
  return !CGAL::is_negative(b.edge_parameter()) && b.edge_parameter() <= Q(1);
}

EdgePosition EdgePosition::of(std::uint64_t id, const SymbolicVertex& q, const ExactVertex& x, int from) {
  EdgePosition e;
  e.id = id;
  if (q.type == SymbolicVertex::Type::A) {
    e.end = q.v[0] == from ? 0 : 1;
  } else {
    e.vertex = &x;
    e.reversed = q.v[0] != from;
  }
  return e;
}

Q EdgePosition::exact() const {
  if (!vertex) return Q(end);
  return reversed ? Q(1) - vertex->edge_parameter() : vertex->edge_parameter();
}

std::optional<Sign> compare_filtered(const EdgePosition& x, const EdgePosition& y) {
  if (x.id == y.id && x.reversed == y.reversed) return Sign::Zero;
  Sign s = Sign::Zero;
  if (!x.reversed && !y.reversed) {
    // Both boxes hold the positions themselves: disjoint boxes order them, and no arithmetic
    // (nor rounding mode) is needed. Overlapping ones are what the filter below leaves undecided.
    const Interval bx = x.vertex ? x.vertex->parameter_box : Interval(x.end);
    const Interval by = y.vertex ? y.vertex->parameter_box : Interval(y.end);
    if (bx.inf() > by.sup()) s = Sign::Positive;
    else if (bx.sup() < by.inf()) s = Sign::Negative;
  } else {
    auto box = [](const EdgePosition& e) {
      if (!e.vertex) return Interval(e.end);
      return e.reversed ? Interval(1) - e.vertex->parameter_box : e.vertex->parameter_box;
    };
    CGAL::Protect_FPU_rounding<true> upward;
    s = filtered_sign(box(x) - box(y));
  }
  if (s == Sign::Zero) return std::nullopt;
  return s;
}

Sign compare(const EdgePosition& x, const EdgePosition& y) {
  if (const std::optional<Sign> s = compare_filtered(x, y)) return *s;
  return sign_of(x.exact() - y.exact());
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
  return compare_power_distance_exact(q, a, b);
}

Sign compare_power_distance_exact(const ExactVertex& q, const Site& a, const Site& b) {
  Q exact(0);
  for (int c = 0; c < 3; ++c) {
    const Q pa(a.p[c]), pb(b.p[c]);
    exact += Q(2) * coordinate(q.p(), c) * (pb - pa) + pa * pa - pb * pb;
  }
  exact += Q(b.w) - Q(a.w);
  return sign_of(exact);
}

std::vector<SiteTerms> site_terms(const std::vector<Site>& sites) {
  std::vector<SiteTerms> terms(sites.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sites.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    CGAL::Protect_FPU_rounding<true> upward;
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const Site& s = sites[k];
      terms[k].x2 = 2.0 * s.p;
      terms[k].c = Interval(s.p.x) * s.p.x + Interval(s.p.y) * s.p.y + Interval(s.p.z) * s.p.z - s.w;
    }
  });
  return terms;
}

void merge_into(PropertyResult& into, const PropertyResult& part) {
  into.passed = into.passed && part.passed;
  into.checked += part.checked;
  into.violations += part.violations;
  for (const std::string& s : part.first_offenders)
    if (into.first_offenders.size() < 10) into.first_offenders.push_back(s);
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
