// Remesh quality metrics (paper §5): triangle quality Q(t) = 6/√3·|t|/(p(t)h(t)), angles, and the
// two-sided Hausdorff and RMS distance to the reference surface.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "mesh/surface_mesh.h"

namespace lrvd {

struct QualityMetrics {
  double q_min = 0, q_avg = 0;              //!< Q(t) over the triangles (1 for equilateral)
  double theta_min = 0, theta_max = 0;      //!< smallest and largest angle, degrees
  double pct_triangles_below_30 = 0;        //!< % of triangles with an angle below 30°
  double pct_angles_below_30 = 0;           //!< % of angles below 30° (the paper's "<30°")
  double hausdorff_pct = 0, rms_pct = 0;    //!< two-sided, % of the reference's bbox diagonal
  int triangles = 0, vertices = 0;
  nlohmann::json to_json() const;
};

struct DistanceOptions {
  int samples_per_surface = 200000;  //!< points drawn on each surface (plus its vertices)
  unsigned long long seed = 20140701;  //!< the same points every run
};

//! Q(t) = 6/√3 · |t| / (p(t) h(t)) of one triangle: 1 when equilateral, 0 when degenerate.
double triangle_quality(const Vec3& a, const Vec3& b, const Vec3& c);
//! The smallest corner angle of one triangle, in degrees (0 when an edge has zero length).
double triangle_min_angle(const Vec3& a, const Vec3& b, const Vec3& c);

//! Triangle-shape metrics alone (degenerate triangles count with Q = 0 and angles 0/180).
//! \throw InputError when a triangle names a missing vertex or a used vertex is not finite.
QualityMetrics shape_metrics(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles);

//! Shape metrics plus distances between the triangles and the reference surface. The triangles
//! may be non-manifold; formulas and sampling: docs/reference/metrics.md.
//! \throw InputError as shape_metrics, and when no triangle has three non-collinear corners.
QualityMetrics quality_metrics(const SurfaceMesh& reference, const std::vector<Vec3>& positions,
                               const std::vector<Triangle>& triangles, const DistanceOptions& options = {});

}  // namespace lrvd
