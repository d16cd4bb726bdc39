// Closest-point queries on a triangle mesh with Embree 3 user geometry (double-precision distances).
#include "mesh/closest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <embree3/rtcore.h>

#include "mesh/surface_mesh.h"

namespace lrvd {

namespace {

// Closest point of segment [a, b] to p, as barycentric weights (1 - s, s).
double segment_parameter(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = dot(ab, ab);
  if (!(len2 > 0)) return 0;
  return std::clamp(dot(p - a, ab) / len2, 0.0, 1.0);
}

// A triangle with coincident or collinear corners: the best of its three edges.
ClosestPoint closest_point_on_degenerate(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 corner[3] = {a, b, c};
  ClosestPoint best;
  best.distance = std::numeric_limits<double>::infinity();
  for (int e = 0; e < 3; ++e) {
    const int i = e, j = (e + 1) % 3;
    const double s = segment_parameter(p, corner[i], corner[j]);
    ClosestPoint r;
    r.point = (1 - s) * corner[i] + s * corner[j];
    r.barycentric[i] = 1 - s;
    r.barycentric[j] = s;
    r.distance = distance(p, r.point);
    if (r.distance < best.distance) best = r;
  }
  return best;
}

}  // namespace

ClosestPoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  if (!(squared_norm(cross(b - a, c - a)) > 0)) return closest_point_on_degenerate(p, a, b, c);
  // Region classification over the triangle's Voronoi regions (vertices, edges, face).
  auto make = [&](double u, double v, double w) {
    ClosestPoint r;
    r.barycentric = {u, v, w};
    r.point = u * a + v * b + w * c;
    r.distance = distance(p, r.point);
    return r;
  };
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return make(1, 0, 0);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return make(0, 1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return make(1 - v, v, 0);
  }
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return make(0, 0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return make(1 - w, 0, w);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return make(0, 1 - w, w);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return make(1 - v - w, v, w);
}

struct ClosestPointIndex::Impl {
  std::vector<Vec3> positions;
  std::vector<std::array<int, 3>> triangles;
  // Embree works in floats: it sees the mesh times this power of two, which brings the largest
  // coordinate into [1, 2), so that squared distances neither overflow nor vanish whatever the
  // model's unit. Scaling by a power of two is exact, so the traversal is the same at any scale.
  double scale = 1;
  // A model far from the origin for its size (a part at 1e8 in a plant's coordinates) would have
  // all its boxes within a few floats of each other, and every query would visit every triangle;
  // and a closest point computed at coordinates of 1000 is a few 1e-13 off, which is the size of
  // a model 1e-6 across. Such a model is kept relative to `origin`, a point near the centre of
  // its bounding box that is a multiple of the largest coordinate's unit in the last place: the
  // translation is exact (every coordinate is a multiple of its own unit, which divides that
  // one), so `positions` are the input's doubles moved, and distances are measured on them
  // with the precision of the model's size. The query point is moved the same way and the answer
  // moved back. Elsewhere `origin` is 0 and nothing moves.
  Vec3 origin;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

namespace {

float round_down(double x) {
  float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float round_up(double x) {
  float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

void triangle_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* impl = static_cast<const ClosestPointIndex::Impl*>(args->geometryUserPtr);
  const auto& tri = impl->triangles[args->primID];
  Vec3 lo = impl->positions[tri[0]], hi = lo;
  for (int k = 1; k < 3; ++k)
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], impl->positions[tri[k]][c]);
      hi[c] = std::max(hi[c], impl->positions[tri[k]][c]);
    }
  lo = impl->scale * lo, hi = impl->scale * hi;
  RTCBounds* box = args->bounds_o;
  box->lower_x = round_down(lo.x), box->lower_y = round_down(lo.y), box->lower_z = round_down(lo.z);
  box->upper_x = round_up(hi.x), box->upper_y = round_up(hi.y), box->upper_z = round_up(hi.z);
  if (impl->origin != Vec3{}) {  // one float more on every side covers a query point's rounded move
    constexpr float inf = std::numeric_limits<float>::infinity();
    box->lower_x = std::nextafter(box->lower_x, -inf), box->lower_y = std::nextafter(box->lower_y, -inf);
    box->lower_z = std::nextafter(box->lower_z, -inf);
    box->upper_x = std::nextafter(box->upper_x, inf), box->upper_y = std::nextafter(box->upper_y, inf);
    box->upper_z = std::nextafter(box->upper_z, inf);
  }
}

struct QueryState {
  const ClosestPointIndex::Impl* impl;
  Vec3 p;               // the query point, relative to the index's origin
  double query_offset;  // |p - float(p)| in Embree's units: the BVH measures from the rounded query point
  const int* group;     // if not null: only triangles t with group[t] == group_id count
  int group_id;
  ClosestPoint best;
};

bool visit_triangle(RTCPointQueryFunctionArguments* args) {
  auto* state = static_cast<QueryState*>(args->userPtr);
  if (state->group && state->group[args->primID] != state->group_id) return false;
  const auto& tri = state->impl->triangles[args->primID];
  const auto& pos = state->impl->positions;
  ClosestPoint c = closest_point_on_triangle(state->p, pos[tri[0]], pos[tri[1]], pos[tri[2]]);
  if (state->best.triangle >= 0 && !(c.distance < state->best.distance)) return false;
  c.triangle = static_cast<int>(args->primID);
  state->best = c;
  args->query->radius = round_up((state->impl->scale * c.distance + state->query_offset) * (1 + 1e-12));
  return true;
}

}  // namespace

ClosestPointIndex::ClosestPointIndex(const std::vector<Vec3>& positions,
                                     const std::vector<std::array<int, 3>>& triangles)
    : impl_(std::make_unique<Impl>()) {
  impl_->positions = positions;
  impl_->triangles = triangles;
  if (!positions.empty()) {
    const BoundingBox box = bounding_box(positions);
    const Vec3 centre = 0.5 * box.min + 0.5 * box.max, extent = box.max - box.min;
    const double size = std::max({extent.x, extent.y, extent.z});
    // Only where floats would lose the model: elsewhere the boxes are as they always were.
    const double reach = box.reach();
    if (is_finite(centre) && std::isfinite(reach) && reach > 0 &&
        std::max({std::abs(centre.x), std::abs(centre.y), std::abs(centre.z)}) > 64 * size) {
      const double unit = box.coordinate_step();
      impl_->origin = {unit * std::nearbyint(centre.x / unit), unit * std::nearbyint(centre.y / unit),
                       unit * std::nearbyint(centre.z / unit)};
      for (Vec3& p : impl_->positions) p = p - impl_->origin;  // exact
    }
  }
  double largest = 0;
  for (const Vec3& d : impl_->positions) largest = std::max({largest, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  // (A subnormal largest coordinate would need a factor beyond the doubles: it gets 2^1000.)
  if (largest > 0 && std::isfinite(largest)) impl_->scale = std::ldexp(1.0, std::min(-std::ilogb(largest), 1000));
  impl_->device = rtcNewDevice("threads=1");
  if (!impl_->device) throw std::runtime_error("Embree device could not be created");
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(triangles.size()));
  rtcSetGeometryUserData(geometry, impl_.get());
  rtcSetGeometryBoundsFunction(geometry, triangle_bounds, nullptr);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl_->scene);
}

ClosestPointIndex::ClosestPointIndex(const SurfaceMesh& mesh)
    : ClosestPointIndex(mesh.positions(), mesh.triangles()) {}

ClosestPointIndex::~ClosestPointIndex() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

ClosestPoint ClosestPointIndex::query(const Vec3& p, int hint) const { return query_within(p, nullptr, 0, hint); }

ClosestPoint ClosestPointIndex::query_within(const Vec3& p, const int* group, int g, int hint) const {
  RTCPointQuery q;
  const Vec3 moved = p - impl_->origin;  // exact for points within the model's reach
  const Vec3 scaled = impl_->scale * moved;
  q.x = static_cast<float>(scaled.x), q.y = static_cast<float>(scaled.y), q.z = static_cast<float>(scaled.z);
  const Vec3 rounded{q.x, q.y, q.z};
  // With an origin, the subtraction's rounding (at most 2^-53 of each coordinate) is added.
  const double offset = distance(scaled, rounded) + (impl_->origin != Vec3{} ? 0x1p-51 * norm(scaled) : 0.0);
  QueryState state{impl_.get(), moved, offset, group, g, {}};
  q.time = 0;
  q.radius = std::numeric_limits<float>::infinity();
  if (hint >= 0 && hint < static_cast<int>(impl_->triangles.size()) && (!group || group[hint] == g)) {
    // Only the radius is set: the hint is visited again in the traversal like any triangle, so
    // among triangles at the same distance the first one the traversal meets still wins, as
    // without a hint. The radius is the one visit_triangle would set after meeting the hint.
    const auto& tri = impl_->triangles[hint];
    const auto& pos = impl_->positions;
    // Embree compares its boxes' distances in floats: the margin is float-sized (16 units in the
    // last place), so the hint's own box is always within reach. With 1e-12, a point whose closest
    // point is a corner of its hint (a box corner) could find the box an ulp too far and get no
    // triangle at all (issue #51's pulled cube corner: index -1 read in the remesh's fitting).
    const double d = closest_point_on_triangle(moved, pos[tri[0]], pos[tri[1]], pos[tri[2]]).distance;
    q.radius = round_up((impl_->scale * d + state.query_offset) * (1 + 0x1p-20));
  }
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(impl_->scene, &q, &context, visit_triangle, &state);
  // A guard: a hint whose radius reached no box answers as a plain query, never -1.
  if (state.best.triangle < 0 && hint >= 0) return query_within(p, group, g);
  if (impl_->origin != Vec3{} && state.best.triangle >= 0) state.best.point = state.best.point + impl_->origin;
  return state.best;
}

}  // namespace lrvd
