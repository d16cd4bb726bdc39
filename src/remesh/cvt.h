// Centroidal Voronoi tessellation on a surface (paper §4.1): Lloyd relaxation or L-BFGS on the
// CVT energy computed exactly on the LRVD (or the RVD, for comparison); the result lies on the surface.
#pragma once

#include <functional>
#include <vector>

#include "diagram/diagram.h"
#include "mesh/closest_point.h"
#include "mesh/surface_mesh.h"

namespace lrvd {

enum class CvtOptimizer { Lbfgs, Lloyd };
enum class CvtDensity { Uniform, Curvature };

struct CvtOptions {
  DiagramKind diagram = DiagramKind::Lrvd;      //!< Lrvd (the paper) or Rvd (the baseline)
  CvtOptimizer optimizer = CvtOptimizer::Lbfgs;
  int iterations = 60;                          //!< iteration cap (L-BFGS iterations or Lloyd steps)
  int lloyd_warmup = 3;                         //!< Lloyd steps before L-BFGS (robust first moves)
  double relative_gradient = 1e-7;              //!< stop when ||∇F|| < this · F / (mean cell size)
  double relative_energy_change = 1e-9;         //!< stop when F changes less than this, relatively
  CvtDensity density = CvtDensity::Uniform;
  std::vector<double> triangle_density;         //!< if not empty: ρ per mesh triangle, overrides `density`
  //! When a sample's new position (a centroid, or an L-BFGS site) is closest to a triangle outside
  //! its cell that faces the other way than its cell there (across a thin wall or a narrow gap),
  //! the sample goes to the closest point of its own cell instead (remesh/remesh.h: the repair
  //! rounds).
  bool keep_to_sheets = false;
  //! If not empty (one entry per sample): only the samples with a nonzero entry move; the others
  //! keep their position, triangle and barycentric coordinates exactly (their gradient is left out
  //! of L-BFGS's, they skip the Lloyd steps). For a repair round that re-optimises the samples
  //! near a defect only (remesh/local_repair.h).
  std::vector<char> movable;
  //! Called after every iteration with (iteration, energy); for progress output.
  std::function<void(int, double)> on_iteration;
};

struct CvtResult {
  Samples samples;                   //!< final positions, on the surface
  Diagram diagram;                   //!< the diagram of the final samples
  int iterations = 0;                //!< Lloyd steps + L-BFGS iterations (one whose line search failed counts once)
  int diagram_evaluations = 0;
  bool line_search_stopped = false;  //!< L-BFGS ended on a failed line search (non-smooth energy)
  double energy = 0;
  std::vector<double> energy_history;  //!< energy after each iteration (first entry: initial)
  double time_s = 0;
};

//! Per-triangle density for the curvature-adaptive CVT: larger where the surface bends, so that
//! more samples go there; smoothed over about the width of a cell of `sample_count` samples, and
//! normalised to mean 1 by area (docs/algorithms/cvt-remeshing.md, "The CVT", has the formula).
std::vector<double> curvature_density(const SurfaceMesh& mesh, int sample_count);

//! CVT energy and its gradient 2 m_i (x_i - c_i) at the given samples (for tests and optimisers).
struct CvtEnergy {
  double energy = 0;
  std::vector<Vec3> gradient;
  Diagram diagram;
  CellIntegrals cells;
};
CvtEnergy cvt_energy(const SurfaceMesh& mesh, const Samples& samples, DiagramKind kind,
                     const std::vector<double>* density = nullptr);
//! The same, on the diagram of the samples already computed (the density may differ from the one
//! the diagram was last integrated with: the diagram does not depend on it).
CvtEnergy cvt_energy(const SurfaceMesh& mesh, const Samples& samples, Diagram diagram,
                     const std::vector<double>* density = nullptr);

//! Moves the samples towards a CVT of the surface. `diagram_of_initial`, when the caller has it
//! (a previous CVT's result), is the diagram of `initial` of the kind `options.diagram`: it is used
//! instead of computing the same diagram again. `index`, when the caller runs several CVTs on the
//! same mesh, is a closest-point index of `mesh`, used instead of building one per call.
//! \throw InputError on an empty sample set.
CvtResult optimize_cvt(const SurfaceMesh& mesh, const Samples& initial, const CvtOptions& options = {},
                       const Diagram* diagram_of_initial = nullptr, const ClosestPointIndex* index = nullptr);

}  // namespace lrvd
