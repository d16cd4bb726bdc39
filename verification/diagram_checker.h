// What the passes of verify_diagram share (internal to verification/): the input every worker reads,
// and what the triangle pass (diagram_triangle.h) leaves for the edge pass (diagram_edges.h).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "verification/diagram_geometry.h"

namespace lrvd::verify_detail {

//! What every worker of one verification reads, and the per-polygon state the triangle pass
//! leaves for the edge pass (each polygon written by the worker of its triangle).
struct DiagramInput {
  DiagramInput(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram, const VerifyOptions& options);

  const SurfaceMesh& mesh;
  const Samples& samples;
  const Diagram& d;
  const VerifyOptions& options;
  SymbolicContext context;
  RationalStore rationals;       //!< every vertex's rationals, made once, whichever triangle needs them
  std::vector<SiteTerms> terms;  //!< of every site, for (3)
  //! The samples located on triangle t, in increasing order: sample_order[sample_first[t]] ..
  //! sample_order[sample_first[t + 1] - 1]. A sample on no triangle is in none.
  std::vector<int> sample_first, sample_order;
  std::vector<std::uint8_t> polygon_state;  //!< kUsable, kPiece

  //! The identity along a mesh edge of a vertex with edge bits that is neither a mesh vertex nor
  //! a type B vertex of that edge (a type A vertex with stray fields: a malformed diagram).
  std::uint64_t irregular_key(const SymbolicVertex& q) const;

 private:
  mutable tbb::concurrent_unordered_map<SymbolicVertex, std::uint64_t, SymbolicVertexHash> irregular_;
  mutable std::atomic<std::uint64_t> next_irregular_{0};
};

//! DiagramInput::polygon_state bits. Usable: its cell is a sample and its vertices are well formed
//! and name points (the geometric checks read it). Piece: usable, with positive area (only those
//! make up a cell's region: a zero-area polygon is the unperturbed limit of an infinitesimal
//! sliver at a degenerate input, no piece of its own).
constexpr std::uint8_t kUsable = 1, kPiece = 2;

//! A vertex's identity along a mesh edge, the same from both triangles of the edge: a mesh vertex
//! by its index, a type B vertex of the edge by its labels (its edge is the mesh edge), any other
//! by DiagramInput::irregular_key.
inline std::uint64_t corner_key(int v) { return std::uint64_t{1} << 63 | static_cast<std::uint32_t>(v); }
inline std::uint64_t edge_key(const SymbolicVertex& q) {
  return static_cast<std::uint64_t>(static_cast<std::uint32_t>(q.label[0])) << 31 | static_cast<std::uint32_t>(q.label[1]);
}

//! Whether a polygon side's ends are one point, as far as the interval filter tells.
enum class SideLength : std::uint8_t { Zero, Positive, Undecided };

//! A polygon side along an edge of its triangle: its ends' identities (lo <= hi), the polygon
//! and where the side starts in it.
struct SideSegment {
  std::uint64_t lo, hi;
  int cell, polygon;
  int k;                 //!< the side runs from the polygon's vertex k to vertex k + 1
  std::uint8_t edge;     //!< the triangle's edge e, from corner e to corner e + 1
  SideLength length;
  bool same_split(const SideSegment& o) const { return lo == o.lo && hi == o.hi && cell == o.cell; }
};

//! The triangle pass's results for one chunk of kCheckChunk triangles.
struct TriangleChunk {
  DiagramVerification part;  //!< (3), (4), (5); rational_points: the samples'
  std::vector<std::pair<int, std::string>> sample_failures;  //!< (1): sample, offender
  std::vector<SideSegment> sides;  //!< the sides of every usable polygon along its triangle's edges
  //! Per triangle of the chunk and edge e, where its sides along e start (3 t + e); one more at the end.
  std::vector<int> first_side;
  //! Per triangle and edge: its distinct type B vertices on the edge, -1 when some of them ends no
  //! side along it (then the edge pass counts them from the polygons).
  std::vector<std::array<int, 3>> b_count;
  std::int64_t c_count = 0;  //!< distinct type C vertices of the triangle defined by it, summed
  bool irregular = false;    //!< some vertex not counted above: a vertex of another triangle or edge
};

}  // namespace lrvd::verify_detail
