// The entry points the fuzz targets (fuzz_target.cpp) and the unit tests' replay of their findings
// (tests/test_hostile_inputs.cpp) share: each takes arbitrary bytes and either returns or throws
// something other than InputError, which is a finding.
#pragma once

#include <cstddef>
#include <cstdint>

namespace lrvd::fuzz {

//! The first byte chooses: bits 0-1 the extension (.off, .obj, .ply, .stl: ascii and binary PLY and
//! STL are told apart by the reader), bit 2 --repair, bit 3 read_polygon_soup (vertices without
//! faces allowed, a PLY's face colours) instead of read_mesh. The rest is the file.
void mesh_file(const std::uint8_t* data, std::size_t size);

//! The first byte's bit 0: the rest is a --points file (read, then located on an octahedron with
//! its weights) or a --weights file.
void point_files(const std::uint8_t* data, std::size_t size);

//! A tiny mesh, then its LRVD and the diagram's verification, as `lrvd compute` does. Bytes:
//! sample count (1 + b % 16), seed, vertex count (4 + b % 13), triangle count (4 + b % 29), a
//! power-of-two scale (b - 128, within +-60), then 16-bit little-endian coordinates, 3 a vertex,
//! then one byte a corner (modulo the vertex count); missing bytes are 0. The mesh goes through
//! an OFF file and read_mesh. A diagram that fails its verification throws std::logic_error.
void compute(const std::uint8_t* data, std::size_t size);

//! The corpus folders under tests/data/fuzz/ and the entry each replays through.
struct Target {
  const char* name;
  void (*entry)(const std::uint8_t*, std::size_t);
};
extern const Target kTargets[3];

}  // namespace lrvd::fuzz
