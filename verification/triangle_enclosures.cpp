// Per-triangle interval enclosures of symbolic vertices: enclose_position's formulas (type B: q1 +
// t (q2 - q1), t = F1 / (F1 - F2); type C: Cramer's rule relative to corner 0), each operation in
// the same order on the same operands, so the intervals are the same bits; the squared distances
// from the corners to the sites and the triangle's normal made once per triangle.
#include "verification/triangle_enclosures.h"

#include <cmath>

namespace lrvd::verify_detail {

namespace {

using Interval = TriangleEnclosures::Interval;
using V3 = TriangleEnclosures::V3;

V3 lift(const Vec3& a) { return {Interval(a.x), Interval(a.y), Interval(a.z)}; }
V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator*(const Interval& s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
Interval dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(const V3& a, const V3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

bool finite_interval(const Interval& i) { return std::isfinite(i.inf()) && std::isfinite(i.sup()); }

// With this many sites or fewer, a site's distances are looked for one by one.
constexpr std::size_t kLinearUpTo = 8;

}  // namespace

void TriangleEnclosures::reset(const std::array<int, 3>& tri, const SymbolicContext& ctx) {
  tri_ = tri;
  ctx_ = &ctx;
  for (int c = 0; c < 3; ++c) corner_[c] = lift(ctx.vertices[tri[c]]);
  normal_.reset();
  distances_.clear();
  slots_.clear();
}

// The index of the site's entry in distances_, made the first time.
int TriangleEnclosures::site_index(int site) {
  if (distances_.size() < kLinearUpTo || slots_.empty()) {
    for (std::size_t k = 0; k < distances_.size(); ++k)
      if (distances_[k].site == site) return static_cast<int>(k);
    if (distances_.size() < kLinearUpTo) {
      distances_.push_back({site, 0, {}});
      return static_cast<int>(distances_.size()) - 1;
    }
  }
  if (2 * distances_.size() >= slots_.size()) {  // (re)build the table, at most half full
    slots_.assign(std::max<std::size_t>(64, 4 * distances_.size()), -1);
    for (std::size_t k = 0; k < distances_.size(); ++k) {
      std::size_t j = static_cast<std::size_t>(distances_[k].site) * 0x9E3779B1u & (slots_.size() - 1);
      while (slots_[j] >= 0) j = (j + 1) & (slots_.size() - 1);
      slots_[j] = static_cast<int>(k);
    }
  }
  std::size_t j = static_cast<std::size_t>(site) * 0x9E3779B1u & (slots_.size() - 1);
  for (; slots_[j] >= 0; j = (j + 1) & (slots_.size() - 1))
    if (distances_[slots_[j]].site == site) return slots_[j];
  distances_.push_back({site, 0, {}});
  slots_[j] = static_cast<int>(distances_.size()) - 1;
  return slots_[j];
}

// |corner c - x_s|^2 of the entry, as bisector_value evaluates dot(u, u), u = corner - x_s.
const Interval& TriangleEnclosures::distance(int index, int c) {
  Distances& d = distances_[index];
  if (!(d.made >> c & 1)) {
    const V3 u = corner_[c] - lift(ctx_->sites[d.site].p);
    d.d[c] = dot(u, u);
    d.made |= static_cast<std::uint8_t>(1 << c);
  }
  return d.d[c];
}

// f_ab at corner c: dot(u, u) - dot(v, v) - w_a + w_b with u = corner - x_a, v = corner - x_b.
Interval TriangleEnclosures::bisector_value(int c, int a, int b) {
  const int ia = site_index(a), ib = site_index(b);
  return distance(ia, c) - distance(ib, c) - Interval(ctx_->sites[a].w) + Interval(ctx_->sites[b].w);
}

bool TriangleEnclosures::enclose(const SymbolicVertex& q, std::array<Interval, 3>& box, Interval& parameter) {
  if (q.type == SymbolicVertex::Type::A) {
    const Vec3& p = ctx_->vertices[q.v[0]];
    box = {Interval(p.x), Interval(p.y), Interval(p.z)};
    parameter = Interval(0);
    return true;
  }
  if (q.type == SymbolicVertex::Type::B) {
    const int c0 = corner(q.v[0]), c1 = corner(q.v[1]);
    if (c0 >= 0 && c1 >= 0) return on_edge(q, c0, c1, box, parameter);
  } else if (q.v == tri_) {
    parameter = Interval(0);
    return in_plane(q, box);
  }
  // A vertex of another triangle or edge (a malformed diagram).
  const std::optional<PositionEnclosure> e = enclose_position(q, *ctx_);
  if (!e) return false;
  box = e->box;
  parameter = e->parameter;
  return true;
}

// Type B on the edge from corner c0 (its v[0]) to corner c1.
bool TriangleEnclosures::on_edge(const SymbolicVertex& q, int c0, int c1, std::array<Interval, 3>& box,
                                 Interval& parameter) {
  const V3& origin = corner_[c0];
  const V3 direction = corner_[c1] - origin;
  const int ia = site_index(q.label[0]), ib = site_index(q.label[1]);
  const Interval wa(ctx_->sites[q.label[0]].w), wb(ctx_->sites[q.label[1]].w);
  const Interval numerator = distance(ia, c0) - distance(ib, c0) - wa + wb;
  const Interval denominator = numerator - (distance(ia, c1) - distance(ib, c1) - wa + wb);
  if (!(denominator.inf() > 0 || denominator.sup() < 0)) return false;
  parameter = numerator / denominator;
  const V3 r = origin + parameter * direction;
  box = {r.x, r.y, r.z};
  return finite_interval(r.x) && finite_interval(r.y) && finite_interval(r.z) && finite_interval(parameter);
}

// Type C whose corners are the triangle's, in its order: relative to corner 0, n.x = 0 and
// 2 (x_m - x_a).x = -f_am(corner 0) for m = b, c.
bool TriangleEnclosures::in_plane(const SymbolicVertex& q, std::array<Interval, 3>& box) {
  const Site& a = ctx_->sites[q.label[0]];
  const Site& b = ctx_->sites[q.label[1]];
  const Site& c = ctx_->sites[q.label[2]];
  const V3& origin = corner_[0];
  if (!normal_) normal_ = cross(corner_[1] - origin, corner_[2] - origin);
  const V3& r0 = *normal_;
  const V3 r1 = Interval(2) * (lift(b.p) - lift(a.p)), r2 = Interval(2) * (lift(c.p) - lift(a.p));
  const Interval s1 = -bisector_value(0, q.label[0], q.label[1]), s2 = -bisector_value(0, q.label[0], q.label[2]);
  const Interval denominator = dot(r0, cross(r1, r2));
  if (!(denominator.inf() > 0 || denominator.sup() < 0)) return false;
  const V3 numerator = s1 * cross(r2, r0) + s2 * cross(r0, r1);
  const V3 r = origin + (Interval(1) / denominator) * numerator;
  box = {r.x, r.y, r.z};
  return finite_interval(r.x) && finite_interval(r.y) && finite_interval(r.z);
}

}  // namespace lrvd::verify_detail
