// Smaller disks where the LRRT of a maximal Poisson-disk sampling has defects: the radius field
// of a new sampling, lowered round the samples the remesh's defect finder locates (run_mps,
// report/mps_report.h, runs the rounds).
#pragma once

#include <vector>

#include "diagram/diagram.h"
#include "diagram/dual.h"
#include "mps/mps.h"

namespace lrvd {

//! Rounds of smaller disks an LRRT gets at most (each halves the radius round its defects). The
//! five sheet and tube stress meshes at r = 0.02 and 0.05 (seed 1) need at most 4; feline at
//! r = 0.005 takes 2-8 on seeds 1-3 (docs/results.md, "The LRRT on the Table 3 models").
constexpr int kMaxLrrtRounds = 8;
//! No round starts whose radius field would take more than this many times the samples of the
//! first (expected_sample_count of the fields), plus kLrrtGrowthAllowance: a radius cut at a vertex of large input triangles
//! spreads over them (ChineseDragon-10kv at r = 0.005, seed 2: 68,624 samples to 249,451 and
//! 191 CPU s over eight rounds), and the work stays bounded.
constexpr int kMaxLrrtGrowth = 2;
//! ... plus this many, so that a small sampling can take what its LRRT needs (the folded sheet at
//! r = 0.05: a few hundred samples, its defects at 48 of them; with 1000 the rounds stopped after
//! two, invalid, and with this after four, valid); 10,000 samples take a fraction of a second.
constexpr double kLrrtGrowthAllowance = 10000;
//! A round lowers the radius on the vertices within this many radii of a defect sample. With
//! every sample resampled each round, at 2 the folded sheet and the thin plate at 0.02 stayed
//! invalid after eight rounds and at 3 they passed.
constexpr double kLoweredReach = 3;

//! The radius at each vertex of `input` (the surface sampled, or a refinement of it) that the
//! sampling `result` used (absolute): its radius everywhere, the adaptive field, or the field it
//! was given (which must then be of `input`'s vertices).
std::vector<double> sampled_radius_field(const SurfaceMesh& input, const MpsOptions& options, const MpsResult& result);

//! The samples at the defects of `dual`, the LRRT of `lrpd` (the samples' LRPD on result.mesh):
//! those find_dual_defects (remesh/dual_defects.h) would act on.
std::vector<int> lrrt_defect_samples(const SurfaceMesh& input, const MpsResult& result, const Diagram& lrpd,
                                     const DualMesh& dual);

//! Lowers `field` (one radius per vertex of `input`, the surface sampled) round `samples` of `result`: every vertex
//! within kLoweredReach·r_s of sample s, or the three nearest if none is, gets at most r_s / 2; then the field
//! changes by at most `gradation` per unit length (limit_radius_gradation). Returns the number of
//! vertices whose radius went down.
int halve_radius_round(const SurfaceMesh& input, const MpsResult& result, const std::vector<int>& samples,
                       double gradation, std::vector<double>& field);

//! The positions of the samples of `result` outside the part of the surface a round changes round
//! `defects` (farther than (kLoweredReach + 1/(2·gradation) + 1)·r_d from each defect sample d:
//! the halved radius, its ramp back up at the gradation, and a disk), for the next sampling to
//! place first (MpsOptions::first_samples): a round then samples again only round its defects, and
//! the LRRT elsewhere, which passed, stays as it was.
std::vector<Vec3> samples_away_from(const MpsResult& result, const std::vector<int>& defects, double gradation);

//! Adds to `exclusions` (MpsOptions::feature_exclusions) a ball of kLoweredReach·r_s about each of
//! `samples` that is a feature sample of `result` (the result.feature_samples after its first
//! samples): on scanned
//! meshes whose creases are feature lines (feline: 824 edges at 60°) the LRRT's defects at such
//! samples stayed through eight halvings of the radius. Returns the balls added.
int exclude_feature_samples(const MpsResult& result, const std::vector<int>& samples,
                            std::vector<std::pair<Vec3, double>>& exclusions);

//! Pairs of triangles of `input` that cross each other within one connected component (exact,
//! find_self_intersections): a refused LRRT's line names them, since a remesh that must keep the
//! topology of a surface cutting through itself may have no valid form there.
std::vector<std::pair<int, int>> crossings_within_parts(const SurfaceMesh& input);

//! `samples` of `result` but those within kLoweredReach·r_s of a triangle of `crossings` (pairs of
//! crossing triangles of `input`): smaller disks there sample a surface that cuts through itself
//! more finely, and its LRRT's defects there stay or grow (ChineseDragon-10kv at r = 0.005, seed
//! 1: refused after eight rounds and 64 CPU s when they were acted on, after one round and 11 s
//! when left alone).
std::vector<int> away_from_crossings(const SurfaceMesh& input, const MpsResult& result, const std::vector<int>& samples,
                                     const std::vector<std::pair<int, int>>& crossings);

}  // namespace lrvd
