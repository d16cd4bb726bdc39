// Verification of a maximal Poisson-disk sampling (paper §4.2): the minimum-distance property (no
// sample inside another sample's disk) and maximality (the disks cover the surface, checked cell
// by cell on an LRPD computed afresh), independently of the sampler's data structures.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "mesh/surface_mesh.h"
#include "verification/diagram_check.h"
#include "voronoi/diagram.h"
#include "voronoi/samples.h"

namespace lrvd {

struct MpsVerifyOptions {
  //! Decide every polygon vertex of the maximality check with rational arithmetic; otherwise only
  //! those whose double power distance lies within 1e-6·r² of zero (the rest by doubles).
  bool exact_maximality = false;
};

struct MpsVerification {
  bool passed = true;  //!< min_distance, maximal and diagram_covers all hold
  double time_s = 0;
  //! Local samples are at least max(r_i, r_j) apart (exact). Samples i and j are local to each
  //! other when each one's triangle lies in the local region of the other's ball of radius
  //! max(r_i, r_j): the triangles the ball meets that face like the centre's triangle (normals at
  //! less than 90°), edge-connected to it through such triangles.
  PropertyResult min_distance;
  //! Every polygon of cell i of the LRPD (weights r²) lies in the ball (x_i, r_i): all its vertices
  //! do, which suffices since the polygon is convex and the ball cut by its plane is a convex disk.
  PropertyResult maximal;
  //! The LRPD's polygons fill every triangle (area sums, relative 1e-9): the cells do cover the surface.
  PropertyResult diagram_covers;
  double min_distance_ratio = 0;           //!< smallest |x_i - x_j| / max(r_i, r_j) over pairs seen in a region, not one-sided
  std::int64_t close_pairs_not_local = 0;  //!< pairs closer than max(r_i, r_j) that are not local (other sheet, past a notch); allowed
  std::int64_t one_sided_close_pairs = 0;  //!< of those, pairs where one sees the other in its region but not back (a notch)
  std::int64_t exact_vertex_tests = 0;       //!< maximality decisions that needed rational arithmetic
  nlohmann::json to_json() const;
  std::string summary() const;
};

//! Checks the samples (weights = radius²) against an LRPD of them on `mesh` (the mesh their
//! triangles index). \throw InputError when the diagram is not an LRPD/RPD of these samples or a
//! sample has no weight.
MpsVerification verify_mps(const SurfaceMesh& mesh, const Samples& samples, const Diagram& lrpd,
                           const MpsVerifyOptions& options = {});

//! As above with an LRPD computed here.
MpsVerification verify_mps(const SurfaceMesh& mesh, const Samples& samples, const MpsVerifyOptions& options = {});

}  // namespace lrvd
