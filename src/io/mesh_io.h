// Mesh files in and out: reading OFF/OBJ/PLY/STL through CGAL's IO into a validated SurfaceMesh
// (with optional CGAL polygon-soup repair), and writing meshes and Voronoi-cell polygons.
// What is checked, the error messages and what repair does: docs/guide/input.md.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/surface_mesh.h"

namespace lrvd {

struct ReadOptions {
  bool repair = false;  //!< weld, clean, orient and stitch the polygon soup (CGAL PMP) before validation
  //! If > 0: after validation (and repair), fill every hole whose boundary loop is at most this
  //! fraction of the bounding-box diagonal long (fill_small_holes).
  double fill_holes = 0;
  //! If > 0 (with repair): first weld every vertex to an earlier one closer than this fraction of
  //! the bounding-box diagonal (weld_representatives: no chains; the earlier vertex's position).
  double weld = 0;
};

//! What reading changed between the file and the returned mesh. Indices in the notes are 0-based.
struct RepairReport {
  int welded_vertices = 0;                  //!< vertices welded into an earlier one within ReadOptions::weld
  int weld_collapsed_sides = 0;             //!< face sides of the file whose two ends that weld joined
  int merged_vertices = 0;                  //!< vertices welded into an earlier one with identical coordinates
  int removed_degenerate_faces = 0;         //!< zero-area faces (exact test) and faces repeating a vertex
  int removed_duplicate_faces = 0;          //!< faces on the same vertices as an earlier face, any orientation
  int removed_internal_faces = 0;           //!< faces of walls between two solids, listed once each way (both copies)
  int removed_unreferenced_vertices = 0;    //!< vertices no face uses (dropped even without repair)
  int reoriented_faces = 0;                 //!< faces reversed to orient their component consistently
  int duplicated_nonmanifold_vertices = 0;  //!< vertices copied to cut non-manifold edges / vertices apart
  int stitched_edges = 0;                   //!< pairs of coincident boundary edges glued together
  int split_edges = 0;                      //!< boundary edges split at corners of other faces lying on them (T-junctions)
  int triangulated_faces = 0;               //!< polygons with more than 3 vertices split into triangles
  int filled_holes = 0;                     //!< boundary loops closed with triangles (ReadOptions::fill_holes)
  std::vector<std::string> notes;           //!< one human-readable line per change worth knowing
  bool soup_changed() const;  //!< any count but filled_holes (what --repair did)
  bool changed() const;       //!< any count
};

struct LoadedMesh {
  SurfaceMesh mesh;
  RepairReport repair;
};

//! Reads OFF, OBJ, PLY (ascii or binary) or STL (ascii or binary), chosen by the extension
//! (any letter case). Polygons are triangulated (ear clipping with exact orientation tests);
//! unreferenced vertices are dropped. With options.repair the soup is welded, cleaned, oriented
//! and stitched first (see docs/guide/input.md).
//! \throw InputError "<path>: <reason>" for a missing/unreadable file, an unknown extension, an
//!        empty, truncated or unparsable file, non-finite coordinates, out-of-range indices, an
//!        unwelded triangle soup (suggests --repair), boundary corners within 1e-6 of the bounding-box
//!        diagonal of each other but not at one point (suggests --repair --weld), a boundary corner
//!        within that distance of another face's boundary edge (a crack; suggests --repair), and every
//!        SurfaceMesh precondition.
LoadedMesh read_mesh(const std::string& path, const ReadOptions& options = {});

//! The mesh with every hole whose boundary loop is at most `max_length` long (the sum of its edge
//! lengths) closed by triangles between the loop's own vertices (CGAL's triangulate_hole with its
//! defaults: no new vertices; Liepa's weights, the worst dihedral angle first, then the area). A
//! remesh keeps every hole of its input, and one much smaller than the cells needs many rounds and
//! vertices there, or fails: scans and CAD exports often have such holes by mistake. Left open, with
//! a note each: longer loops; the whole outline of a component without inner vertices; a loop CGAL
//! finds no triangulation for; a patch with a degenerate triangle, or one that cuts the mesh, itself
//! or another patch (exact tests; vertices at the same point count as shared). The triangles are
//! appended after the mesh's own; the notes and the count go to `report` when given.
//! \throw InputError when the model is too large or small for the tests (require_workable_size), or
//!        when the result is not a valid mesh.
SurfaceMesh fill_small_holes(const SurfaceMesh& mesh, double max_length, RepairReport* report = nullptr);

//! Positions and triangles exactly as a file holds them (polygons triangulated), without the
//! manifold validation: for measuring other tools' output, which may be non-manifold.
//! \throw InputError for a missing, unknown, empty, truncated or unparsable file, non-finite
//!        coordinates or out-of-range indices.
struct PolygonSoup {
  std::vector<Vec3> positions;
  std::vector<std::array<int, 3>> triangles;
  //! With `face_colors`, per triangle, its face's colour in a PLY whose faces have uchar red,
  //! green, blue (such as lrvd compute's cells); else, and for other files, empty.
  std::vector<std::array<unsigned char, 3>> face_color;
};
//! With `allow_no_faces`, vertices without a face are read too (a remesh at its topological minimum
//! can come out so; its checks then fail), except from STL, which has no vertices of its own. With
//! `face_colors`, a PLY's face colours too (the file is parsed a second time for them).
PolygonSoup read_polygon_soup(const std::string& path, bool allow_no_faces = false, bool face_colors = false);

//! Writes a triangle mesh as OFF, OBJ (ascii, %.17g so doubles round-trip exactly) or PLY
//! (binary little-endian, double coordinates), chosen by the extension.
//! \throw InputError on an unknown extension or a path that cannot be opened for writing; WriteError
//!        when the write or the replacement fails (a full disk);
//!        std::invalid_argument when a triangle index is out of range or a coordinate is not finite
//!        (nothing is written then).
//! The extensions read_mesh reads and write_mesh writes (lower case, with the dot).
extern const std::vector<std::string> kMeshReadExtensions, kMeshWriteExtensions;

void write_mesh(const std::string& path, const std::vector<Vec3>& positions,
                const std::vector<std::array<int, 3>>& triangles);
void write_mesh(const std::string& path, const SurfaceMesh& mesh);

//! Polygons with a cell label and a colour per face: the Voronoi cells clipped to the mesh.
struct PolygonMesh {
  std::vector<Vec3> positions;
  std::vector<std::vector<int>> faces;
  std::vector<int> face_cell;                            //!< empty, or one cell index per face
  std::vector<std::array<unsigned char, 3>> face_color;  //!< empty, or one colour per face
};

//! Writes binary little-endian PLY: vertex (double x, y, z); face (list uchar int vertex_indices,
//! int cell, uchar red, green, blue) — cell / colour properties only when given.
//! \throw InputError when the path cannot be opened for writing, WriteError when the write fails;
//!        std::invalid_argument when face_cell or face_color has neither 0 nor faces.size()
//!        entries, a face has more than 255 vertices or an index is out of range.
void write_cells_ply(const std::string& path, const PolygonMesh& mesh);

//! Writes `text` to `path` whole or not at all (as every writer here: into a file beside it that
//! replaces it when complete, with the permissions of the file it replaces; a device or a pipe is
//! written in place; through a symbolic link, the file the link leads to is replaced so, and the
//! link stays).
//! \throw InputError when the path cannot be opened for writing, WriteError when the write fails.
void write_text_file(const std::string& path, std::string_view text);

//! Installs handlers for SIGINT, SIGTERM and SIGHUP (unless the process ignores them) that remove
//! the part files being written, then end the process as the signal would have: an interrupted
//! write leaves the old file and nothing beside it. For programs (the CLI calls it first).
void remove_part_files_on_signals();

//! The file a writer replaces for `path`: `path` itself, or, when it is a symbolic link, the end
//! of its chain of links (at most 40; relative targets taken from their link's folder), whether
//! or not a file is there yet.
std::string written_file(const std::string& path);

}  // namespace lrvd
