// The seconds the reports' time fields give.
#pragma once

#include <chrono>
#include <ctime>

namespace lrvd {

//! Seconds on std::chrono::steady_clock since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

//! CPU seconds the process has used so far, all its threads together: on a machine other jobs
//! share, a single-threaded stage's CPU time drifts less than its wall time.
inline double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace lrvd
