// Small helpers the benchmarks share: comma-separated argument lists, process CPU time, a limit
// of the worker threads.
#pragma once

#include <time.h>

#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <tbb/global_control.h>

namespace lrvd::bench {

//! "a,b,c" -> {"a", "b", "c"}.
inline std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

//! CPU time of the process (all threads): with one thread, a load-independent measure of the work.
inline double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

//! The worker threads limited to `threads` while the result lives; no limit for 0 or less (every core).
inline std::unique_ptr<tbb::global_control> limit_threads(int threads) {
  if (threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
}

}  // namespace lrvd::bench
