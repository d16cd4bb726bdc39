// Verification of a maximal Poisson-disk sampling (paper §4.2): the minimum-distance property (no
// sample inside another sample's disk) and maximality (the disks cover the surface, checked on an
// LRPD computed afresh and on the samples' own disks), independently of the sampler's data structures.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "diagram/diagram.h"
#include "mesh/surface_mesh.h"
#include "samples/samples.h"
#include "verification/report.h"

namespace lrvd {

struct MpsVerifyOptions {
  //! Decide every polygon vertex of the maximality check with rational arithmetic; otherwise only
  //! those whose power distance's sign the interval enclosure of their position leaves open.
  bool exact_maximality = false;
  //! Judge by the facing cut (MpsConflict::CloseAcrossTurns: regions stop where the surface turns
  //! by 90° or more, and both samples must reach each other); false (the default): by the paper's
  //! rule (MpsConflict::Reach, the sampler's default).
  bool facing_cut = false;
};

struct MpsVerification {
  bool passed = true;  //!< min_distance, maximal and diagram_covers all hold
  double time_s = 0;  //!< the whole call: with the overload that computes the LRPD, that LRPD too
  //! Local samples are at least ρ = max(r_i, r_j) apart (exact). Samples i and j are local to each
  //! other when, with MpsVerifyOptions::facing_cut, each one's triangle lies in the
  //! local region of the other's ball of radius ρ: the triangles the ball meets that face like the
  //! centre's triangle (normals at less than 90°), edge-connected to it through such triangles.
  //! Without it (the paper's rule): the local region of one's ball holds a triangle of the other,
  //! the region being all the triangles the ball meets, edge-connected to the centre's.
  PropertyResult min_distance;
  //! Every point of the surface is covered (checked = triangles): it lies in the ball of the sample
  //! whose LRPD cell (weights r²) holds it, or in the disk of a sample whose local region reaches
  //! its triangle (that sample may be no LRPD candidate there). A triangle whose LRPD polygons all
  //! lie in their cells' balls (all corners: the polygon is convex, the ball cut by its plane a
  //! convex disk) is covered; any other is decided exactly on the power diagram of its LRPD cells
  //! and the samples whose disks reach it.
  PropertyResult maximal;
  //! The LRPD's polygons fill every triangle (area sums, relative 1e-9): the cells do cover the surface.
  PropertyResult diagram_covers;
  double min_distance_ratio = 0;           //!< smallest |x_i - x_j| / max(r_i, r_j) over pairs seen in a region, not one-sided;
                                           //!< NaN (null in JSON) when no such pair exists
  std::int64_t close_pairs_not_local = 0;  //!< pairs closer than max(r_i, r_j) that are not local (other sheet, past a notch); allowed
  std::int64_t one_sided_close_pairs = 0;  //!< close pairs where one's region reaches the other's triangle but not back (a notch)
  bool facing_cut = false;                 //!< judged by the facing cut (MpsVerifyOptions::facing_cut)
  //! With the facing cut: close pairs that the paper's rule calls local and the cut lets through
  //! (across sharp edges, round a thin sheet's rim).
  std::int64_t close_pairs_local_past_facing_cut = 0;
  std::int64_t exact_vertex_tests = 0;       //!< maximality decisions that needed rational arithmetic
  std::int64_t polygons_outside_own_ball = 0;  //!< LRPD polygons not inside their cell's ball
  //! Triangles holding such polygons that are covered all the same: by disks of samples that reach
  //! the triangle but are no LRPD candidate there.
  std::int64_t triangles_covered_by_other_disks = 0;
  //! Polygons of the maximality check outside their own ball that samples cover whose balls
  //! their spots' regions reach (the paper's rule read from the spot's side, a reach certificate).
  std::int64_t polygons_covered_from_spot_side = 0;
  std::int64_t polygons_of_remote_balls = 0;  //!< LRPD polygons in their cell's ball where that cell's disk does not reach
  nlohmann::json to_json() const;
  std::string summary() const;
};

//! Checks the samples (weights = radius²) against an LRPD of them on `mesh` (the mesh their
//! triangles index). \throw InputError when the diagram is not an LRPD/RPD of these samples or a
//! sample has no weight.
MpsVerification verify_mps(const SurfaceMesh& mesh, const Samples& samples, const Diagram& lrpd,
                           const MpsVerifyOptions& options = {});

//! As above with the LRPD that `compute_lrpd` returns, computed beside the checks that do not need
//! it (minimum distance, close pairs), on another thread when there is one; the results do not
//! depend on it. The checks build no diagram: the caller passes the builder (verify_mps of
//! report/mps_report.h passes compute_lrvd). The diagram goes to `*lrpd` when asked for (the LRRT
//! of the samples is its dual).
MpsVerification verify_mps(const SurfaceMesh& mesh, const Samples& samples, const std::function<Diagram()>& compute_lrpd,
                           const MpsVerifyOptions& options = {}, Diagram* lrpd = nullptr);

}  // namespace lrvd
