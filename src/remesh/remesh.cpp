// CVT remeshing with repair of the dual by moving samples into under-sampled thin parts: the
// driver of remesh_cvt, a class whose methods are the stages (first CVT, repair rounds, the retries,
// polish, ease, fit, untangle), over the defect finder (dual_defects.h) and the moves of densities
// and samples (repair_moves.h).
#include "remesh/remesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <iterator>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "common/timing.h"
#include "mesh/closest_point.h"
#include "mesh/curvature.h"
#include "metrics/quality.h"
#include "remesh/remesh_pipeline.h"
#include "remesh/repair_moves.h"

namespace lrvd {

namespace {

// Rounds of the third run without a better state after which the rings round the tip caps
// (DualDefects::tip_cap_rings) get the caps' lower density too, for the rest of the run.
constexpr int kRingLoweringAfter = 3;

// Another run's result replaces `result` when it leaves fewer defects; the counters of work done
// (rounds, iterations, diagrams) cover both either way.
void keep_if_fewer(RemeshResult again, DualDefects again_defects, RemeshResult& result, DualDefects& defects) {
  again.repair_rounds += result.repair_rounds;
  again.total_iterations += result.total_iterations;
  again.diagram_evaluations += result.diagram_evaluations;
  if (again_defects.fewer_than(defects)) {
    result = std::move(again);
    defects = std::move(again_defects);
  } else {
    result.repair_rounds = again.repair_rounds;
    result.total_iterations = again.total_iterations;
    result.diagram_evaluations = again.diagram_evaluations;
  }
}

// \throw InputError when `mesh` is not a refinement of `reference`, or an option is out of range.
void check_remesh_input(const SurfaceMesh& reference, const SurfaceMesh& mesh, const Samples& initial,
                        const RemeshOptions& options) {
  require_workable_model(reference, "remeshing");
  require_workable_model(mesh, "remeshing");
  require_remesh_vertex_count(reference, initial.size());
  if (mesh.component_count() != reference.component_count() ||
      mesh.euler_characteristic() != reference.euler_characteristic() ||
      mesh.boundary_loops().size() != reference.boundary_loops().size())
    throw InputError(fmt::format("remesh_cvt: the mesh ({} components, Euler characteristic {}, {} boundary loops) is "
                                 "not a refinement of the reference ({}, {}, {})",
                                 mesh.component_count(), mesh.euler_characteristic(), mesh.boundary_loops().size(),
                                 reference.component_count(), reference.euler_characteristic(),
                                 reference.boundary_loops().size()));
  if (!(options.ease_fraction >= 0 && options.ease_fraction <= 1) || options.ease_iterations < 0)
    throw InputError(fmt::format("remesh options: ease_fraction ({}) must be in [0, 1] and ease_iterations ({}) not negative",
                                 options.ease_fraction, options.ease_iterations));
  if (options.repair_rounds < 0 || options.repair_iterations < 1 || options.polish_steps < 0)
    throw InputError(fmt::format("remesh options: repair_rounds ({}) and polish_steps ({}) may not be negative, and "
                                 "repair_iterations ({}) must be at least 1",
                                 options.repair_rounds, options.polish_steps, options.repair_iterations));
  if (options.relax.rounds < 0 || options.relax.worst_triangles < 0)
    throw InputError(fmt::format("remesh options: the relaxation's rounds ({}) and worst_triangles ({}) may not be negative",
                                 options.relax.rounds, options.relax.worst_triangles));
  if (!(options.repair_factor > 1) || !std::isfinite(options.repair_factor))
    throw InputError(fmt::format("remesh options: the repair factor must be a number above 1 (got {})",
                                 options.repair_factor));
}

// One run: the first CVT, then rounds that raise the density where the worst kind of defect is
// (topology first, crossings next); the state with the fewest defects is its result, with the
// counters of the whole run.
struct Run {
  bool keep_to_sheets = false;       // the second and third runs
  bool lower_tip_caps = false;       // the third run
  CvtOptions first;                  // of the first CVT
  CvtOptions again;                  // of the rounds; its density changes round by round
  std::vector<double> base_density;  // the rounds' density before any round changed it
  RemeshResult result;               // the state the last round left, with the run's counters
  DualDefects defects;               // of result.dual
  RemeshResult best;                 // the state with the fewest defects so far
  DualDefects best_defects;
  std::vector<double> best_density;  // the density `best` was optimised for
  int rounds_without_progress = 0;   // since the best state so far
  int rounds_behind = 0;             // since a state with fewer defects than any run's best (switch_after)
  bool lower_rings = false;          // the third run's caps stalled: their rings are lowered from then on
  bool saw_tip_caps = false;         // some round's dual had a cap on a sharp tip
  int round = 0;                     // the next repair round, from 0
  bool stopped = false;              // a round found nothing it could change (repair_round)
};

// The state remesh_cvt's stages share: the surfaces, the options, what the runs found, and the
// state kept over all of them.
class RemeshDriver {
 public:
  RemeshDriver(const SurfaceMesh& reference, const SurfaceMesh& mesh, const Samples& initial,
               const RemeshOptions& options)
      : reference_(reference), mesh_(mesh), initial_(initial), options_(options),
        start_(std::chrono::steady_clock::now()), clock_(times_), inherited_(mesh), index_(mesh) {}

  // The first run from the initial samples, and its retries while defects are left: the run again
  // with samples kept to their sheets, then with the density lowered on caps at sharp tips.
  void runs() { kept_ = runs_from(initial_, kept_defects_); }
  void reallocation_retry();
  void lloyd_rounds_retry();
  void fit();
  void untangle_further();
  RemeshResult finish();

 private:
  RemeshResult runs_from(const Samples& start, DualDefects& defects);
  Run start_run(const Samples& start, bool keep_to_sheets, bool lower_tip_caps);
  bool start_next_run(const Samples& start, std::deque<Run>& runs);
  bool can_go_on(const Run& r) const {
    return !r.stopped && r.round < options_.repair_rounds && !r.defects.empty() && !r.defects.where_to_act().empty();
  }
  RemeshResult end_runs(std::deque<Run>& runs, std::optional<std::size_t> clean, DualDefects& defects);
  void first_cvt(Run& r, const Samples& start);
  void begin_rounds(Run& r);
  bool repair_round(Run& r, int round);
  std::vector<int> cells_to_lower(Run& r) const;
  void optimise_round(Run& r, const std::vector<int>& raised, const std::vector<int>& lowered, int round);
  RemeshResult end_run(Run& r);
  void polish(RemeshResult& state, const std::vector<double>& density, Run& r);
  void ease(Run& r);
  DualDefects find_defects(const DualMesh& dual, const CvtResult& cvt) const {
    const StageClock::Scope timed(clock_, &RemeshStageTimes::defects);
    return find_dual_defects(dual, cvt.diagram, mesh_, cvt.samples, reference_.is_closed(), inherited_);
  }
  DualMesh dual_of(const CvtResult& cvt) const {
    const StageClock::Scope timed(clock_, &RemeshStageTimes::defects);
    return compute_dual(cvt.diagram, mesh_, cvt.samples);
  }
  void settle(RemeshResult& r, DualDefects& d) const;
  void progress(const std::string& message) const {
    if (options_.on_progress) options_.on_progress(message);
  }

  const SurfaceMesh& reference_;  // the surface whose topology the output keeps
  const SurfaceMesh& mesh_;       // the (maybe refined) surface the samples live on
  const Samples& initial_;
  const RemeshOptions& options_;
  const std::chrono::steady_clock::time_point start_;
  RemeshStageTimes times_;  // charged by clock_ from the driver's construction on
  mutable StageClock clock_;
  // On the CVT's mesh, whose components the samples' triangles name (the reference's cross alike).
  const InputCrossings inherited_;
  const ClosestPointIndex index_;  // one for every CVT and repair round
  // The third run, and the second of the runs again with Lloyd rounds, start from the second run's
  // first CVT (the same samples, options and result), kept here for the samples it started from,
  // not computed again. (The first run's is not kept: only a remesh that ends with defects would
  // use it, and every remesh would pay for the copy.)
  struct Start {
    RemeshResult result;
    DualDefects defects;
  };
  std::optional<Start> sheets_start_;
  std::vector<Vec3> sheets_start_of_;  // the positions of the samples it started from
  bool lloyd_rounds_ = false;    // the repair rounds take Lloyd steps (RemeshOptions::lloyd_rounds_retry)
  Samples reallocated_;          // the reallocation's samples (RemeshOptions::reallocation_retry), if it ran
  // Runs tried, and those that stopped at a round that would have raised the density everywhere.
  int runs_ = 0, saturated_runs_ = 0;
  RemeshResult kept_;         // the state kept over every run
  DualDefects kept_defects_;  // of kept_.dual, as the rounds saw it
};

// The first run from `start`, then the second and third while defects are left. With
// RemeshOptions::switch_after, a run that stalls pauses and the next takes its turn; the paused runs
// go on, in order, to their last round only if no later run ends without defects.
RemeshResult RemeshDriver::runs_from(const Samples& start, DualDefects& defects) {
  if (start.positions != sheets_start_of_) {
    sheets_start_.reset();
    sheets_start_of_ = start.positions;
  }
  std::deque<Run> runs;  // a deque: a run stays where it is while the next ones start
  runs.push_back(start_run(start, false, false));
  // The fewest defects any run has reached: a run pauses when it goes switch_after rounds without
  // beating them (for the first run, its own best; a later run must overtake the paused ones).
  DualDefects fewest = runs.back().defects;
  auto overtakes = [&fewest](Run& r) {
    if (!r.defects.fewer_than(fewest)) return false;
    fewest = r.defects;
    return true;
  };
  const int passes = options_.switch_after > 0 ? 2 : 1;
  for (int pass = 0; pass < passes; ++pass) {
    const int stall_limit = pass + 1 < passes ? options_.switch_after : 0;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      Run& r = runs[k];
      if (pass > 0 && can_go_on(r))
        progress(fmt::format("run {} resumes at repair round {}: no later run ended without defects", k + 1,
                             r.round + 1));
      while (can_go_on(r) && !(stall_limit > 0 && r.rounds_behind >= stall_limit)) {
        if (!repair_round(r, r.round)) r.stopped = true;
        ++r.round;
        r.rounds_behind = overtakes(r) ? 0 : r.rounds_behind + 1;
      }
      if (r.best_defects.empty()) return end_runs(runs, k, defects);
      if (can_go_on(r))
        progress(fmt::format("run {} pauses after repair round {}: {} rounds without fewer defects than any run's best",
                             k + 1, r.round, r.rounds_behind));
      if (k + 1 == runs.size() && start_next_run(start, runs)) overtakes(runs.back());
    }
  }
  return end_runs(runs, std::nullopt, defects);
}

// The run's first CVT and the bookkeeping its rounds start from.
Run RemeshDriver::start_run(const Samples& start, bool keep_to_sheets, bool lower_tip_caps) {
  ++runs_;
  Run r;
  r.keep_to_sheets = keep_to_sheets;
  r.lower_tip_caps = lower_tip_caps;
  first_cvt(r, start);
  begin_rounds(r);
  return r;
}

// After the last run started has ended or paused with defects: the second run (samples kept to their
// sheets: the centroid of a cell wrapping a thin wall lies in the wall or in the gap beside it, and
// the closest point of the surface to it is often on the other side, so samples drain from one side
// to the other there), or the third (the second again, with a lower density on the caps of sharp
// tips, once some round of the second met such caps). False when no run is left to start.
bool RemeshDriver::start_next_run(const Samples& start, std::deque<Run>& runs) {
  if (!options_.keep_to_sheets_retry) return false;
  const Run& last = runs.back();
  if (runs.size() == 1) {
    progress(fmt::format("defects left after {} rounds: the run again with every sample kept to its own sheet",
                         last.result.repair_rounds));
    runs.push_back(start_run(start, true, false));
    return true;
  }
  if (runs.size() == 2 && last.saw_tip_caps && options_.tip_caps_retry) {
    progress(fmt::format("defects left after {} rounds of the second run, caps on sharp tips among them: the second "
                         "run again with a lower density on those caps",
                         last.result.repair_rounds));
    runs.push_back(start_run(start, true, true));
    return true;
  }
  return false;
}

// The runs' result: the run that ended without defects (`clean`), or else the one with the fewest
// defects, the earlier run on a tie; the counters of work done cover every run.
RemeshResult RemeshDriver::end_runs(std::deque<Run>& runs, std::optional<std::size_t> clean, DualDefects& defects) {
  RemeshResult result;
  bool first = true;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (clean && k != *clean) continue;
    Run& r = runs[k];
    DualDefects run_defects = r.best_defects;
    RemeshResult again = end_run(r);
    again.path.kept_to_sheets = r.keep_to_sheets;
    again.path.tip_caps_lowered = r.lower_tip_caps;
    if (first) {
      result = std::move(again);
      defects = std::move(run_defects);
      first = false;
    } else {
      keep_if_fewer(std::move(again), std::move(run_defects), result, defects);
    }
  }
  if (clean)  // the other runs' work, which end_run did not count
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (k != *clean) {
        result.repair_rounds += runs[k].result.repair_rounds;
        result.total_iterations += runs[k].result.total_iterations;
        result.diagram_evaluations += runs[k].result.diagram_evaluations;
      }
  return result;
}

// Defects left on a component that holds no more samples than its topology needs, or one more (a
// CVT of four samples on an elongated part is a chain of ring cells, not a tetrahedron): the runs
// again with two more samples on every such component, taken from the components with the most
// to spare (CGAL's bones at 200: 32 samples onto 16 of its 26 bones). Samples do not change
// components otherwise, but for the second run's moves. One defect there is enough: the other
// components' CVTs change too, so one spared now may fail in the new runs.
void RemeshDriver::reallocation_retry() {
  if (kept_defects_.empty() || !options_.reallocation_retry) return;
  Samples moved = initial_;
  const int added = add_samples_to_starved_components(mesh_, kept_.cvt.samples, kept_defects_.where_to_act(), moved);
  if (added == 0) return;
  progress(fmt::format("defects left after {} rounds on a component holding the fewest samples its topology "
                       "needs or one more: the runs again from the start, {} samples moved onto such components",
                       kept_.repair_rounds, added));
  DualDefects again_defects;
  RemeshResult again = runs_from(moved, again_defects);
  again.path.samples_reallocated = added;
  keep_if_fewer(std::move(again), std::move(again_defects), kept_, kept_defects_);
  kept_.path.reallocation_tried = added;
  reallocated_ = std::move(moved);
}

// Defects left after every run: the runs again from the start of the kept result, their repair
// rounds by Lloyd steps (RemeshOptions::lloyd_rounds_retry).
void RemeshDriver::lloyd_rounds_retry() {
  if (kept_defects_.empty() || !options_.lloyd_rounds_retry || options_.repair_rounds == 0 ||
      options_.cvt.optimizer != CvtOptimizer::Lbfgs)
    return;
  progress(fmt::format("defects left after {} rounds: the runs again with Lloyd steps in the repair rounds",
                       kept_.repair_rounds));
  lloyd_rounds_ = true;
  DualDefects again_defects;
  RemeshResult again = runs_from(kept_.path.samples_reallocated > 0 ? reallocated_ : initial_, again_defects);
  again.path.samples_reallocated = kept_.path.samples_reallocated;
  again.path.reallocation_tried = kept_.path.reallocation_tried;
  again.path.lloyd_rounds = true;
  keep_if_fewer(std::move(again), std::move(again_defects), kept_, kept_defects_);
}

// The run's first state: the first CVT of `start`, its dual and the dual's defects, settled. The
// third run takes the second's (kept in sheets_start_).
void RemeshDriver::first_cvt(Run& r, const Samples& start) {
  r.first = options_.cvt;
  r.first.keep_to_sheets = r.keep_to_sheets;
  if (r.keep_to_sheets && sheets_start_) {
    r.result = sheets_start_->result;
    r.defects = sheets_start_->defects;
    r.result.total_iterations = r.result.diagram_evaluations = 0;  // the counters count work done
    return;
  }
  {
    const StageClock::Scope timed(clock_, &RemeshStageTimes::first_cvt);
    r.result.cvt = optimize_cvt(mesh_, start, r.first, nullptr, &index_);
  }
  r.result.total_iterations = r.result.cvt.iterations;
  r.result.diagram_evaluations = r.result.cvt.diagram_evaluations;
  r.result.dual = dual_of(r.result.cvt);
  r.defects = find_defects(r.result.dual, r.result.cvt);
  settle(r.result, r.defects);
  if (r.keep_to_sheets && (options_.tip_caps_retry || options_.lloyd_rounds_retry)) sheets_start_ = Start{r.result, r.defects};
}

// The rounds' options and density, the first CVT's progress line, and its state as the best so far.
void RemeshDriver::begin_rounds(Run& r) {
  r.again = r.first;
  r.again.iterations = options_.repair_iterations;
  r.again.lloyd_warmup = 1;
  if (lloyd_rounds_) r.again.optimizer = CvtOptimizer::Lloyd;
  if (r.again.triangle_density.empty())
    r.again.triangle_density = options_.cvt.density == CvtDensity::Curvature
                                   ? curvature_density(mesh_, initial_.size())
                                   : std::vector<double>(mesh_.triangle_count(), 1.0);
  r.base_density = r.again.triangle_density;  // before any round changes it
  progress(fmt::format("{}CVT: {} iterations, {} diagrams, energy {:.6g}; the dual has {}",
                       r.lower_tip_caps ? "third run, from the second's first " : r.keep_to_sheets ? "second run, " : "",
                       r.result.cvt.iterations, r.result.cvt.diagram_evaluations, r.result.cvt.energy,
                       r.defects.describe()));
  r.best = r.result;
  r.best_defects = r.defects;
  r.best_density = r.first.triangle_density;
}

// One repair round: the density lowered on the cells that are to grow and raised around the other
// defects and their neighbours, then CVT iterations from the state the last round left (see
// optimise_round). False when the raise would have been uniform: the run stops there.
bool RemeshDriver::repair_round(Run& r, int round) {
  r.saw_tip_caps = r.saw_tip_caps || !r.defects.tip_caps.empty();
  const std::vector<int> lowered = cells_to_lower(r);
  std::vector<int> raised;
  if (lowered.empty())
    raised = r.defects.where_to_act();
  else
    std::set_difference(r.defects.topological.begin(), r.defects.topological.end(), lowered.begin(), lowered.end(),
                        std::back_inserter(raised));
  if (!lowered.empty()) lower_density(r.result.cvt.diagram, lowered, options_.repair_factor, r.again.triangle_density);
  const std::size_t raised_triangles =
      raised.empty() ? 0 : raise_density(r.result.cvt.diagram, raised, options_.repair_factor, r.again.triangle_density);
  // Every cell at a defect or next to one, and none lowered: the surface is thinner than the
  // cells (or has more handles than they can hold) everywhere, which only more vertices mend.
  // (The density raised here goes with the run.)
  if (lowered.empty() && raised_triangles == r.again.triangle_density.size()) {
    ++saturated_runs_;
    progress(fmt::format("repair round {}: every cell is at a defect or next to one, and a density raised "
                         "everywhere changes nothing: the run stops",
                         round + 1));
    return false;
  }
  ++r.result.repair_rounds;
  progress(lowered.empty()
               ? fmt::format("repair round {} of {}: density x{} around {} samples and their neighbours", round + 1,
                             options_.repair_rounds, options_.repair_factor, raised.size())
               : fmt::format("repair round {} of {}: density x{} around {} samples and their neighbours, /{} in "
                             "{} cells at sharp corners or tips",
                             round + 1, options_.repair_rounds, options_.repair_factor, raised.size(),
                             options_.repair_factor, lowered.size()));
  optimise_round(r, raised, lowered, round);
  return true;
}

// The cells whose density a round lowers: cornered cells, and in the third run caps on sharp tips
// (before it they are left to the raise, which keeps more of the tip: lowered from the first run,
// triceratops 1000's Hausdorff distance went 0.47 -> 2.11 %). Both are topological defects, which
// are acted on first.
std::vector<int> RemeshDriver::cells_to_lower(Run& r) const {
  std::vector<int> lowered = r.defects.cornered;
  if (!r.lower_tip_caps) return lowered;
  lowered.insert(lowered.end(), r.defects.tip_caps.begin(), r.defects.tip_caps.end());
  // No better state for kRingLoweringAfter rounds: from then on the rings round the caps are
  // lowered too, so a cap can take the narrowing part below it (a larger cap).
  r.lower_rings = r.lower_rings || r.rounds_without_progress >= kRingLoweringAfter;
  if (r.lower_rings) lowered.insert(lowered.end(), r.defects.tip_cap_rings.begin(), r.defects.tip_cap_rings.end());
  std::sort(lowered.begin(), lowered.end());
  lowered.erase(std::unique(lowered.begin(), lowered.end()), lowered.end());
  return lowered;
}

// The round's CVT with the changed density, from the state the last round left; its dual and
// defects, settled; the state kept as the best when it has fewer defects.
void RemeshDriver::optimise_round(Run& r, const std::vector<int>& raised, const std::vector<int>& lowered,
                                  int round) {
  RemeshResult& result = r.result;
  // The second run also moves samples into the defect cells (the first, whose raised density
  // suffices on the 20 rows of docs/results.md, leaves them to the CVT: moving them there too took
  // elk 516 to Qmin 0.554, docs/decisions.md); not into the cells that are to grow.
  const bool moved = r.keep_to_sheets && !raised.empty() &&
                     relocate_samples(result.cvt.diagram, mesh_, r.again.triangle_density, raised, result.cvt.samples) > 0;
  // The diagram of the samples is the last one computed: the density changed, the diagram not.
  // RemeshOptions::repair: every sample, or those near the cells acted on (remesh/local_repair.h).
  {
    const StageClock::Scope timed(clock_, &RemeshStageTimes::round_cvts);
    if (options_.repair == RepairScope::Whole) {
      result.cvt = optimize_cvt(mesh_, result.cvt.samples, r.again, moved ? nullptr : &result.cvt.diagram, &index_);
    } else {
      std::vector<int> acted_on(raised);
      acted_on.insert(acted_on.end(), lowered.begin(), lowered.end());
      LocalRound local;
      result.cvt = repair_round_cvt(mesh_, result.cvt.samples, result.cvt.diagram, acted_on, r.again,
                                    options_.local_repair, round, r.rounds_without_progress, index_, &local);
      progress(*local.whole_because
                   ? fmt::format("repair round {}: a whole CVT ({}{})", round + 1, local.whole_because,
                                 local.window ? fmt::format(": {} of {} samples", local.window, result.cvt.samples.size()) : "")
                   : fmt::format("repair round {}: {} samples move in a window of {}", round + 1, local.moving, local.window));
    }
  }
  result.total_iterations += result.cvt.iterations;
  result.diagram_evaluations += result.cvt.diagram_evaluations;
  result.dual = dual_of(result.cvt);
  r.defects = find_defects(result.dual, result.cvt);
  result.path.fitted_in_rounds = false;
  result.fit = {};
  result.untangle = {};
  settle(result, r.defects);
  const bool better = r.defects.fewer_than(r.best_defects);
  // How long the run went without a better state before this one (RemeshOptions::switch_after).
  progress(fmt::format("repair round {}: {} iterations, energy {:.6g}{}; the dual has {}", round + 1,
                       result.cvt.iterations, result.cvt.energy,
                       better && r.rounds_without_progress > 0
                           ? fmt::format(" (a better state after {} rounds without one)", r.rounds_without_progress)
                           : "",
                       r.defects.describe()));
  if (better) {
    r.best_defects = r.defects;
    r.best = result;
    r.best_density = r.again.triangle_density;
    r.rounds_without_progress = 0;
  } else {
    ++r.rounds_without_progress;
  }
}

// The run's result: its best state, polished and eased when its dual has no defect, with the
// counters of the whole run. A state whose crossings were untangled (settle) is kept as it is.
RemeshResult RemeshDriver::end_run(Run& r) {
  const bool clean = r.best_defects.empty() && !r.best.path.fitted_in_rounds;
  if (clean) polish(r.best, r.best_density, r);
  if (clean && options_.ease_iterations > 0 && r.result.repair_rounds > 0 &&
      r.best_density.size() == r.base_density.size())
    ease(r);
  r.best.repair_rounds = r.result.repair_rounds;
  r.best.total_iterations = r.result.total_iterations;
  r.best.diagram_evaluations = r.result.diagram_evaluations;
  return std::move(r.best);
}

// A state without defects gets its Lloyd steps (RemeshOptions::polish_steps), with the density it
// was optimised for; they stand if its dual still has no defect. Their work is counted in the run.
void RemeshDriver::polish(RemeshResult& state, const std::vector<double>& density, Run& r) {
  const StageClock::Scope timed(clock_, &RemeshStageTimes::polish_ease);
  if (options_.polish_steps == 0 || r.first.optimizer != CvtOptimizer::Lbfgs) return;
  CvtOptions lloyd = r.first;
  lloyd.optimizer = CvtOptimizer::Lloyd;
  lloyd.iterations = options_.polish_steps;
  lloyd.triangle_density = density;
  CvtResult polished = optimize_cvt(mesh_, state.cvt.samples, lloyd, &state.cvt.diagram, &index_);
  r.result.total_iterations += polished.iterations;
  r.result.diagram_evaluations += polished.diagram_evaluations;
  DualMesh dual = dual_of(polished);
  DualDefects after = find_defects(dual, polished);
  progress(fmt::format("{} Lloyd step{} on the samples: the dual has {}{}", polished.iterations,
                       polished.iterations == 1 ? "" : "s", after.describe(),
                       after.empty() ? "" : ", the state before them stands"));
  if (!after.empty()) return;
  // The kept CVT is the run and its polish: its history, iterations and evaluations cover both.
  polished.energy_history.insert(polished.energy_history.begin(), state.cvt.energy_history.begin(),
                                 state.cvt.energy_history.end() - 1);
  polished.iterations += state.cvt.iterations;
  polished.diagram_evaluations += state.cvt.diagram_evaluations;
  polished.line_search_stopped = state.cvt.line_search_stopped;
  polished.time_s += state.cvt.time_s;
  state.cvt = std::move(polished);
  state.dual = std::move(dual);
  state.path.polished = true;
}

// A state the repair rounds left without defects is optimised again with the raised density eased
// part of the way back (RemeshOptions::ease_iterations), and takes its Lloyd steps too; it stands
// if its dual has no defect and a better worst triangle than the state before.
void RemeshDriver::ease(Run& r) {
  const StageClock::Scope timed(clock_, &RemeshStageTimes::polish_ease);
  RemeshResult& best = r.best;
  CvtOptions eased = r.again;
  eased.iterations = options_.ease_iterations;
  for (std::size_t t = 0; t < r.base_density.size(); ++t)
    eased.triangle_density[t] =
        r.base_density[t] * std::pow(r.best_density[t] / r.base_density[t], 1 - options_.ease_fraction);
  CvtResult eased_cvt = optimize_cvt(mesh_, best.cvt.samples, eased, &best.cvt.diagram, &index_);
  // The candidate is `best` with the eased CVT: copied with its CVT moved out, and back.
  CvtResult best_cvt = std::move(best.cvt);
  RemeshResult candidate = best;
  best.cvt = std::move(best_cvt);
  candidate.cvt = std::move(eased_cvt);
  candidate.path.polished = false;
  r.result.total_iterations += candidate.cvt.iterations;
  r.result.diagram_evaluations += candidate.cvt.diagram_evaluations;
  candidate.dual = dual_of(candidate.cvt);
  const DualDefects after = find_defects(candidate.dual, candidate.cvt);
  progress(fmt::format("{} iterations with the density eased {}% of the way back: the dual has {}{}",
                       candidate.cvt.iterations, std::lround(100 * options_.ease_fraction), after.describe(),
                       after.empty() ? "" : ", the state before them stands"));
  if (!after.empty()) return;
  polish(candidate, eased.triangle_density, r);
  const double q_before = shape_metrics(best.dual.positions, best.dual.triangles).q_min;
  const double q_after = shape_metrics(candidate.dual.positions, candidate.dual.triangles).q_min;
  const bool better = q_after > q_before;
  progress(better ? fmt::format("the eased state: worst triangle {:.3f} -> {:.3f}, kept", q_before, q_after)
                  : fmt::format("the eased state: worst triangle {:.3f}, not above {:.3f}: the state before stands",
                                q_after, q_before));
  if (!better) return;
  // The history, iterations and evaluations of the kept CVT cover the state it started from.
  std::vector<double>& history = candidate.cvt.energy_history;
  history.insert(history.begin(), best.cvt.energy_history.begin(), best.cvt.energy_history.end() - 1);
  candidate.cvt.iterations += best.cvt.iterations;
  candidate.cvt.diagram_evaluations += best.cvt.diagram_evaluations;
  candidate.cvt.time_s += best.cvt.time_s;
  candidate.path.eased = true;
  best = std::move(candidate);
}

// A dual whose only defect is crossings is fitted and untangled; the crossings left, if any, are
// the ones to act on.
void RemeshDriver::settle(RemeshResult& r, DualDefects& d) const {
  if (!options_.untangle || !d.topological.empty() || !d.euler_ok || d.crossing.empty()) return;
  const StageClock::Scope timed(clock_, &RemeshStageTimes::round_untangle);
  // The crossings found in `d` (and then by the fitting) are not searched for again.
  if (options_.fit) r.fit = fit_to_surface(r.cvt.diagram, mesh_, r.dual, options_.fit_options, &index_, &d.crossing_pairs);
  r.untangled_from = r.dual;
  r.untangle = untangle_crossings(mesh_, r.cvt.samples, r.dual, inherited_, options_.untangle_options,
                                  options_.fit ? &r.fit.crossings : &d.crossing_pairs);
  r.path.fitted_in_rounds = true;
  std::set<int> left;
  for (const auto& [s, t] : r.untangle.remaining)
    for (int u : {s, t}) left.insert(r.dual.triangles[u].begin(), r.dual.triangles[u].end());
  d.crossing.assign(left.begin(), left.end());
}

// The kept state, unless the rounds fitted and untangled it already: its worst triangles relaxed
// (RemeshOptions::relax), its vertices fitted to the surface and its crossings untangled.
void RemeshDriver::fit() {
  if (kept_.path.fitted_in_rounds) return;
  const StageClock::Scope timed(clock_, &RemeshStageTimes::fit);
  RemeshResult& result = kept_;
  // `kept_defects_` are those of result.dual (found before the fitting, which is not done yet).
  // `kept_defects_.crossing_pairs` are those of result.dual as long as no vertex moved.
  const std::vector<std::pair<int, int>>* crossings = &kept_defects_.crossing_pairs;
  if (options_.relax.rounds > 0) {
    const double before = shape_metrics(result.dual.positions, result.dual.triangles).q_min;
    result.relax = relax_worst_triangles(mesh_, index_, result.cvt.samples, result.dual, options_.relax, crossings);
    crossings = &result.relax.crossings;
    progress(fmt::format("{} vertices of the worst triangles moved towards their neighbours: worst triangle {:.3f} -> "
                         "{:.3f}",
                         result.relax.moved, before, shape_metrics(result.dual.positions, result.dual.triangles).q_min));
  }
  if (options_.fit) {
    progress("fitting the vertices to the surface");
    result.fit = fit_to_surface(result.cvt.diagram, mesh_, result.dual, options_.fit_options, &index_, crossings);
  }
  if (options_.untangle) {
    const StageClock::Scope untangling(clock_, &RemeshStageTimes::untangle);
    result.untangled_from = result.dual;
    result.untangle = untangle_crossings(mesh_, result.cvt.samples, result.dual, inherited_, options_.untangle_options,
                                         options_.fit ? &result.fit.crossings : crossings);
  }
}

// Crossings left in the state kept: it is untangled again from its fitted vertices with each reach
// of RemeshOptions::final_max_moves, the fewest crossings kept.
void RemeshDriver::untangle_further() {
  const StageClock::Scope timed(clock_, &RemeshStageTimes::untangle);
  for (double reach : options_.final_max_moves) {
    if (!options_.untangle || kept_.untangle.remaining.empty()) break;
    UntangleOptions further = options_.untangle_options;
    further.max_move = reach;
    DualMesh dual = kept_.untangled_from;
    UntangleResult untangled = untangle_crossings(mesh_, kept_.cvt.samples, dual, inherited_, further,
                                                  options_.fit ? &kept_.fit.crossings : nullptr);
    if (untangled.crossings_after < kept_.untangle.crossings_after) {
      kept_.dual = std::move(dual);
      kept_.untangle = std::move(untangled);
    }
  }
}

// The kept state with the runs' account: how many, whether the repair saturated, the defects left.
RemeshResult RemeshDriver::finish() {
  kept_.untangled_from = {};
  // Only when no run got past such a round: a run that went on (the third, lowering the density on
  // caps at sharp tips) and ran out of rounds may mend with more rounds, not only more vertices.
  kept_.path.repair_saturated = saturated_runs_ == runs_ && !kept_defects_.empty();
  kept_.path.runs = runs_;
  kept_.defects = std::move(kept_defects_);
  kept_.time_s = seconds_since(start_);
  clock_.charge();
  kept_.stage_cpu_s = times_;
  return std::move(kept_);
}

}  // namespace

RemeshResult remesh_cvt(const SurfaceMesh& reference, const SurfaceMesh& mesh, const Samples& initial,
                        const RemeshOptions& options) {
  check_remesh_input(reference, mesh, initial, options);
  RemeshDriver driver(reference, mesh, initial, options);
  driver.runs();
  driver.reallocation_retry();
  driver.lloyd_rounds_retry();
  driver.fit();
  driver.untangle_further();
  return driver.finish();
}

}  // namespace lrvd
