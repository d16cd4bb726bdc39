// The maximal Poisson-disk sampling of `lrvd mps` and of the Python module's mps: the sampler, its
// check on a fresh LRPD, the optional LRRT remesh and the JSON report, one path for both.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "diagram/dual.h"
#include "mps/mps.h"
#include "report/report.h"
#include "verification/mps_check.h"

namespace lrvd {

//! The choices of a sampling, as the command's options name them (`*_given`: the option was set).
struct MpsSettings {
  double radius = 0;
  bool adaptive = false;
  double max_radius_ratio = MpsOptions{}.max_radius_ratio;
  bool max_radius_ratio_given = false;
  std::uint64_t seed = 1;
  std::string gap_update = "local";  //!< local | lrpd
  std::string split_to = "field";    //!< field | rmin
  std::string conflict = "reach";    //!< reach (the paper's rule) | close-across-turns (MpsConflict::CloseAcrossTurns; "facing" too)
  double split_factor = MpsOptions{}.split_factor;
  bool split_factor_given = false;
  bool exact = false;     //!< decide every vertex of the maximality check with rational arithmetic
  bool features = true;   //!< sample the feature lines first when the mesh has any (--no-features: false)
  double feature_angle = MpsOptions{}.feature_angle;
  bool feature_angle_given = false;
  //! With the LRRT: keep the radius where the LRRT has defects (by default the radius is halved
  //! round them and the surface sampled again, up to kMaxLrrtRounds times: report/lrrt_repair.h).
  bool keep_radius = false;
};

//! verify_mps (verification/mps_check.h) on an LRPD of the samples computed here with compute_lrvd;
//! it goes to `*lrpd` when asked for.
MpsVerification verify_mps(const SurfaceMesh& mesh, const Samples& samples, const MpsVerifyOptions& options = {},
                           Diagram* lrpd = nullptr);

//! What can be refused before the mesh is read: the radius, the ranges and names of the options,
//! --max-radius-ratio without --adaptive. \throw InputError
void check_mps_settings(const MpsSettings& settings);

struct MpsRun {
  MpsOptions options;
  MpsResult result;
  MpsVerification check;
  bool maximal = false, min_distance_ok = false;
  Diagram lrpd;       //!< the samples' LRPD the check computed (the LRRT is its dual)
  bool lrrt = false;  //!< the LRRT was asked for; then:
  DualMesh dual;
  //! The rounds that halved the radius round the LRRT's defects and sampled again, the input
  //! vertices whose radius they lowered, and their seconds, wall and CPU (each round's sampling,
  //! check and LRRT; MpsSettings::keep_radius). `result` and `check` are the last round's.
  struct {
    int rounds = 0;
    int vertices = 0;
    double time_s = 0, cpu_s = 0;
  } smaller_disks;
  RemeshVerification remesh_check;
  //! The LRRT failed its checks: one line saying that these samples give no valid LRRT at this
  //! radius and which properties fail; empty when it passed.
  std::string lrrt_refusal;
  //! When the LRRT failed: the first sample at its defects, if the defect finder locates one, and
  //! the input's crossing pairs of triangles within one part (crossings_within_parts).
  std::optional<Vec3> first_defect;
  int input_crossings = 0;
  bool measurable = false;  //!< the LRRT has triangles
  QualityMetrics quality;
  nlohmann::json report;  //!< complete but for `predicates`, taken when the caller is done
};

//! Samples loaded.mesh, `on_samples` with them (to write them), checks them, and with `lrrt`
//! computes, `on_dual` (to write it), checks and measures their LRRT. The paths go into the report.
//! \throw InputError for options that contradict each other, or a mesh the sampler refuses.
MpsRun run_mps(const LoadedMesh& loaded, bool repair_requested, const MpsSettings& settings,
               const std::string& mesh_path, const std::string& output_path, bool lrrt,
               const std::string& remesh_path, const ProgressFn& on_progress,
               const std::function<void(const Samples&)>& on_samples,
               const std::function<void(const DualMesh&)>& on_dual);

}  // namespace lrvd
