// The entries of the LRVD's region growing (paper §3.2, voronoi/lrvd.cpp), in a header of their
// own so that the tests can check their order.
#pragma once

#include <cstdint>
#include <cstring>

namespace lrvd::detail {

// A sample's region reaching a vertex during the region growing of §3.2, ordered by (power
// distance, sample, vertex). The three are one 128-bit key, the distance's bits on top mapped so
// that unsigned order is the doubles' order: the heap's comparisons are then one integer
// comparison each, without the branches a distance, then sample, then vertex test takes (which
// the processor guesses wrong half the time deep in the heap).
struct VertexEntry {
  unsigned __int128 key;

  VertexEntry() = default;
  VertexEntry(double d, int sample, int vertex) {
    std::uint64_t bits;
    const double positive_zero = d + 0.0;  // -0 as +0, which the doubles' order does not tell apart
    std::memcpy(&bits, &positive_zero, sizeof bits);
    bits = bits >> 63 ? ~bits : bits | (std::uint64_t{1} << 63);
    key = static_cast<unsigned __int128>(bits) << 64 |
          static_cast<std::uint64_t>(static_cast<std::uint32_t>(sample)) << 32 | static_cast<std::uint32_t>(vertex);
  }
  int sample() const { return static_cast<int>(static_cast<std::uint32_t>(key >> 32)); }
  int vertex() const { return static_cast<int>(static_cast<std::uint32_t>(key)); }
  bool operator>(const VertexEntry& o) const { return key > o.key; }
};

}  // namespace lrvd::detail
