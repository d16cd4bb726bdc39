// The seconds the reports' time fields give.
#pragma once

#include <chrono>

namespace lrvd {

//! Seconds on std::chrono::steady_clock since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace lrvd
