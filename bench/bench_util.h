// Small helpers the benchmarks share: comma-separated argument lists and process CPU time.
#pragma once

#include <time.h>

#include <sstream>
#include <string>
#include <vector>

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

}  // namespace lrvd::bench
