// The repair steps of read_mesh (--repair, --weld: CGAL's polygon-soup repair, then the orientation
// of each component) and fill_small_holes (--fill-holes), in mesh_repair.cpp apart from the readers
// of mesh_io.cpp; the soup's types and the functions the two files share, private to io/.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "io/mesh_io.h"

namespace lrvd::mesh_io_detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Polygon = std::vector<std::size_t>;
using SoupTriangle = std::array<std::size_t, 3>;

//! Boundary corners closer than this fraction of the bounding-box diagonal, yet not at the same
//! point, are a seam written with rounding noise (docs/guide/input.md, "Near-coincident corners"): a
//! float's rounding at the model's size is about 6e-8 of it, a coordinate printed with six digits
//! about 1e-6 of its value. The reader refuses them; --repair splits the T-junctions they make.
constexpr double kNearTwinFraction = 1e-6;

//! \throw InputError "path: reason".
[[noreturn]] void fail(const std::string& path, const std::string& reason);

//! The polygons as triangles, each by exact ear clipping (mesh_io.cpp). `strict` (a read without
//! --repair): a polygon that visits a vertex twice, or that no triangulation covers without overlap,
//! is refused; otherwise it is fanned, and a note says so. With `face_of`, the polygon of each triangle.
std::vector<SoupTriangle> triangulate(const std::string& path, const std::vector<Point>& points,
                                      const std::vector<Polygon>& polygons, RepairReport& report, bool strict,
                                      std::vector<std::size_t>* face_of = nullptr);

struct RepairedSoup {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<char> reversed;  // per triangle: reversed by the orientation step
  std::string weld_damage;     // the file's edges --weld collapsed, or "": a likely cause if the read fails
};

//! --weld and --repair on the soup: points welded and merged, degenerate, duplicate and internal
//! faces removed, T-junctions split, the soup oriented and stitched into a mesh. \throw InputError
//! when nothing usable is left.
RepairedSoup repair_soup(const std::string& path, std::vector<Point> points, std::vector<Polygon> polygons,
                         double weld, RepairReport& report);

//! Each component's orientation chosen: a closed one bounds its volume outwards, an open one keeps
//! the orientation most of its faces have in the file; `reversed` and the report follow.
void choose_component_orientation(SurfaceMesh& mesh, std::vector<char>& reversed, RepairReport& report);

}  // namespace lrvd::mesh_io_detail
