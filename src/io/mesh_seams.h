// The reader's refusals of open seams (docs/guide/input.md, "Triangle soups" and "Near-coincident
// corners"): a soup whose boundary corners coincide or nearly coincide without being shared, and a
// boundary corner on another face's boundary edge (a T-junction). Private to io/: read_mesh runs them.
#pragma once

#include <string>
#include <vector>

#include "mesh/surface_mesh.h"

namespace lrvd::mesh_io_detail {

//! An unwelded soup: two vertices on boundary edges at the same point (a seam that welding would
//! close), or two within kNearTwinFraction of the model's size (or twice a --weld given) that are
//! not at the same point and share no edge and no neighbour (a seam that --weld would close).
//! Closed meshes touching themselves at a point are not refused. After --repair (`repaired`) only
//! the near twins are looked for (the orientation step copies vertices at non-manifold points), and
//! the vertices named are the repaired mesh's; otherwise `original` maps them to the file's.
//! `weld_damage`, when not empty, is what --weld collapsed: named as the cause of the seams left.
//! \throw InputError "path: reason", with the --weld that would close the seams.
void refuse_triangle_soup(const std::string& path, const std::vector<Vec3>& positions,
                          const std::vector<Triangle>& triangles, const std::vector<int>& original, bool repaired,
                          double weld, const std::string& weld_damage);

//! A boundary corner on another face's boundary edge (a T-junction): the seam is open there, a
//! crack the remesh would keep. --repair splits such edges; after it, what is left is refused as well.
//! \throw InputError "path: reason".
void refuse_t_junctions(const std::string& path, const SurfaceMesh& mesh, const std::vector<int>& original,
                        bool repaired);

}  // namespace lrvd::mesh_io_detail
