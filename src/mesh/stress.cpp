// Stress meshes: the eight generators and the catalog that `lrvd stress` lists (see stress.h).
#include "mesh/stress.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "common/error.h"
#include "mesh/stress_builders.h"

namespace lrvd {

namespace {

constexpr double kPi = 3.14159265358979323846;

using stress::MeshParts;
using Point2 = std::array<double, 2>;

void require_positive(const char* model, const char* option, double value) {
  if (!(value > 0) || !std::isfinite(value))
    throw InputError(fmt::format("{}: option {} must be a positive number (got {})", model, option, value));
}

void require_count(const char* model, const char* option, int value, int minimum) {
  if (value < minimum || value > 1000000)
    throw InputError(fmt::format("{}: option {} must be in [{}, 1000000] (got {})", model, option, minimum, value));
}

// n + 1 values from a to b; both ends exact.
std::vector<double> subdivide(double a, double b, int n) {
  std::vector<double> out(n + 1);
  for (int i = 0; i < n; ++i) out[i] = a + (b - a) * (static_cast<double>(i) / n);
  out[n] = b;
  return out;
}

SurfaceMesh to_mesh(MeshParts parts) { return SurfaceMesh(std::move(parts.positions), std::move(parts.triangles)); }

// Trefoil centre curve (scale 1) and its derivative.
Vec3 trefoil(double t) {
  return {std::sin(t) + 2.0 * std::sin(2.0 * t), std::cos(t) - 2.0 * std::cos(2.0 * t), -std::sin(3.0 * t)};
}
Vec3 trefoil_derivative(double t) {
  return {std::cos(t) + 4.0 * std::cos(2.0 * t), -std::sin(t) + 4.0 * std::sin(2.0 * t), -3.0 * std::cos(3.0 * t)};
}

}  // namespace

SurfaceMesh make_thin_plate(const ThinPlateOptions& o) {
  const char* model = "thin_plate";
  require_positive(model, "size_x", o.size_x);
  require_positive(model, "size_y", o.size_y);
  require_positive(model, "thickness", o.thickness);
  require_count(model, "cells_x", o.cells_x, 1);
  require_count(model, "cells_y", o.cells_y, 1);
  // One layer of cells: the box boundary with gridded top and bottom and one-cell-high side walls.
  return to_mesh(stress::grid_union_boundary(subdivide(-o.size_x / 2, o.size_x / 2, o.cells_x),
                                             subdivide(-o.size_y / 2, o.size_y / 2, o.cells_y),
                                             {-o.thickness / 2, o.thickness / 2}, [](int, int, int) { return true; }));
}

SurfaceMesh make_folded_sheet(const FoldedSheetOptions& o) {
  const char* model = "folded_sheet";
  require_positive(model, "wall_length", o.wall_length);
  require_positive(model, "gap", o.gap);
  require_positive(model, "thickness", o.thickness);
  require_positive(model, "width", o.width);
  require_count(model, "wall_segments", o.wall_segments, 1);
  require_count(model, "bend_segments", o.bend_segments, 2);
  require_count(model, "width_segments", o.width_segments, 1);
  // The strip's inner side (facing the gap) runs along the upper wall towards +x, around the bend
  // at +x and back along the lower wall: the strip lies on its left.
  const double inner = o.gap / 2, outer = o.gap / 2 + o.thickness, half = o.wall_length / 2;
  const std::vector<double> xs = subdivide(-half, half, o.wall_segments);
  std::vector<Point2> left, right;
  for (double x : xs) {
    right.push_back({x, inner});
    left.push_back({x, outer});
  }
  for (int k = 1; k < o.bend_segments; ++k) {
    const double angle = kPi / 2 - kPi * k / o.bend_segments;
    right.push_back({half + inner * std::cos(angle), inner * std::sin(angle)});
    left.push_back({half + outer * std::cos(angle), outer * std::sin(angle)});
  }
  for (auto x = xs.rbegin(); x != xs.rend(); ++x) {
    right.push_back({*x, -inner});
    left.push_back({*x, -outer});
  }
  return to_mesh(stress::extrude_strip(left, right, -o.width / 2, o.width / 2, o.width_segments));
}

SurfaceMesh make_open_cup(const OpenCupOptions& o) {
  const char* model = "open_cup";
  require_positive(model, "radius", o.radius);
  require_positive(model, "height", o.height);
  require_positive(model, "wall_thickness", o.wall_thickness);
  require_count(model, "angular_segments", o.angular_segments, 3);
  require_count(model, "bottom_segments", o.bottom_segments, 1);
  require_count(model, "wall_segments", o.wall_segments, 1);
  require_count(model, "rim_segments", o.rim_segments, 1);
  const double w = o.wall_thickness;
  if (!(w < o.radius) || !(w < o.height))
    throw InputError(fmt::format("{}: wall_thickness ({}) must be below radius ({}) and height ({})", model, w,
                                 o.radius, o.height));
  // Profile in the (r, z) half-plane, counterclockwise around the wall's cross-section: bottom pole,
  // outer bottom, outer wall, rim, inner wall, inner bottom, top pole (the inner bottom's centre).
  const double r_out = o.radius + w / 2, r_in = o.radius - w / 2;
  const double z_bottom = -o.height / 2, z_rim = o.height / 2, z_floor = z_bottom + w;
  std::vector<Point2> profile{{0.0, z_bottom}};
  auto add_run = [&profile](Point2 from, Point2 to, int segments) {
    const std::vector<double> r = subdivide(from[0], to[0], segments), z = subdivide(from[1], to[1], segments);
    for (int k = 1; k <= segments; ++k) profile.push_back({r[k], z[k]});
  };
  add_run({0.0, z_bottom}, {r_out, z_bottom}, o.bottom_segments);
  add_run({r_out, z_bottom}, {r_out, z_rim}, o.wall_segments);
  add_run({r_out, z_rim}, {r_in, z_rim}, o.rim_segments);
  add_run({r_in, z_rim}, {r_in, z_floor}, o.wall_segments);
  add_run({r_in, z_floor}, {0.0, z_floor}, o.bottom_segments);
  return to_mesh(stress::revolve_profile(profile, o.angular_segments));
}

SurfaceMesh make_flat_ellipsoid(const FlatEllipsoidOptions& o) {
  const char* model = "flat_ellipsoid";
  require_positive(model, "semi_axes.x", o.semi_axes.x);
  require_positive(model, "semi_axes.y", o.semi_axes.y);
  require_positive(model, "semi_axes.z", o.semi_axes.z);
  require_count(model, "subdivision", o.subdivision, 1);
  // The affine image of a point on the unit sphere lies on the ellipsoid (up to one rounding per
  // coordinate, the best a double can do).
  MeshParts parts = stress::unit_icosphere(o.subdivision);
  for (Vec3& p : parts.positions) p = {o.semi_axes.x * p.x, o.semi_axes.y * p.y, o.semi_axes.z * p.z};
  return to_mesh(std::move(parts));
}

double trefoil_closest_approach() {
  // Smallest distance between curve points at least 1/8 of the period apart (nearer points are on
  // the same strand: the chord there is > 2, the answer ≈ 1.21), found on a grid then polished by
  // a pattern search; a local minimum of the distance is a doubly-critical pair.
  static const double closest = [] {
    const int n = 720;
    std::vector<Vec3> p(n);
    for (int i = 0; i < n; ++i) p[i] = trefoil(2.0 * kPi * i / n);
    double best = INFINITY;
    int best_i = 0, best_j = 0;
    for (int i = 0; i < n; ++i)
      for (int j = i + n / 8; j <= i + n - n / 8 && j < n; ++j) {
        const double d = squared_distance(p[i], p[j]);
        if (d < best) { best = d; best_i = i; best_j = j; }
      }
    double s = 2.0 * kPi * best_i / n, t = 2.0 * kPi * best_j / n;
    best = squared_distance(trefoil(s), trefoil(t));
    for (double h = 2.0 * kPi / n; h > 1e-13;) {
      bool moved = false;
      for (int ds = -1; ds <= 1; ++ds)
        for (int dt = -1; dt <= 1; ++dt) {
          const double d = squared_distance(trefoil(s + ds * h), trefoil(t + dt * h));
          if (d < best) { best = d; s += ds * h; t += dt * h; moved = true; }
        }
      if (!moved) h /= 2;
    }
    return std::sqrt(best);
  }();
  return closest;
}

SurfaceMesh make_knot_tube(const KnotTubeOptions& o) {
  const char* model = "knot_tube";
  require_positive(model, "scale", o.scale);
  require_positive(model, "tube_radius_fraction", o.tube_radius_fraction);
  if (!(o.tube_radius_fraction < 1))
    throw InputError(fmt::format("{}: option tube_radius_fraction must be below 1 (got {}): the strands would touch",
                                 model, o.tube_radius_fraction));
  require_count(model, "rings", o.rings, 3);
  require_count(model, "ring_segments", o.ring_segments, 3);
  // Half the closest approach (≈ 0.607) is below the curve's smallest radius of curvature (≈ 1.29),
  // so it is the reach of the curve: any smaller radius gives an embedded tube.
  const double radius = o.tube_radius_fraction * o.scale * trefoil_closest_approach() / 2;
  std::vector<Vec3> centers(o.rings), normals(o.rings), binormals(o.rings);
  const Vec3 up{0, 0, 1};
  for (int i = 0; i < o.rings; ++i) {
    const double t = 2.0 * kPi * i / o.rings;
    const Vec3 d = trefoil_derivative(t);
    const Vec3 tangent = d / norm(d);
    // The tangent stays within 45° of the xy-plane (|xy'|² = 17 + 8 cos 3t >= 9 >= z'²), so the
    // projection of +z onto the normal plane is a smooth periodic frame with no twist correction.
    const Vec3 normal = up - dot(up, tangent) * tangent;
    centers[i] = o.scale * trefoil(t);
    normals[i] = normal / norm(normal);
    binormals[i] = cross(tangent, normals[i]);
  }
  return to_mesh(stress::closed_tube(centers, normals, binormals, radius, o.ring_segments));
}

SurfaceMesh make_comb(const CombOptions& o) {
  const char* model = "comb";
  require_count(model, "finger_count", o.finger_count, 1);
  require_positive(model, "finger_width", o.finger_width);
  require_positive(model, "finger_gap", o.finger_gap);
  require_positive(model, "finger_length", o.finger_length);
  require_positive(model, "depth", o.depth);
  require_positive(model, "base_height", o.base_height);
  require_count(model, "cells_per_finger_width", o.cells_per_finger_width, 1);
  require_count(model, "cells_per_gap", o.cells_per_gap, 1);
  require_count(model, "depth_cells", o.depth_cells, 1);
  require_count(model, "length_cells", o.length_cells, 1);
  require_count(model, "base_height_cells", o.base_height_cells, 1);
  // Grid columns along x alternate finger, gap, finger, ...; the base fills every column.
  const double pitch = o.finger_width + o.finger_gap;
  const double x0 = -(o.finger_count * pitch - o.finger_gap) / 2;
  std::vector<double> xs{x0};
  std::vector<char> finger_column;
  for (int f = 0; f < o.finger_count; ++f) {
    const double start = x0 + f * pitch, end = start + o.finger_width;
    const std::vector<double> finger = subdivide(start, end, o.cells_per_finger_width);
    xs.insert(xs.end(), finger.begin() + 1, finger.end());
    finger_column.insert(finger_column.end(), o.cells_per_finger_width, 1);
    if (f + 1 == o.finger_count) break;
    const std::vector<double> gap = subdivide(end, x0 + (f + 1) * pitch, o.cells_per_gap);
    xs.insert(xs.end(), gap.begin() + 1, gap.end());
    finger_column.insert(finger_column.end(), o.cells_per_gap, 0);
  }
  const double z0 = -(o.base_height + o.finger_length) / 2, z_top_of_base = z0 + o.base_height;
  std::vector<double> zs = subdivide(z0, z_top_of_base, o.base_height_cells);
  const std::vector<double> fingers = subdivide(z_top_of_base, z_top_of_base + o.finger_length, o.length_cells);
  zs.insert(zs.end(), fingers.begin() + 1, fingers.end());
  const int base_cells = o.base_height_cells;
  // Finger columns are separated by gap columns, so no two filled cells meet only at an edge.
  return to_mesh(stress::grid_union_boundary(
      xs, subdivide(-o.depth / 2, o.depth / 2, o.depth_cells), zs,
      [&](int i, int, int k) { return k < base_cells || finger_column[i] != 0; }));
}

SurfaceMesh make_interpenetrating_spheres(const InterpenetratingSpheresOptions& o) {
  const char* model = "interpenetrating_spheres";
  require_positive(model, "radius_a", o.radius_a);
  require_positive(model, "radius_b", o.radius_b);
  require_count(model, "subdivision", o.subdivision, 1);
  const double d = distance(o.center_a, o.center_b);
  if (!(d < o.radius_a + o.radius_b) || !(d > std::fabs(o.radius_a - o.radius_b)))
    throw InputError(fmt::format("{}: the spheres do not interpenetrate: centre distance {} must lie between "
                                 "|radius_a - radius_b| = {} and radius_a + radius_b = {}",
                                 model, d, std::fabs(o.radius_a - o.radius_b), o.radius_a + o.radius_b));
  const MeshParts unit = stress::unit_icosphere(o.subdivision);
  MeshParts a = unit, b = unit;
  for (Vec3& p : a.positions) p = o.center_a + o.radius_a * p;
  // Turn b's lattice (0.5 rad about z, then 0.3 rad about x) so its vertices do not mirror a's.
  const double cz = std::cos(0.5), sz = std::sin(0.5), cx = std::cos(0.3), sx = std::sin(0.3);
  for (Vec3& p : b.positions) {
    const Vec3 q{cz * p.x - sz * p.y, sz * p.x + cz * p.y, p.z};
    p = o.center_b + o.radius_b * Vec3{q.x, cx * q.y - sx * q.z, sx * q.y + cx * q.z};
  }
  stress::append(a, b);
  return to_mesh(std::move(a));
}

SurfaceMesh make_thin_tube(const ThinTubeOptions& o) {
  const char* model = "thin_tube";
  require_positive(model, "length", o.length);
  require_positive(model, "radius", o.radius);
  if (!(o.length > 2 * o.radius))
    throw InputError(fmt::format("{}: length ({}) must exceed the two caps, 2 * radius ({})", model, o.length,
                                 2 * o.radius));
  require_count(model, "ring_segments", o.ring_segments, 3);
  require_count(model, "length_segments", o.length_segments, 1);
  require_count(model, "cap_segments", o.cap_segments, 1);
  // Capsule profile along the axis: quarter circle, straight part, quarter circle, pole to pole.
  const double r = o.radius, h = o.length / 2 - r;
  std::vector<Point2> profile{{0.0, -o.length / 2}};
  for (int k = 1; k < o.cap_segments; ++k) {
    const double angle = -kPi / 2 + (kPi / 2) * k / o.cap_segments;
    profile.push_back({r * std::cos(angle), -h + r * std::sin(angle)});
  }
  for (double z : subdivide(-h, h, o.length_segments)) profile.push_back({r, z});
  for (int k = 1; k < o.cap_segments; ++k) {
    const double angle = (kPi / 2) * k / o.cap_segments;
    profile.push_back({r * std::cos(angle), h + r * std::sin(angle)});
  }
  profile.push_back({0.0, o.length / 2});
  // Revolved about z, then laid along x by the cyclic (orientation-preserving) map (x,y,z) -> (z,x,y).
  MeshParts parts = stress::revolve_profile(profile, o.ring_segments);
  for (Vec3& p : parts.positions) p = {p.z, p.x, p.y};
  return to_mesh(std::move(parts));
}

namespace {

int scaled(int count, double scale, int minimum) {
  const double value = std::round(count * scale);
  if (value > 1000000)
    throw InputError(fmt::format("resolution_scale {} is too large: a subdivision count would be {}", scale, value));
  return std::max(minimum, static_cast<int>(value));
}

struct CatalogEntry {
  StressMeshInfo info;
  SurfaceMesh (*make)(double scale);
};

const std::vector<CatalogEntry>& catalog() {
  static const std::vector<CatalogEntry> entries{
      {{"thin_plate", "closed thin box 1 x 1 x 0.01: two parallel sheets far closer than the sample spacing",
        true, 2, 1},
       [](double s) {
         ThinPlateOptions o;
         o.cells_x = scaled(o.cells_x, s, 1);
         o.cells_y = scaled(o.cells_y, s, 1);
         return make_thin_plate(o);
       }},
      {{"folded_sheet",
        "closed U-shaped slab: a sheet 0.005 thick folded so its 1.0-long walls face each other 0.02 apart", true,
        2, 1},
       [](double s) {
         FoldedSheetOptions o;
         o.wall_segments = scaled(o.wall_segments, s, 1);
         o.bend_segments = scaled(o.bend_segments, s, 2);
         o.width_segments = scaled(o.width_segments, s, 1);
         return make_folded_sheet(o);
       }},
      {{"open_cup",
        "thin-walled cup (radius 0.5, height 1, wall 0.01) as one closed surface: inner and outer sheets "
        "joined at the rim",
        true, 2, 1},
       [](double s) {
         OpenCupOptions o;
         o.angular_segments = scaled(o.angular_segments, s, 3);
         o.bottom_segments = scaled(o.bottom_segments, s, 1);
         o.wall_segments = scaled(o.wall_segments, s, 1);
         o.rim_segments = scaled(o.rim_segments, s, 1);
         return make_open_cup(o);
       }},
      {{"flat_ellipsoid", "the paper's flat ellipsoid: semi-axes 1, 0.5, 0.05 from a subdivided icosahedron", true,
        2, 1},
       [](double s) {
         FlatEllipsoidOptions o;
         o.subdivision = scaled(o.subdivision, s, 1);
         return make_flat_ellipsoid(o);
       }},
      {{"knot_tube", "trefoil-knot tube whose strands nearly touch at the crossings (gap 10% of the closest approach)",
        true, 0, 1},
       [](double s) {
         KnotTubeOptions o;
         o.rings = scaled(o.rings, s, 3);
         o.ring_segments = scaled(o.ring_segments, s, 3);
         return make_knot_tube(o);
       }},
      {{"comb", "base block with 8 fingers 1.2 long and 0.01 apart: nearly touching parts", true, 2, 1},
       [](double s) {
         CombOptions o;
         o.cells_per_finger_width = scaled(o.cells_per_finger_width, s, 1);
         o.cells_per_gap = scaled(o.cells_per_gap, s, 1);
         o.depth_cells = scaled(o.depth_cells, s, 1);
         o.length_cells = scaled(o.length_cells, s, 1);
         o.base_height_cells = scaled(o.base_height_cells, s, 1);
         return make_comb(o);
       }},
      {{"interpenetrating_spheres",
        "two closed spheres (radii 0.6, 0.5) that pass through each other: one self-intersecting mesh", true, 4,
        2},
       [](double s) {
         InterpenetratingSpheresOptions o;
         o.subdivision = scaled(o.subdivision, s, 1);
         return make_interpenetrating_spheres(o);
       }},
      {{"thin_tube", "closed capsule 2.0 long with radius 0.03: the paper's thin-tube failure case", true, 2, 1},
       [](double s) {
         ThinTubeOptions o;
         o.ring_segments = scaled(o.ring_segments, s, 3);
         o.length_segments = scaled(o.length_segments, s, 1);
         o.cap_segments = scaled(o.cap_segments, s, 1);
         return make_thin_tube(o);
       }},
  };
  return entries;
}

}  // namespace

std::vector<StressMeshInfo> stress_mesh_catalog() {
  std::vector<StressMeshInfo> out;
  for (const CatalogEntry& e : catalog()) out.push_back(e.info);
  return out;
}

SurfaceMesh make_stress_mesh(const std::string& name, double resolution_scale) {
  if (!(resolution_scale > 0) || !std::isfinite(resolution_scale))
    throw InputError(fmt::format("resolution scale must be a positive number (got {})", resolution_scale));
  std::string names;
  for (const CatalogEntry& e : catalog()) {
    if (e.info.name == name) return e.make(resolution_scale);
    names += (names.empty() ? "" : ", ") + e.info.name;
  }
  throw InputError(fmt::format("unknown stress mesh '{}'; valid names: {}", name, names));
}

}  // namespace lrvd
