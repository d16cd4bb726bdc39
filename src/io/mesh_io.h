// Mesh files in: reading OFF/OBJ/PLY/STL through CGAL's IO into a validated SurfaceMesh (with
// optional CGAL polygon-soup repair); the writers are in mesh_writers.h.
// What is checked, the error messages and what repair does: docs/guide/input.md.
#pragma once

#include <array>
#include <string>
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

//! The extensions read_mesh reads (lower case, with the dot).
extern const std::vector<std::string> kMeshReadExtensions;

}  // namespace lrvd
