// Building blocks of the stress meshes (mesh/stress.h): closed surfaces that are manifold and
// outward-oriented by construction — the boundary of a union of grid cells, a surface of
// revolution, a geodesic sphere, a tube around a closed curve, an extruded polygon strip.
// Internal to the stress generators; the vertex order they produce is part of their output.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "mesh/surface_mesh.h"
#include "predicates/vec3.h"

namespace lrvd::stress {

//! Positions and triangles before validation; parts are appended into one mesh.
struct MeshParts {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
};

//! Appends `part` to `into`, shifting its vertex indices (no vertex is shared).
void append(MeshParts& into, const MeshParts& part);

//! The boundary of the union of the cells (i, j, k) of the rectilinear grid xs × ys × zs (strictly
//! increasing coordinates) for which filled(i, j, k) holds: every cell face whose neighbour is empty
//! or outside, as two triangles, outward. Only grid points on the boundary become vertices.
//! \pre no two filled cells touch only along an edge or at a corner (the result would not be manifold).
MeshParts grid_union_boundary(const std::vector<double>& xs, const std::vector<double>& ys,
                              const std::vector<double>& zs, const std::function<bool(int, int, int)>& filled);

//! The surface swept by the profile polyline (r, z), rotated about the z axis in `segments` steps.
//! The profile starts and ends on the axis (r = 0, the two poles) and has r > 0 in between; it runs
//! counterclockwise in the (r, z) half-plane around the solid it bounds (e.g. from the bottom pole
//! outward and up), which makes the normals point outward.
MeshParts revolve_profile(const std::vector<std::array<double, 2>>& profile, int segments);

//! The unit sphere as an icosahedron whose edges are split into `frequency` segments, every lattice
//! point projected radially onto the sphere: 10·n² + 2 vertices, 20·n² triangles, outward.
MeshParts unit_icosphere(int frequency);

//! A tube of the given radius around a closed curve: ring i is the circle around centers[i] in the
//! plane spanned by the unit vectors normals[i] and binormals[i] (with tangent = normals × binormals
//! pointing along increasing i). Quads are split along the shorter diagonal. A torus: χ = 0.
MeshParts closed_tube(const std::vector<Vec3>& centers, const std::vector<Vec3>& normals,
                      const std::vector<Vec3>& binormals, double radius, int ring_segments);

//! The closed surface of the prism over a polygon strip in the xy-plane, from z0 to z1 in
//! `layers` steps. The strip is two polylines of equal length, `left` and `right`, joined at both
//! ends; walking along `right` the strip lies on the left (so right[0], right[1], left[1], left[0]
//! is counterclockwise). Each cap is the strip's quads, two triangles each.
MeshParts extrude_strip(const std::vector<std::array<double, 2>>& left, const std::vector<std::array<double, 2>>& right,
                        double z0, double z1, int layers);

}  // namespace lrvd::stress
