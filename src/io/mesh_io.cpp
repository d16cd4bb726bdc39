// Mesh IO: CGAL's readers into a polygon soup, checks with messages naming the first offender,
// exact ear-clipping triangulation, and read_mesh, which runs the repair steps of mesh_repair.cpp
// when asked and the refusals of open seams of mesh_seams.cpp (writers: mesh_writers.cpp). With mesh_repair.cpp, the only translation units that
// include CGAL's IO and repair headers.
#include "io/mesh_io.h"

#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "common/error.h"
#include "common/text.h"
#include "io/mesh_file_diagnosis.h"
#include "io/mesh_file_layout.h"
#include "io/mesh_repair.h"
#include "io/mesh_seams.h"
#include "mesh/weld.h"

namespace lrvd {

using namespace mesh_io_detail;

const std::vector<std::string> kMeshReadExtensions = {".off", ".obj", ".ply", ".stl"};

[[noreturn]] void mesh_io_detail::fail(const std::string& path, const std::string& reason) {
  throw InputError(path + ": " + reason);
}

namespace {


using Format = MeshFileFormat;


Format input_format(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  if (ext == ".off") return Format::Off;
  if (ext == ".obj") return Format::Obj;
  if (ext == ".ply") return Format::Ply;
  if (ext == ".stl") return Format::Stl;
  fail(path, ext.empty() ? "has no extension; expected .off, .obj, .ply or .stl"
                         : fmt::format("unknown extension '{}'; expected .off, .obj, .ply or .stl", ext));
}

void check_readable(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) fail(path, "no such file");
  if (fs::is_directory(status)) fail(path, "is a directory, not a mesh file");
  // Before opening it: a pipe blocks the opening until a writer comes.
  if (std::string problem = special_file_problem(path); !problem.empty()) fail(path, problem);
  if (!std::ifstream(path, std::ios::binary)) fail(path, "cannot be opened for reading (check its permissions)");
  if (fs::file_size(path, ec) == 0) fail(path, "is empty");
}

// ---------------------------------------------------------------------------------------------
// Reading, checking and triangulating the soup.

// One face element's items, with indices of type Index under `tag`; false when the element has no
// such list (and `read` tells whether reading them went well).
template <class Index>
bool read_ply_faces(std::istream& in, CGAL::IO::internal::PLY_element& element, const char* tag,
                    std::vector<Polygon>& polygons, bool& read, std::vector<CGAL::IO::Color>* colors) {
  if (!element.has_property<std::vector<Index>>(tag)) return false;
  read = colors ? CGAL::IO::internal::read_PLY_faces<Index>(in, element, polygons, std::back_inserter(*colors), tag)
                : CGAL::IO::internal::read_PLY_faces<Index>(in, element, polygons, CGAL::Emptyset_iterator(), tag);
  return true;
}

// The value of the scalar property `name` of the item `element` holds now, of any PLY type, as a
// double (CGAL's point reader takes float and double only, and calls through a null pointer on an
// integer coordinate); 0 when there is no such property (find_missing_ply_coordinates refuses that).
template <class Type>
bool ply_number_as(const CGAL::IO::internal::PLY_read_number* property, double& value) {
  const auto* typed = dynamic_cast<const CGAL::IO::internal::PLY_read_typed_number<Type>*>(property);
  if (typed) value = static_cast<double>(typed->buffer());
  return typed != nullptr;
}

template <class... Types>
double ply_number_of(const CGAL::IO::internal::PLY_read_number* property) {
  double value = 0;
  (ply_number_as<Types>(property, value) || ...);
  return value;
}

double ply_number(CGAL::IO::internal::PLY_element& element, const char* name) {
  for (std::size_t k = 0; k < element.number_of_properties(); ++k)
    if (element.property(k)->name() == name)
      return ply_number_of<std::int8_t, std::uint8_t, std::int16_t, std::uint16_t, std::int32_t, std::uint32_t, float,
                           double>(element.property(k));
  return 0;
}

// CGAL's read_PLY (5.5), reading face indices of every integer type PLY has: CGAL's own takes
// int and uint only, and refused the char, uchar, short and ushort that some writers use; and vertex
// coordinates of every scalar type (ply_number). With `colors`, also the faces' uchar red, green,
// blue (none when the faces have no such properties).
bool read_ply(const std::string& path, std::vector<Point>& points, std::vector<Polygon>& polygons,
              std::vector<CGAL::IO::Color>* colors = nullptr) {
  namespace ply = CGAL::IO::internal;
  std::ifstream in(path, std::ios::binary);
  CGAL::IO::set_mode(in, CGAL::IO::BINARY);
  ply::PLY_reader reader(false);
  if (!in || !reader.init(in)) return false;
  for (std::size_t i = 0; i < reader.number_of_elements(); ++i) {
    ply::PLY_element& element = reader.element(i);
    const bool vertices = element.name() == "vertex" || element.name() == "vertices";
    if (element.name() == "face" || element.name() == "faces") {
      bool read = false, found = false;
      for (const char* tag : {"vertex_indices", "vertex_index"}) {
        found = found || read_ply_faces<std::int32_t>(in, element, tag, polygons, read, colors) ||
                read_ply_faces<std::uint32_t>(in, element, tag, polygons, read, colors);
      }
      for (const char* tag : {"vertex_indices", "vertex_index"}) {
        found = found || read_ply_faces<std::int8_t>(in, element, tag, polygons, read, colors) ||
                read_ply_faces<std::uint8_t>(in, element, tag, polygons, read, colors) ||
                read_ply_faces<std::int16_t>(in, element, tag, polygons, read, colors) ||
                read_ply_faces<std::uint16_t>(in, element, tag, polygons, read, colors);
      }
      if (!found) return false;
      continue;  // CGAL goes on after a face element that failed: the stream's state says it
    }
    for (std::size_t j = 0; j < element.number_of_items(); ++j) {
      for (std::size_t k = 0; k < element.number_of_properties(); ++k) {
        element.property(k)->get(in);
        if (in.fail()) return false;
      }
      if (vertices) points.push_back(Point(ply_number(element, "x"), ply_number(element, "y"), ply_number(element, "z")));
    }
  }
  return !in.fail();
}

bool read_soup(const std::string& path, Format format, std::vector<Point>& points, std::vector<Polygon>& polygons) {
  // CGAL's readers print their own complaints to std::cerr; lrvd gives one line of its own
  // (diagnose_mesh_file), so theirs are dropped while they read.
  struct QuietCerr {
    std::streambuf* saved = std::cerr.rdbuf(nullptr);
    ~QuietCerr() { std::cerr.rdbuf(saved); }
  } quiet;
  try {
    switch (format) {
      case Format::Off:
        return CGAL::IO::read_OFF(path, points, polygons);
      case Format::Obj:
        return CGAL::IO::read_OBJ(path, points, polygons);
      case Format::Ply:
        return read_ply(path, points, polygons);
      case Format::Stl:
        return CGAL::IO::read_STL(path, points, polygons);
    }
  } catch (const std::exception&) {
  }
  return false;
}

// What CGAL accepted but lrvd cannot use: no faces, non-finite coordinates, short faces, and
// out-of-range indices (CGAL's PLY reader does not check them; its OBJ reader lets index n pass).
void check_soup(const std::string& path, Format format, const std::vector<Point>& points,
                const std::vector<Polygon>& polygons, bool allow_no_faces = false) {
  // A face CGAL read short or out of range often comes from a line it misread (a binary OFF, an
  // OBJ index 0 or a letter, header counts that do not match): the line scanner names that line
  // when it can, with what is wrong there.
  auto fail_face = [&](const std::string& reason) {
    const std::string scanned = diagnose_unreadable_mesh_file(path, format);
    fail(path, scanned.rfind("cannot be parsed", 0) == 0 ? reason : scanned);
  };
  if (polygons.empty() && !(allow_no_faces && !points.empty() && format != Format::Stl)) {
    // An STL file is made of facets only: corners without one are a facet cut short.
    if (format == Format::Stl && !points.empty()) fail(path, "has no complete facet (is the file truncated?)");
    fail(path, points.empty() ? "has no vertices and no faces"
                              : fmt::format("has {} vertices but no faces (a point cloud?)", points.size()));
  }
  for (std::size_t v = 0; v < points.size(); ++v) {
    const Point& p = points[v];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      fail(path, fmt::format("vertex {} has a non-finite coordinate ({}, {}, {})", v, p.x(), p.y(), p.z()));
  }
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    if (polygons[f].size() < 3)
      fail_face(fmt::format("face {} has only {} vertices; a face needs at least 3", f, polygons[f].size()));
    for (std::size_t index : polygons[f])
      if (index >= points.size())
        fail_face(fmt::format("face {} has vertex index {} out of range [0, {}){}", f,
                               static_cast<std::ptrdiff_t>(index), points.size(),
                               format == Format::Obj ? fmt::format(" (index {} in the file, which counts from 1)",
                                                                   static_cast<std::ptrdiff_t>(index) + 1)
                                                     : std::string()));
  }
}

// Ear clipping in the coordinate plane most orthogonal to the polygon's Newell normal. The
// projection only drops a coordinate, so CGAL's exact 2D orientation decides convexity and
// containment exactly. Returns false when no ear exists (self-intersecting or degenerate
// polygon); the remainder is then fanned and the validation reports what is wrong with it.
bool triangulate_polygon(const std::vector<Point>& points, const Polygon& polygon, std::vector<SoupTriangle>& out) {
  const std::size_t n = polygon.size();
  double normal[3] = {0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    const Point& a = points[polygon[i]];
    const Point& b = points[polygon[(i + 1) % n]];
    normal[0] += (a.y() - b.y()) * (a.z() + b.z());
    normal[1] += (a.z() - b.z()) * (a.x() + b.x());
    normal[2] += (a.x() - b.x()) * (a.y() + b.y());
  }
  int axis = 0;
  for (int c = 1; c < 3; ++c)
    if (std::abs(normal[c]) > std::abs(normal[axis])) axis = c;
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  const CGAL::Orientation convex = normal[axis] >= 0 ? CGAL::LEFT_TURN : CGAL::RIGHT_TURN;
  const CGAL::Orientation reflex = CGAL::opposite(convex);
  std::vector<Kernel::Point_2> q(n);
  for (std::size_t i = 0; i < n; ++i) q[i] = Kernel::Point_2(points[polygon[i]][u], points[polygon[i]][w]);
  const auto orient = [&](std::size_t a, std::size_t b, std::size_t c) { return CGAL::orientation(q[a], q[b], q[c]); };

  // The remaining polygon as a doubly linked ring over local positions.
  std::vector<std::size_t> next(n), prev(n);
  for (std::size_t i = 0; i < n; ++i) next[i] = (i + 1) % n, prev[i] = (i + n - 1) % n;
  std::size_t remaining = n, b = 0, misses = 0;
  while (remaining > 3 && misses < remaining) {
    const std::size_t a = prev[b], c = next[b];
    bool ear = orient(a, b, c) == convex;
    for (std::size_t r = next[c]; ear && r != a; r = next[r]) {
      if (q[r] == q[a] || q[r] == q[b] || q[r] == q[c]) continue;
      if (orient(a, b, r) != reflex && orient(b, c, r) != reflex && orient(c, a, r) != reflex) ear = false;
    }
    if (ear) {
      out.push_back({polygon[a], polygon[b], polygon[c]});
      next[a] = c, prev[c] = a;
      --remaining;
      b = a, misses = 0;
    } else {
      b = c, ++misses;
    }
  }
  const bool clipped = remaining == 3;
  for (std::size_t r = next[b]; next[r] != b; r = next[r]) out.push_back({polygon[b], polygon[r], polygon[next[r]]});
  return clipped;
}

}  // namespace

// `strict` (a read without --repair): a polygon that visits a vertex twice, or that no
// triangulation covers without overlap (a quad crossed into a bow tie), is refused; with --repair
// it is fanned, and a note says so.
// With `face_of`, the polygon each triangle comes from.
std::vector<SoupTriangle> mesh_io_detail::triangulate(const std::string& path, const std::vector<Point>& points,
                                                      const std::vector<Polygon>& polygons, RepairReport& report,
                                                      bool strict, std::vector<std::size_t>* face_of) {
  std::vector<SoupTriangle> triangles;
  triangles.reserve(polygons.size());
  std::vector<std::size_t> corners;
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    if (face_of) face_of->resize(triangles.size(), f - 1);  // the triangles of the polygon before
    const Polygon& polygon = polygons[f];
    if (polygon.size() == 3) {
      triangles.push_back({polygon[0], polygon[1], polygon[2]});
      continue;
    }
    ++report.triangulated_faces;
    if (strict) {
      corners.assign(polygon.begin(), polygon.end());
      std::sort(corners.begin(), corners.end());
      if (const auto twice = std::adjacent_find(corners.begin(), corners.end()); twice != corners.end())
        fail(path, fmt::format("face {} ({} vertices) visits vertex {} twice: its triangles would overlap; fix the face, "
                               "or rerun with --repair to fan it",
                               f, polygon.size(), *twice));
    }
    if (!triangulate_polygon(points, polygon, triangles)) {
      if (strict)
        fail(path, fmt::format("face {} ({} vertices) is self-intersecting or degenerate: no triangulation of it "
                               "lies inside it; fix the face, or rerun with --repair to fan it",
                               f, polygon.size()));
      report.notes.push_back(
          fmt::format("face {} ({} vertices) is self-intersecting or degenerate; it was fanned", f, polygon.size()));
    }
  }
  if (face_of) face_of->resize(triangles.size(), polygons.size() - 1);
  return triangles;
}

namespace {

// Drops vertices no triangle uses; `original` maps new indices to the old ones.
int drop_unreferenced(std::vector<Vec3>& positions, std::vector<Triangle>& triangles, std::vector<int>& original) {
  std::vector<int> new_index(positions.size(), -1);
  for (const Triangle& t : triangles)
    for (int v : t) new_index[v] = 0;
  original.clear();
  for (std::size_t v = 0; v < positions.size(); ++v)
    if (new_index[v] == 0) {
      new_index[v] = static_cast<int>(original.size());
      positions[original.size()] = positions[v];
      original.push_back(static_cast<int>(v));
    }
  const int dropped = static_cast<int>(positions.size() - original.size());
  positions.resize(original.size());
  for (Triangle& t : triangles)
    for (int& v : t) v = new_index[v];
  return dropped;
}

SurfaceMesh validated_mesh(const std::string& path, std::vector<Vec3> positions, std::vector<Triangle> triangles,
                           const std::string& numbering_note, bool repaired) {
  try {
    return SurfaceMesh(std::move(positions), std::move(triangles));
  } catch (const InputError& e) {
    const std::string what = e.what();
    const bool repairable = what.find("not manifold") != std::string::npos ||
                            what.find("inconsistent orientation") != std::string::npos ||
                            what.find("degenerate") != std::string::npos ||
                            what.find("zero area") != std::string::npos || what.find("duplicates") != std::string::npos;
    if (repaired) fail(path, "is still invalid after --repair: " + what + numbering_note);
    fail(path, what + numbering_note + (repairable ? "; --repair may fix it" : ""));
  }
}

}  // namespace

namespace {

// An OBJ of `v` lines and no face (what lrvd writes for a remesh without triangles), which CGAL's
// reader refuses: its vertices, or false when the file has a face or a line it cannot read so.
bool read_obj_vertices_only(const std::string& path, std::vector<Point>& points) {
  std::ifstream in(path);
  std::vector<Point> read;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string tag;
    if (!(fields >> tag) || tag[0] == '#') continue;
    if (tag == "f") return false;
    if (tag != "v") continue;
    double x = 0, y = 0, z = 0;
    if (!(fields >> x >> y >> z)) return false;
    read.emplace_back(x, y, z);
  }
  if (read.empty()) return false;
  points = std::move(read);
  return true;
}

// The file's points and polygons, parsed and checked (finite, indices in range, faces present).
void read_checked_soup(const std::string& path, std::vector<Point>& points, std::vector<Polygon>& polygons,
                       bool allow_no_faces = false) {
  check_readable(path);
  const Format format = input_format(path);
  if (format == Format::Stl)  // before CGAL, whose STL reader would weld a NaN corner into another
    if (std::string problem = find_non_finite_binary_stl_coordinate(path); !problem.empty()) fail(path, problem);
  if (format == Format::Ply)  // CGAL reads a PLY without coordinates as points at the origin
    if (std::string problem = find_missing_ply_coordinates(path); !problem.empty()) fail(path, problem);
  // Counts the file cannot hold, before CGAL allocates for them; content after the last element.
  if (std::string problem = find_layout_problem(path, format); !problem.empty()) fail(path, problem);
  // CGAL's OFF reader allocates each face's declared vertex count before reading its indices, so
  // the line scan (which catches what CGAL reads wrong: '3.7' as the index 3, words after a face's
  // indices) runs first; its message is the one a refusal by CGAL would get.
  if (format == Format::Off)
    if (!find_misread_line(path, format).empty()) fail(path, diagnose_unreadable_mesh_file(path, format));
  if (!read_soup(path, format, points, polygons) &&
      !(allow_no_faces && format == Format::Obj && read_obj_vertices_only(path, points)))
    fail(path, diagnose_unreadable_mesh_file(path, format));
  if (format == Format::Stl)  // CGAL stops after the declared facets and ignores what follows
    if (std::string problem = find_extra_binary_stl_facets(path, polygons.size()); !problem.empty())
      fail(path, problem);
  check_soup(path, format, points, polygons, allow_no_faces);
  // The same scan for OBJ (a file of vertices alone, when allowed, has no face to misread, and the
  // scan would call it a point cloud).
  if (allow_no_faces && polygons.empty()) return;
  if (format == Format::Obj)
    if (std::string problem = find_misread_line(path, format); !problem.empty()) fail(path, problem);
}

}  // namespace

PolygonSoup read_polygon_soup(const std::string& path, bool allow_no_faces, bool face_colors) {
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  read_checked_soup(path, points, polygons, allow_no_faces);
  // A PLY's face colours (lrvd compute's cells), read again from the file checked above.
  std::vector<CGAL::IO::Color> colors;
  if (face_colors && input_format(path) == Format::Ply) {
    std::vector<Point> again;
    std::vector<Polygon> faces;
    if (!read_ply(path, again, faces, &colors) || faces.size() != polygons.size() || colors.size() != polygons.size())
      colors.clear();
  }
  RepairReport ignored;
  PolygonSoup soup;
  std::vector<std::size_t> face_of;
  for (const SoupTriangle& t : triangulate(path, points, polygons, ignored, false, &face_of))
    soup.triangles.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
  if (!colors.empty())
    for (std::size_t f : face_of) soup.face_color.push_back({colors[f].red(), colors[f].green(), colors[f].blue()});
  for (const Point& p : points) soup.positions.push_back({p.x(), p.y(), p.z()});
  return soup;
}

LoadedMesh read_mesh(const std::string& path, const ReadOptions& options) {
  if (!(options.weld >= 0) || !std::isfinite(options.weld) || !(options.fill_holes >= 0))
    throw InputError(fmt::format("read options: weld ({}) and fill_holes ({}) are fractions of the bounding-box "
                                 "diagonal, 0 or more (0: off)",
                                 options.weld, options.fill_holes));
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  read_checked_soup(path, points, polygons);

  LoadedMesh loaded;
  RepairReport& report = loaded.repair;
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::vector<char> reversed;
  std::string weld_damage;
  if (options.repair) {
    RepairedSoup repaired = repair_soup(path, std::move(points), std::move(polygons), options.weld, report);
    positions = std::move(repaired.positions);
    triangles = std::move(repaired.triangles);
    reversed = std::move(repaired.reversed);
    weld_damage = std::move(repaired.weld_damage);
  } else {
    for (const SoupTriangle& t : triangulate(path, points, polygons, report, true))
      triangles.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
    positions.reserve(points.size());
    for (const Point& p : points) positions.push_back({p.x(), p.y(), p.z()});
  }
  std::vector<int> original;
  report.removed_unreferenced_vertices = drop_unreferenced(positions, triangles, original);

  // SurfaceMesh's messages count triangles and vertices after these changes: say so.
  std::string numbering_note;
  if (!options.repair && report.triangulated_faces > 0)
    numbering_note = fmt::format("triangulating {} polygons", report.triangulated_faces);
  if (!options.repair && report.removed_unreferenced_vertices > 0)
    numbering_note += fmt::format("{}dropping {} unreferenced vertices", numbering_note.empty() ? "" : " and ",
                                  report.removed_unreferenced_vertices);
  if (!numbering_note.empty()) numbering_note = " (numbering after " + numbering_note + ")";
  try {
    refuse_triangle_soup(path, positions, triangles, original, options.repair, options.repair ? options.weld : 0.0,
                         weld_damage);
    loaded.mesh = validated_mesh(path, std::move(positions), std::move(triangles), numbering_note, options.repair);
    // A crack is a boundary: a closed mesh has none to look for.
    if (!loaded.mesh.is_closed())
      refuse_t_junctions(path, loaded.mesh, original, options.repair);
  } catch (const InputError& e) {
    if (weld_damage.empty() || std::string(e.what()).find(weld_damage) != std::string::npos) throw;
    const std::string reason = e.what();
    throw InputError(fmt::format("{}: {}, and the welded mesh is refused: {}", path, weld_damage,
                                 reason.substr(std::min(reason.size(), path.size() + 2))));
  }
  if (options.repair) {
    choose_component_orientation(loaded.mesh, reversed, report);
    if (report.changed() && !loaded.mesh.is_closed()) {
      const std::size_t loops = loaded.mesh.boundary_loops().size();
      report.notes.push_back(fmt::format("the repaired mesh has {} boundary loop{}", loops, loops == 1 ? "" : "s"));
    }
  }
  if (options.fill_holes > 0) {
    try {
      loaded.mesh = fill_small_holes(loaded.mesh, options.fill_holes * loaded.mesh.bounding_box().diagonal(), &report);
    } catch (const InputError& e) {
      fail(path, e.what());
    }
  }
  return loaded;
}

}  // namespace lrvd
