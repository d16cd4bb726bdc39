// Mesh files out: OFF / OBJ (ascii, %.17g so doubles round-trip) and binary PLY, the Voronoi-cell
// polygons with a cell label and colour per face, and any text file, each written whole or not at all.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/surface_mesh.h"
#include "predicates/vec3.h"

namespace lrvd {

//! The extensions write_mesh writes (lower case, with the dot).
extern const std::vector<std::string> kMeshWriteExtensions;

//! Writes a triangle mesh as OFF, OBJ (ascii, %.17g so doubles round-trip exactly) or PLY
//! (binary little-endian, double coordinates), chosen by the extension.
//! \throw InputError on an unknown extension or a path that cannot be opened for writing; WriteError
//!        when the write or the replacement fails (a full disk);
//!        std::invalid_argument when a triangle index is out of range or a coordinate is not finite
//!        (nothing is written then).
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
