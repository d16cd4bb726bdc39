// Low-resolution remeshing (paper §4.1): CVT on the LRVD, its dual with exactly N vertices, and
// repair of the dual where thin parts are too coarsely sampled (paper Fig. 13) by moving samples
// there through a locally raised density.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "diagram/dual.h"
#include "remesh/cvt.h"
#include "remesh/dual_defects.h"
#include "remesh/fit.h"
#include "remesh/local_repair.h"
#include "remesh/stage_times.h"
#include "remesh/untangle.h"

namespace lrvd {

struct RemeshOptions {
  CvtOptions cvt;
  int repair_rounds = 24;          //!< rounds of "move a sample to a defect, optimise again"
  int repair_iterations = 30;      //!< CVT iterations after each density raise
  double repair_factor = 2;        //!< each round multiplies the density around defects by this
  //! A run that goes this many repair rounds in a row without a state with fewer defects than any
  //! run's best so far pauses, and the next run (samples kept to their sheets, then tip caps
  //! lowered) takes its turn; the paused runs go on to their last round, in order, only when no
  //! later run ends without defects (0: each run goes to its last round before the next starts).
  //! Every run can still take all its rounds, so a remesh the runs in turn would mend is mended
  //! either way. 6 takes feline 200 from 57 rounds to 28 and Happy Buddha 300 from 39 to 23 with
  //! the same output, and costs rounds where a paused run was about to end valid (the thin plate at
  //! 50 and 100, CGAL's diplodocus at 200): docs/results.md.
  int switch_after = 6;
  //! What a repair round re-optimises (remesh/local_repair.h): every sample (Whole), or after the
  //! first rounds the samples within a few cell rings of the cells it acts on, on the part of the
  //! mesh round them (Local: 2.3-4.4 times less CPU on the folded sheet at 100 and 300, but worse
  //! triangles where it ends the repair, armadillo 2000 Qmin 0.605 -> 0.588, so not the default)
  RepairScope repair = RepairScope::Whole;
  LocalRepairOptions local_repair;
  bool fit = true;                 //!< move the vertices onto their cells' planes (remesh/fit.h)
  FitOptions fit_options;
  //! Before the fitting, move the vertices of the worst triangles towards their neighbours, on the
  //! surface (relax_worst_triangles, remesh/fit.h): a higher worst triangle for a larger distance on
  //! the bends (0 rounds, the default: none; `lrvd remesh --priority shape`: 5). A kept state that
  //! was fitted and untangled during the repair rounds (its dual had crossings) is not relaxed.
  RelaxOptions relax;
  //! when the dual's only defect is crossings, fit and untangle it (remesh/untangle.h) before
  //! deciding whether to raise the density; the crossings left are where it is raised
  bool untangle = true;
  UntangleOptions untangle_options;
  //! when the state the loop keeps has crossings left, it is untangled again from its fitted
  //! vertices with each of these reaches (UntangleOptions::max_move) in turn, the fewest crossings
  //! kept: vertices move further only where the repair rounds could not do without it
  std::vector<double> final_max_moves = {0.75, 1.0};
  //! when the run (first CVT and repair rounds) ends with defects, run it again from the same
  //! samples with CvtOptions::keep_to_sheets, each round also moving samples into the defect
  //! cells, and keep the run with fewer defects
  bool keep_to_sheets_retry = true;
  //! when the second run ends with defects too and some round of it found a cap on a sharp tip
  //! (DualDefects::tip_caps), run it a third time with the density lowered on those caps instead of
  //! raised, and keep it if it has fewer defects (a larger cap cuts more of the tip off, so this is
  //! the last resort, not the rule)
  bool tip_caps_retry = true;
  //! when defects are left on a component holding at most one sample more than the fewest its
  //! topology needs (several components, samples drawn per component), run everything again with
  //! two more samples on each such component, moved from the components with the most to spare,
  //! and keep that if it leaves fewer defects
  bool reallocation_retry = true;
  //! when every run (and the reallocation's) ended with defects, all the runs again from the kept
  //! result's start with Lloyd steps instead of L-BFGS in the repair rounds (`repair_iterations`
  //! of them, one diagram each), kept if they leave fewer defects. A Lloyd step (each sample to its
  //! cell's centroid) needs no line search, where L-BFGS's line searches fail near thin parts
  //! and close sheets (feline 200: 969 of its 2,153 diagrams in line searches that halved the step
  //! 5 to 19 times). The outputs the runs before mend are unchanged; on the hard rows of
  //! docs/results.md (seeds 1-3), 116 of 129 runs end valid instead of 110.
  bool lloyd_rounds_retry = true;
  //! Lloyd steps on the state a run keeps when its dual has no defect (L-BFGS only): L-BFGS moves
  //! the sites in space and puts them on the surface at the end, which can leave two samples a
  //! tenth of the cell size apart with slivers between them (Igea at 20000: Qmin 0.29); a Lloyd
  //! step moves every sample to its cell's centroid. The polished state is kept when its dual has
  //! no defect either.
  int polish_steps = 1;
  //! CVT iterations on the state a run keeps when its repair rounds ended without defects, with the
  //! density eased back `ease_fraction` of the way (in log scale) from the raised one towards the
  //! density the run began with; the eased state then takes its polish_steps too. The rounds double
  //! the density round each defect, and a density that steep gives poor triangles where it
  //! changes; the eased state replaces the polished one when its dual has no defect and a better
  //! worst triangle (before the fitting). 0: no easing.
  int ease_iterations = 10;
  double ease_fraction = 0.25;
  //! Called with one line on each step of the run: the first CVT's outcome, each repair round
  //! (before: where the density goes up; after: the defects left), the Lloyd step, the eased
  //! density and the choice it leads to, the second run, the fitting; for progress output.
  std::function<void(const std::string&)> on_progress;
};

//! Which way remesh_cvt went: the runs it tried, the one it kept, and what followed that run's
//! repair rounds.
struct RemeshPath {
  //! Runs of the first CVT and its repair rounds tried: 1, or more when defects were left (the runs
  //! with samples kept to their sheets, with tip caps lowered, from reallocated samples).
  int runs = 0;
  bool kept_to_sheets = false;    //!< the result is the second or third run's (RemeshOptions::keep_to_sheets_retry)
  bool tip_caps_lowered = false;  //!< the result is the third run's (RemeshOptions::tip_caps_retry)
  int samples_reallocated = 0;    //!< the result is from samples moved between components (RemeshOptions::reallocation_retry)
  //! Samples moved between components for the retry, whether or not its result was kept (0: no retry).
  int reallocation_tried = 0;
  //! The result is from the runs again with Lloyd steps in the repair rounds (RemeshOptions::lloyd_rounds_retry).
  bool lloyd_rounds = false;
  //! The kept state's dual had crossings alone and was fitted and untangled during the repair
  //! rounds (RemeshOptions::untangle): it is neither polished nor relaxed, nor fitted again.
  bool fitted_in_rounds = false;
  bool polished = false;  //!< the result is the polished state (RemeshOptions::polish_steps)
  bool eased = false;     //!< the result is the eased state (RemeshOptions::ease_iterations)
  //! Defects are left, and every run tried stopped at a round with every cell at a defect or next
  //! to one (the raise would have been uniform, which changes no CVT): the surface is thinner than
  //! the cells everywhere, and only more vertices mend it.
  bool repair_saturated = false;
};

struct RemeshResult {
  CvtResult cvt;            //!< the final CVT (samples, diagram, energy, iterations of the last run)
  DualMesh dual;            //!< the output mesh: one vertex per sample
  int total_iterations = 0; //!< over the first optimisation and every repair round
  int diagram_evaluations = 0;  //!< diagrams computed, over the first optimisation and every repair round
  int repair_rounds = 0;    //!< rounds that raised the density around defects and optimised again
  FitResult fit;            //!< what the fitting did (nothing when RemeshOptions::fit is off)
  UntangleResult untangle;  //!< what the untangling did (nothing when the dual had no crossing)
  //! While the remesh runs, once `dual` is fitted: the fitted dual before untangling, which the
  //! final untangling starts again from (RemeshOptions::final_max_moves). Empty in the result.
  DualMesh untangled_from;
  RelaxResult relax;        //!< the worst triangles' relaxation (RemeshOptions::relax)
  RemeshPath path;          //!< which runs were tried, which one was kept, and what followed its rounds
  //! What the repair left in `dual` as the rounds saw it, before the final fitting and untangling
  //! (the crossings those leave are in `untangle.remaining`): where a failed check comes from.
  DualDefects defects;
  double time_s = 0;
  //! CPU seconds of the process (every thread) in each stage of remesh_cvt (remesh/stage_times.h).
  RemeshStageTimes stage_cpu_s;
};

//! CVT remeshing to exactly samples.size() vertices. `reference` is the surface whose topology the
//! output must keep (closed or not); `mesh` the (possibly refined) surface the samples live on.
//! After the first CVT, while the dual has defects (a thin part wrapped by too few cells, sheets
//! that cut through each other), the density is multiplied by `repair_factor` over the defect
//! cells and their neighbours and the CVT runs again, which moves samples from elsewhere into the
//! thin part (with RemeshOptions::repair Local, after the first rounds only the samples within a
//! few cell rings of the defects move: remesh/local_repair.h); a state whose only defect is
//! crossings is fitted and untangled first, and the loop
//! stops when that leaves none. The result is the state with the fewest defects (the caller
//! verifies it). If it still has defects, the whole run is repeated with every sample kept to its
//! own sheet (CvtOptions::keep_to_sheets: the centroid of a cell wrapping a thin wall must not send
//! its sample across the wall or a narrow gap), and each of its rounds first moves the samples of
//! the lightest cells away from the defects (from any component that keeps more than the fewest vertices its
//! topology needs) to the points of the defect cells farthest from their samples; the run with
//! fewer defects is kept, and the counters cover both runs. Samples otherwise stay on their
//! connected components. A sample in no triangle whose cell is a disk in a corner of an open
//! mesh's boundary (DualDefects::cornered) gets the density divided by `repair_factor` on its
//! cell's own triangles instead, so that the cell grows until it meets two others. If the second
//! run ends with defects too and met a cap on a sharp tip (DualDefects::tip_caps), it runs a third
//! time with the density lowered on such caps as on cornered cells, and that run is kept if it has
//! fewer defects. Rounds stop early when no cell is known to act on. Open meshes are
//! repaired where a boundary loop is closed over (met by fewer than three cells, or a cell meets
//! two loops) or the dual is pinched at a vertex. A state the rounds leave without defects is also
//! tried with their density eased back (RemeshOptions::ease_iterations). The result is fitted to
//! the surface under the CVT's quality floor (fit_to_surface) unless switched off; if crossings
//! are left in it, it is untangled again from its fitted vertices with the longer reaches of
//! `final_max_moves`.
RemeshResult remesh_cvt(const SurfaceMesh& reference, const SurfaceMesh& mesh, const Samples& initial,
                        const RemeshOptions& options = {});

}  // namespace lrvd
