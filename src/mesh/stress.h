// Stress meshes: deterministic generators of the inputs the LRVD paper is about (Yan et al. 2014,
// §1 and §5): nearby parallel sheets, thin walls, tight crossings, nearly touching parts, a
// self-intersecting surface (Fig. 11) and a long thin tube (Fig. 13). Every mesh is built from
// explicit formulas (no random numbers), so the same options give the same mesh on every run.
#pragma once

#include <string>
#include <vector>

#include "mesh/surface_mesh.h"
#include "predicates/vec3.h"

namespace lrvd {

//! Two nearby parallel sheets: the closed surface of a thin box size_x × size_y × thickness centred
//! at the origin, its top and bottom faces a regular grid of cells_x × cells_y squares (each split
//! into two triangles); the four side walls are one cell thick. χ = 2.
struct ThinPlateOptions {
  double size_x = 1.0;      //!< extent along x
  double size_y = 1.0;      //!< extent along y
  double thickness = 0.01;  //!< extent along z: far below the grid spacing (1/48)
  int cells_x = 48;         //!< grid cells along x (>= 1)
  int cells_y = 48;         //!< grid cells along y (>= 1)
};

//! A folded sheet: a closed U-shaped slab (two parallel walls joined by a half-round bend), i.e. a
//! sheet of the given thickness folded so that its two halves face each other across a narrow gap.
//! The U lies in the xy-plane (walls parallel to x, the bend at +x), extruded along z. χ = 2.
struct FoldedSheetOptions {
  double wall_length = 1.0;  //!< length of each straight wall (x from -wall_length/2 to +wall_length/2)
  double gap = 0.02;         //!< distance between the two walls' facing (inner) surfaces
  double thickness = 0.005;  //!< thickness of the sheet
  double width = 0.5;        //!< extent of the extrusion along z
  int wall_segments = 40;    //!< segments along each straight wall (>= 1)
  int bend_segments = 12;    //!< segments along the half-round bend (>= 2)
  int width_segments = 20;   //!< segments along the extrusion (>= 1)
};

//! A thin-walled cup as ONE closed surface: the boundary of a solid cup wall (bottom disk plus a
//! cylindrical wall, both of the given thickness) — the outer and inner surfaces are two sheets
//! `wall_thickness` apart, joined by a flat annulus at the rim. Axis z, opening at +z. χ = 2.
//! Built as a surface of revolution, so the triangles around the two poles (the bottom centres)
//! are fans of slivers.
struct OpenCupOptions {
  double radius = 0.5;           //!< radius of the wall's mid-surface
  double height = 1.0;           //!< outer height (bottom of the base to the rim)
  double wall_thickness = 0.01;  //!< thickness of both the wall and the bottom
  int angular_segments = 64;     //!< segments around the axis (>= 3)
  int bottom_segments = 12;      //!< rings across each of the two bottom disks (>= 1)
  int wall_segments = 24;        //!< segments along the height of each of the two walls (>= 1)
  int rim_segments = 1;          //!< segments across the rim annulus (>= 1)
};

//! The paper's flat ellipsoid ("Ellp."): an icosahedron whose edges are split into `subdivision`
//! segments (20·n² triangles; n = 2^k is k levels of 1-to-4 splitting), its vertices mapped onto
//! the unit sphere and from there onto the ellipsoid (x/a)² + (y/b)² + (z/c)² = 1. χ = 2.
struct FlatEllipsoidOptions {
  Vec3 semi_axes{1.0, 0.5, 0.05};  //!< a, b, c
  int subdivision = 24;            //!< segments per icosahedron edge (>= 1)
};

//! A trefoil-knot tube with tight crossings. Centre curve: scale·(sin t + 2 sin 2t,
//! cos t − 2 cos 2t, −sin 3t); tube radius = tube_radius_fraction × half the closest approach of
//! two different strands of the curve (computed numerically), so at the crossings the strands
//! nearly touch without intersecting. rings × ring_segments torus grid, quads split along the
//! shorter diagonal. χ = 0 (a torus).
struct KnotTubeOptions {
  double scale = 0.28;                //!< scale of the centre curve (the default fits in [-1, 1]^3)
  double tube_radius_fraction = 0.9;  //!< in (0, 1): 1 would make the crossing strands touch
  int rings = 240;                    //!< cross-sections along the curve (>= 3)
  int ring_segments = 24;             //!< segments around each cross-section (>= 3)
};

//! A comb of nearly touching fingers: a base block with `finger_count` long fingers standing on
//! it along +z, neighbouring fingers separated by a gap far smaller than their length. The closed
//! surface is the boundary of a union of cells of a rectilinear grid (each boundary square split
//! into two triangles), which is manifold because no two cells touch only along an edge. χ = 2.
struct CombOptions {
  int finger_count = 8;             //!< number of fingers (>= 1)
  double finger_width = 0.1;        //!< extent of a finger along x
  double finger_gap = 0.01;         //!< gap between neighbouring fingers along x
  double finger_length = 1.2;       //!< extent of a finger along z (above the base)
  double depth = 0.2;               //!< extent of base and fingers along y
  double base_height = 0.3;         //!< extent of the base along z
  int cells_per_finger_width = 4;   //!< grid cells across a finger (>= 1)
  int cells_per_gap = 1;            //!< grid cells across a gap (>= 1)
  int depth_cells = 6;              //!< grid cells along y (>= 1)
  int length_cells = 32;            //!< grid cells along a finger's length (>= 1)
  int base_height_cells = 8;        //!< grid cells along the base's height (>= 1)
};

//! Two closed spheres that interpenetrate, as one mesh of two components with no shared vertex:
//! each component is a valid closed manifold, their union intersects itself along a circle (the
//! paper's Fig. 11). Sphere b's vertex lattice is rotated against a's so no vertices coincide.
//! χ = 4, 2 components.
struct InterpenetratingSpheresOptions {
  Vec3 center_a{0.3, 0.0, 0.0};      //!< centre of the first sphere
  double radius_a = 0.6;             //!< radius of the first sphere
  Vec3 center_b{-0.35, 0.04, 0.02};  //!< centre of the second sphere
  double radius_b = 0.5;             //!< radius of the second sphere
  int subdivision = 16;              //!< segments per icosahedron edge of each sphere (>= 1)
};

//! A long thin tube (the paper's failure case, Fig. 13): a closed capsule along x — a cylinder
//! with hemispherical caps — of total length `length` and radius `radius`. χ = 2.
struct ThinTubeOptions {
  double length = 2.0;         //!< total length including both caps (> 2·radius)
  double radius = 0.03;        //!< tube radius
  int ring_segments = 16;      //!< segments around the tube (>= 3)
  int length_segments = 160;   //!< segments along the cylindrical part (>= 1)
  int cap_segments = 6;        //!< segments along each cap's quarter-circle profile (>= 1)
};

//! Each generator returns a validated SurfaceMesh, closed, consistently oriented with outward
//! normals (positive signed volume per component).
//! \throw InputError when an option is out of range (the message names the option and its value).
SurfaceMesh make_thin_plate(const ThinPlateOptions& options = {});
SurfaceMesh make_folded_sheet(const FoldedSheetOptions& options = {});
SurfaceMesh make_open_cup(const OpenCupOptions& options = {});
SurfaceMesh make_flat_ellipsoid(const FlatEllipsoidOptions& options = {});
SurfaceMesh make_knot_tube(const KnotTubeOptions& options = {});
SurfaceMesh make_comb(const CombOptions& options = {});
SurfaceMesh make_interpenetrating_spheres(const InterpenetratingSpheresOptions& options = {});
SurfaceMesh make_thin_tube(const ThinTubeOptions& options = {});

//! Closest approach of two different strands of the trefoil centre curve of make_knot_tube, for
//! scale 1: the smallest doubly-critical distance (≈ 1.2143). The tube radius is a fraction of half of it.
double trefoil_closest_approach();

//! What `lrvd stress --list` shows about one stress mesh.
struct StressMeshInfo {
  std::string name;          //!< the name make_stress_mesh accepts
  std::string description;   //!< one line: what the mesh is and what makes it hard
  bool closed;               //!< no boundary
  int euler_characteristic;  //!< V − E + F of the whole mesh
  int components;            //!< connected components
};

//! The stress meshes, in a fixed order.
std::vector<StressMeshInfo> stress_mesh_catalog();

//! The default instance of a catalogued stress mesh; resolution_scale multiplies every subdivision
//! count of its options (rounded, each kept at its minimum), leaving the geometry unchanged.
//! \throw InputError when the name is not in the catalog (the message lists the valid names) or
//!        resolution_scale is not a positive finite number.
SurfaceMesh make_stress_mesh(const std::string& name, double resolution_scale = 1.0);

}  // namespace lrvd
