// Maximal Poisson-disk sampling on a triangle mesh (paper §4.2, after Yan & Wonka 2013): edge
// splitting (to twice the radius, or to r_min as the paper does), dart throwing with conflict
// checks through triangles (no 3D grid), gap detection with the localized restricted power diagram
// (LRPD, §2.4, §3.5) and gap filling until no gap is left; uniform or curvature-adaptive radius.
// Details and the conflict rule: docs/algorithms/mps.md.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "mesh/refine.h"
#include "mesh/surface_mesh.h"
#include "samples/samples.h"

namespace lrvd {

//! How the gaps are kept up to date while darts fill them.
enum class MpsGapUpdate {
  Local,  //!< LRPD once; every inserted disk re-clips the gap pieces of the triangles it reaches (exact, fast)
  Lrpd    //!< the paper's loop: darts into the gaps until too many rejections, then a new LRPD
};

//! What the mesh's edges are split to before sampling.
enum class MpsRefinement {
  RadiusField,  //!< every edge no longer than split_factor times the radius field at its ends
  MinRadius     //!< every edge no longer than r_min (the paper's §4.2 rule; split_factor is not used)
};

//! Which samples must keep their distance (docs/algorithms/mps.md, "Conflict rule").
enum class MpsConflict {
  Reach,            //!< the paper's (§4.2): the ball's region grows over every edge-adjacent triangle it meets
  CloseAcrossTurns  //!< regions stop where the surface turns by 90° or more (the facing cut): samples may sit
                    //!< closer than r across sharp edges and round the rims of sheets thinner than r
};

//! The largest MpsOptions::radius taken (relative: one disk of it covers any sheet many times over).
constexpr double kMaxMpsRadius = 10;

struct MpsOptions {
  double radius = 0.01;                  //!< r (uniform) or r_min (adaptive), relative to the longest bounding-box side, up to kMaxMpsRadius
  bool adaptive = false;                 //!< radius from curvature, never below r_min
  double max_radius_ratio = 2.0;         //!< adaptive: r_max / r_min (flat parts get r_max)
  double curvature_fraction = 0.5;       //!< adaptive: on curved parts r ≈ this fraction of the radius of curvature
  double gradation = 0.3;                //!< adaptive and radius_field: Lipschitz bound of r along mesh edges (|Δr| <= g·length)
  //! If not empty: the radius at each vertex of the input mesh (absolute), linear over its
  //! triangles, instead of `radius` and `adaptive` (which still set the scale checks); r_min is its
  //! smallest value. The LRRT's repair (report/lrrt_repair.h) gives thin parts smaller disks so.
  std::vector<double> radius_field;
  std::uint64_t seed = 1;                //!< the same seed gives the same samples on every machine
  int max_consecutive_rejections = 300;  //!< dart throwing stops after this many rejections in a row (paper: 300)
  MpsGapUpdate gap_update = MpsGapUpdate::Local;
  MpsRefinement refinement = MpsRefinement::RadiusField;
  MpsConflict conflict = MpsConflict::Reach;
  //! RadiusField: edges are split until no longer than this times the radius at their ends. At 2,
  //! a uniform sample has about 2.5 triangles instead of 9-10 at 1, and the sampler takes about
  //! half the time (0.42-0.77 of it on the Table 3 models); nothing needs a triangle smaller than a disk.
  double split_factor = 2.0;
  //! The order of the refined mesh (MpsResult::mesh). Spatial keeps neighbouring triangles close in
  //! memory, which every stage reads by the triangle: faster on meshes stored in no spatial order
  //! (dragon_100k, whose neighbours lie a median 22k indices apart). The order changes where the darts
  //! land, not what is checked.
  RefineOrder refine_order = RefineOrder::Spatial;
  //! Samples on the corners and feature lines (boundary edges, and edges whose triangles' normals
  //! are more than feature_angle degrees apart) before the surface's darts, when the mesh has any:
  //! the samples then follow the features, which the LRRT needs at sharp edges and boundary corners
  //! (docs/algorithms/mps.md, "Features"). On by default; a mesh without feature lines is sampled
  //! as with it off. The samples on the features are placed, not thrown: off gives the paper's
  //! uniform darts everywhere.
  bool sample_features = true;
  //! Points on the surface sampled first, each through the sampler's test like any dart (the
  //! LRRT's rounds keep the samples away from its defects so), before the features and the darts.
  std::vector<Vec3> first_samples;
  //! Balls (centre, absolute radius) in which no sample goes on the feature lines off the
  //! boundary: darts sample the surface there (the LRRT's rounds put them where feature samples
  //! were at its defects).
  std::vector<std::pair<Vec3, double>> feature_exclusions;
  double feature_angle = 60;             //!< degrees, 0 < angle < 180: what counts as a feature line
  int max_gap_rounds = 30;               //!< LRPD evaluations allowed for gap detection before giving up
  double max_expected_samples = 5e6;     //!< refuse radii that would need more samples than this
  //! Called with a short message at each stage (for progress output); may be empty.
  std::function<void(const std::string&)> on_progress;
};

struct MpsTimings {
  double init = 0;           //!< bounding box, radius field, edge splitting, area table
  double dart_throwing = 0;  //!< the initial dart throwing
  double gap_filling = 0;    //!< LRPD gap detection and darts into the gaps
  double total = 0;
  double cpu_total = 0;      //!< CPU seconds of the whole sampling, all threads (the process's clock)
};

struct MpsResult {
  SurfaceMesh mesh;               //!< the input with its long edges split: the samples' triangles index it
  Samples samples;                //!< positions, weights = radius², triangles, barycentric; in insertion order
  std::vector<double> radii;      //!< radius of each sample (sqrt of its weight)
  double scale = 0;               //!< longest side of the input's bounding box (the unit-cube normalisation)
  double radius = 0;              //!< absolute r (r_min when adaptive)
  double max_radius = 0;          //!< absolute largest radius of the radius field
  //! The input's feature lines at MpsOptions::feature_angle, counted whether or not they are sampled:
  int feature_edges = 0;          //!< edges whose triangles' normals are more than the angle apart, and boundary edges
  int boundary_edges = 0;         //!< of feature_edges: on the boundary
  int feature_corners = 0;        //!< vertices with other than two feature edges, or two that turn by more than the angle
  int first_samples = 0;          //!< of MpsOptions::first_samples, those placed: the first samples
  int feature_samples = 0;        //!< samples placed on corners and feature edges (MpsOptions::sample_features), after those
  int dart_samples = 0;           //!< samples placed by the initial dart throwing (feature samples included)
  int gap_samples = 0;            //!< samples placed into gaps
  std::int64_t darts = 0;         //!< darts thrown in both stages (accepted or not)
  int lrpd_evaluations = 0;       //!< LRPDs computed to find gaps
  int part_lrpd_triangles = 0;    //!< triangles of those computed on a part of the mesh (later rounds)
  int gap_pieces = 0;             //!< gap pieces the first round showed
  int dropped_gap_pieces = 0;     //!< pieces dropped as rounding noise: uncovered area below 1e-15·r² or 1e-13 of their polygon
  //! Gap pieces split by a sample whose centre their darts' regions reach (the paper's rule read
  //! from the dart's side), as by a disk reaching them.
  int carved_gap_pieces = 0;
  //! Required gap pieces left at the end that lie where a dart is refused from its own side (the
  //! paper's rule: within r_s of a sample s whose ball reaches s's triangle round a rim or fold).
  int certified_gap_pieces = 0;
  int dust_samples = 0;           //!< of gap_samples: placed at a dropped piece's corner that was uncovered after all
  int clamped_radii = 0;          //!< adaptive: samples whose radius was cut to the distance of an earlier sample
  //! Adaptive, the paper's rule: of clamped_radii, samples whose radius was cut to below the one at
  //! which a closer sample (across a thin sheet) becomes local to them, not to its distance.
  int radii_below_reach = 0;
  int power_cell_exceptions = 0;  //!< adaptive: samples that keep the power-cell condition only against the
                                  //!< samples facing like them, or if that fails too, only against those local
                                  //!< to them (none met it against all; docs/algorithms/mps.md)
  bool gaps_closed = false;       //!< the sampler found no gap left (verify_mps checks it independently)
  MpsTimings time_s;
};

//! Maximal Poisson-disk samples of the surface: no sample lies in another sample's disk and the
//! disks cover the surface (each cell of the samples' LRPD lies in its own disk).
//! \pre options.radius > 0.
//! \throw InputError when the radius is not a positive finite number, the split factor not a
//!        finite number of at least 1 (below 1 it would only multiply the triangles), or the
//!        radius so small for this mesh that more than options.max_expected_samples samples
//!        would be needed.
MpsResult maximal_poisson_disk_sampling(const SurfaceMesh& mesh, const MpsOptions& options = {});

//! The radius of the adaptive sampling at each vertex (absolute, paper §4.2's r(x) of a density):
//! with κ the mean curvature (cotangent Laplacian, smoothed twice over the one-ring; 0 on the
//! boundary), r_max = max_radius_ratio·r_min and f = curvature_fraction,
//! r = max(r_min, r_max / sqrt(1 + (κ·r_max / f)²)) — r_max where the surface is flat, about f
//! times the radius of curvature where it bends — then limited so that it changes by at most
//! `gradation` per unit length along edges. The sampler interpolates it linearly in triangles.
std::vector<double> adaptive_radius_field(const SurfaceMesh& mesh, double r_min, const MpsOptions& options);

//! Expected number of samples for a radius (absolute) on this mesh: area / (√3/2 · r²), the
//! count of a hexagonal packing at spacing r (an upper estimate for MPS).
double expected_sample_count(const SurfaceMesh& mesh, double radius);
//! The same for a radius field (absolute, one value per vertex): the sum over the triangles of
//! their area over √3/2 · r², r the mean of their corners' radii.
double expected_sample_count(const SurfaceMesh& mesh, const std::vector<double>& vertex_radius);
//! Limits a radius field so that it changes by at most `gradation` per unit length along the
//! mesh's edges, by lowering values only (r(v) <= r(u) + g·|uv|, Dijkstra from the smallest).
void limit_radius_gradation(const SurfaceMesh& mesh, double gradation, std::vector<double>& vertex_radius);

}  // namespace lrvd
