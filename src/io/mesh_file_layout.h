// What a mesh file's header promises against what its bytes can hold, checked before CGAL reads it:
// CGAL's OFF reader sizes its vectors from the header's counts (a 20-byte file declaring 1e9 faces
// took 23 GB), its PLY reader sizes a list from the list's own count, and neither PLY nor binary STL
// looks past the last declared element. Used by mesh_io.cpp; never reads data.
#pragma once

#include <cstddef>
#include <string>

#include "io/mesh_file_diagnosis.h"

namespace lrvd {

//! Before CGAL reads `path` as `format`: a header whose counts the file's size cannot hold (at the
//! fewest bytes an element takes: ascii 6 a vertex, 8 a triangle; binary PLY and OFF their exact
//! sizes), a PLY or binary OFF list longer than the bytes left, a PLY with content after its last
//! declared element, a file too short to be an STL; "" when none (also when the file is merely
//! truncated: the diagnosis names that after CGAL refuses it).
std::string find_layout_problem(const std::string& path, MeshFileFormat format);

//! After CGAL read `facets_read` facets from the STL file `path`: when it is a binary STL of that
//! many facets followed by bytes for one more whole facet or more, the reason; "" otherwise
//! (fewer trailing bytes are tolerated as padding).
std::string find_extra_binary_stl_facets(const std::string& path, std::size_t facets_read);

}  // namespace lrvd
