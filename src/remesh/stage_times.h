// Where a remesh spends its time: CPU seconds of the process (every thread) per stage of the
// remesh driver (remesh/remesh.h), each second charged to the innermost stage running.
#pragma once

#include "common/timing.h"

namespace lrvd {

//! CPU seconds (process, all threads) of remesh_cvt by stage; a second is charged to one stage only.
struct RemeshStageTimes {
  double first_cvt = 0;      //!< the first CVT of each run
  double round_cvts = 0;     //!< the repair rounds' CVTs (whole or in a window)
  double defects = 0;        //!< the duals and their defect searches, after every CVT
  double round_untangle = 0; //!< fitting and untangling of crossings-only states during the rounds
  double polish_ease = 0;    //!< the Lloyd steps and the eased-density CVTs of the kept states
  double fit = 0;            //!< the final relaxation and fitting
  double untangle = 0;       //!< the final untangling, with its longer reaches
  double other = 0;          //!< the rest (indexes, moves of densities and samples, copies)
  double total() const {
    return first_cvt + round_cvts + defects + round_untangle + polish_ease + fit + untangle + other;
  }
};

//! Charges CPU time to one field of RemeshStageTimes at a time: a StageClock::Scope switches to its
//! field for its lifetime and back to the enclosing one after.
class StageClock {
 public:
  explicit StageClock(RemeshStageTimes& times) : times_(times), current_(&times.other), since_(process_cpu_seconds()) {}
  ~StageClock() { charge(); }
  StageClock(const StageClock&) = delete;
  StageClock& operator=(const StageClock&) = delete;

  class Scope {
   public:
    Scope(StageClock& clock, double RemeshStageTimes::*field) : clock_(clock), previous_(clock.current_) {
      clock_.charge();
      clock_.current_ = &(clock_.times_.*field);
    }
    ~Scope() {
      clock_.charge();
      clock_.current_ = previous_;
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StageClock& clock_;
    double* previous_;
  };

  //! The time since the last switch, charged to the current stage.
  void charge() {
    const double now = process_cpu_seconds();
    *current_ += now - since_;
    since_ = now;
  }

 private:
  RemeshStageTimes& times_;
  double* current_;
  double since_;
};

}  // namespace lrvd
