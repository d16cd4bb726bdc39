// One libFuzzer target: LRVD_FUZZ_TARGET (0, 1, 2) names its entry in fuzz::kTargets.
// A program of its own: no header.
#include <cstddef>
#include <cstdint>

#include "fuzz_entry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  lrvd::fuzz::kTargets[LRVD_FUZZ_TARGET].entry(data, size);
  return 0;
}
