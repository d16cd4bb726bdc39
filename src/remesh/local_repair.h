// A local repair round (RemeshOptions::repair): the CVT of the samples within a few cell rings of
// the defects, on the part of the mesh they and a frozen ring of neighbours cover; the rest stay put.
#pragma once

#include <vector>

#include "remesh/cvt.h"

namespace lrvd {

//! What a repair round re-optimises: every sample of the mesh (a whole CVT per round), or the
//! samples near the defects on a window of the mesh (repair_round_cvt), with whole rounds only
//! where local ones stall.
enum class RepairScope { Whole, Local };

struct LocalRepairOptions {
  //! Cell rings round the cells a round acts on whose samples move; one more ring per round
  //! without a better state (RemeshOptions: the rounds' bookkeeping).
  int rings = 2;
  //! The first rounds of a run are whole-mesh CVTs: a remesh those mend (CGAL's elk at 516 in 2)
  //! is the one of RepairScope::Whole, whose triangles and distances are better than local rounds
  //! leave (elk 516 with every round local: Qmin 0.649 -> 0.515), and the local rounds take over
  //! where more are needed (docs/results.md, "Local repair rounds").
  int whole_first = 2;
  //! Rounds without a better state after which the rounds are whole-mesh CVTs again, until one is
  //! better (0: every round whole).
  int whole_after = 4;
  //! A window holding more than this share of the samples (with its frozen ring) is optimised as
  //! a whole CVT: the part of the mesh it covers would save little.
  double max_window_share = 0.5;
};

//! What a local repair round did (repair_round_cvt), for its progress line.
struct LocalRound {
  //! why the round was a whole CVT: "" (it was local), "first rounds" (LocalRepairOptions::whole_first),
  //! "no progress" (whole_after), "window too large" (max_window_share)
  const char* whole_because = "";
  int window = 0;   //!< samples in the window, the frozen ring included (0: no window was built)
  int moving = 0;   //!< of which move
};

//! The samples within `rings` rings of `seeds` in the cell adjacency of `diagram` (two cells are
//! adjacent when they share a diagram vertex): 1 for those, 2 for the ring of cells next to them,
//! 0 for the rest.
std::vector<char> repair_window(const Diagram& diagram, const std::vector<int>& seeds, int rings);

//! A CVT in which only the samples marked 1 in `window` (repair_window) move: it runs on the
//! sub-mesh of the triangles the cells marked 1 or 2 cover in `diagram` (the diagram of
//! `samples`), with those samples, the ring's frozen; then the diagram of every sample on `mesh`
//! is computed once. The moving cells' energy and gradient depend only on their neighbours, which
//! the ring holds, as long as the cells stay inside it. Samples outside the window keep their
//! position, triangle and barycentric coordinates exactly. `options.triangle_density` (one value
//! per triangle of `mesh`) is used on the sub-mesh's triangles. The result's counters cover the
//! window's diagrams and the whole one.
CvtResult optimize_cvt_in_window(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram,
                                 const std::vector<char>& window, const CvtOptions& options);

//! The CVT of repair round `round` (from 0) of a run with local repair (RepairScope::Local). In the
//! first `local.whole_first` rounds, and when the rounds have gone `local.whole_after` rounds
//! without a better state: optimize_cvt of every sample. Otherwise the window of `acted_on` (the cells whose density the round raised or
//! lowered) and, when samples were moved since `diagram` was computed (their position differs from
//! its site), those samples and their former neighbours, grown by `local.rings` rings plus one per
//! round without progress, optimised with optimize_cvt_in_window; a window too large for that
//! (LocalRepairOptions::max_window_share) is a whole CVT. `diagram` is the last diagram computed,
//! of `samples` but for the moved ones.
CvtResult repair_round_cvt(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram,
                           const std::vector<int>& acted_on, const CvtOptions& options, const LocalRepairOptions& local, int round, int rounds_without_progress,
                           const ClosestPointIndex& index, LocalRound* account = nullptr);

}  // namespace lrvd
