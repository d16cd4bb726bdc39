// Why a mesh file is unreadable: a line scanner that names the first offending line of an OFF,
// OBJ, PLY or STL file that CGAL's reader refused (CGAL only says "false"), and the coordinate
// check CGAL's binary STL reader lacks. Used by mesh_io.cpp for its messages; never reads data.
#pragma once

#include <string>

namespace lrvd {

enum class MeshFileFormat { Off, Obj, Ply, Stl };

//! The extension of `path` in lower case, with its dot (".off"), or "" when there is none.
std::string lowercase_extension(const std::string& path);

//! One-line reason, without the path, why CGAL could not read `path` as `format`
//! (e.g. "is truncated: the header declares 8 vertices and 6 faces, but the file ends after 5
//! vertices"). Never empty: falls back to a generic "cannot be parsed as ..." line.
std::string diagnose_unreadable_mesh_file(const std::string& path, MeshFileFormat format);

//! For an OFF or OBJ file CGAL did read: the first line its reader took other than written (a
//! face index '3.7' read as 3, a word after a face's indices), as diagnose_unreadable_mesh_file
//! words it; "" when the line scanner finds nothing (and for PLY and STL, which it does not scan).
std::string find_misread_line(const std::string& path, MeshFileFormat format);

//! For a PLY file whose vertices lack an x, y or z property (CGAL then reads zeros): "its vertex
//! element has no x, y, z properties (it has: a, b, c)"; "" otherwise.
std::string find_missing_ply_coordinates(const std::string& path);

//! For a binary STL file: "facet f has a non-finite coordinate (x, y, z)" for the first facet
//! with a NaN or infinite corner; "" when there is none or the file is not binary STL.
//! (CGAL welds STL corners through a std::map, where NaN compares equal to anything.)
std::string find_non_finite_binary_stl_coordinate(const std::string& path);

}  // namespace lrvd
