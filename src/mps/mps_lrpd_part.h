// The LRPD of maximal Poisson-disk sampling on the part of the mesh around a few triangles, for the
// later gap rounds, which look only at the triangles that may still hold a gap.
#pragma once

#include <vector>

#include "diagram/diagram.h"
#include "mesh/surface_mesh.h"
#include "mps/mps_disks.h"

namespace lrvd::mps_detail {

//! An LRPD for gap detection: of the whole mesh, or of the part of it around some triangles
//! (compute_lrpd_around), whose triangles and cells map back to the mesh's triangles and samples.
struct GapLrpd {
  Diagram diagram;
  bool on_part = false;
  SurfaceMesh part;              //!< on_part: the triangles the diagram covers, as a mesh of their own
  std::vector<int> triangle_of;  //!< on_part: the mesh triangle of each part triangle
  std::vector<int> sample_of;    //!< on_part: the sample of each part cell
};

//! The LRPD of the samples located on the part of the mesh around `triangles`: every triangle a
//! ball of four times the largest radius reaching one of them meets (edge-connected to it),
//! and the whole star of each vertex where those would touch at a point only. The cells of a
//! maximal sampling are a few radii across, so on `triangles` the part's LRPD has the cells of the
//! whole mesh's unless a cell there grows from beyond the part's rim; either way its polygons
//! partition those triangles among cells of samples, which is all gap detection needs (the verifier
//! judges maximality on the whole mesh's LRPD). `shaped`, per mesh triangle: the triangles whose
//! polygons need shapes (LrvdOptions::shapeless). Returns false, leaving `out` alone, when the part
//! would hold more than a quarter of the mesh or a component of it holds no sample.
bool compute_lrpd_around(const SurfaceMesh& mesh, DiskIndex& disks, const std::vector<int>& triangles,
                         const std::vector<char>& shaped, GapLrpd& out);

}  // namespace lrvd::mps_detail
