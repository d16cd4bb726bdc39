// The remesh of `lrvd remesh` and of the Python module's remesh: the samples' preparation, the CVT,
// the check, the quality and the JSON report, one path for both.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "remesh/remesh_pipeline.h"
#include "report/report.h"

namespace lrvd {

//! The choices of a remesh, as the command's options name them.
struct RemeshSettings {
  std::string kind = "lrvd";          //!< lrvd | rvd
  std::string optimizer = "lbfgs";    //!< lbfgs | lloyd
  std::string density = "uniform";    //!< uniform | curvature
  std::string priority = "distance";  //!< distance | shape
  std::string repair_scope = "whole"; //!< whole | local (RemeshOptions::repair)
  int iterations = 60;
  bool fit = true;
};

//! \throw InputError for a power diagram, or a name the options do not know.
void check_remesh_settings(const RemeshSettings& settings);

//! The holes the kept dual closes over (fewer than three cells meet their loop), the longest's length,
//! and the smallest --fill-holes fraction of two significant digits above it: tried on the input,
//! how many of those holes it fills (fill_small_holes leaves some open) and how many other holes.
struct ClosedOverHoles {
  int count = 0;
  double longest = 0;
  double fraction = 0;
  int fillable = 0;  //!< of the `count`, filled by --fill-holes `fraction`
  int others = 0;    //!< other holes it fills
};

//! The narrowest part a ring of cells in the kept dual wraps (DualDefects::rings): the ring's
//! sample(s), how far round the part is, and how many vertices a uniform density needs to fit three
//! cells round it: the input's area over hexagons of area √3/18 · around² (a third of the way round
//! across).
struct NarrowPart {
  int vertex = -1;  //!< -1: no ring
  int other = -1;   //!< the second cell of a pair sharing two arcs
  double around = 0;
  long long uniform_vertices = 0;
};

//! The narrowest of `defects.rings`; `area` is the input surface's.
NarrowPart narrowest_ring(const DualDefects& defects, double area);

struct RemeshRun {
  RemeshOptions options;
  RemeshResult result;
  RemeshVerification check;
  bool measurable = false;  //!< the dual has triangles
  QualityMetrics quality;
  ClosedOverHoles holes;
  NarrowPart narrow;
  double diagonal = 0;  //!< of the input's bounding box
  nlohmann::json report;
};

//! Remeshes input.loaded.mesh to one vertex per sample of `input` (prepared with
//! require_remesh_vertex_count as the count check): random samples (`random_samples`) are drawn
//! again per component when there are several; both are renumbered for the CVT; then remesh_cvt,
//! `on_dual` with the output (to write it), verify_remesh, the quality and the report, whose output
//! path is `output_path`. \throw InputError for weighted samples.
RemeshRun run_remesh(Input& input, const RemeshSettings& settings, bool random_samples, std::uint64_t seed,
                     const std::string& mesh_path, const std::string& output_path, const ProgressFn& on_progress,
                     const std::function<void(const DualMesh&)>& on_dual);

}  // namespace lrvd
