// The parts of verify_diagram (internal to verification/): what its workers share, and the checks of
// one triangle at a time on the triangle's own copy of its vertices ((1), (3), (4), (5)), which list
// the polygon sides the checks along mesh edges read (diagram_edges.h).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "verification/diagram_geometry.h"
#include "verification/triangle_enclosures.h"

namespace lrvd::verify_detail {

class Near;

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

//! The checks of one triangle at a time, on its own copy of its distinct vertices: (4) and (5),
//! (3) for every polygon vertex, (1) for the samples located on it; lists the polygon sides along
//! its edges for the edge pass.
class TriangleChecker {
 public:
  TriangleChecker(DiagramInput& in, TriangleChunk& out) : in_(in), d_(in.d), out_(out) {}
  void check_triangles(int begin, int end);

 private:
  // diagram_triangle.cpp: the triangle's vertices, the driver, the sides along its edges.
  void check_triangle(int t);
  int whole_rotation(const Triangle& tri) const;
  void load_corners(const Triangle& tri);
  void load_vertices(const Triangle& tri);
  void load_whole(const Triangle& tri, int r);
  bool check_whole(const Frame& f);
  void list_whole_sides(const Triangle& tri, int r);
  int local_index(const SymbolicVertex& q, const Triangle& tri);
  int add_local(const SymbolicVertex& q, const Triangle& tri);
  void make_points(const Triangle& tri);

  void load_frame(const Frame& f);
  void check_polygons(int t, const Triangle& tri, const Frame& f);
  void check_structure(int t, const Frame& f);
  void report_unusable(int t, int p);
  void list_sides(const Triangle& tri);
  void count_vertices();
  // diagram_polygons.cpp: (4) and (5).
  std::string polygon_problem(int p, const Triangle& tri, const Frame& f);
  bool vertex_inside(int id, const FrameVertex& x, const Frame& f);
  std::string convexity_problem(int p, const Frame& f);
  bool bounded_by_triangle(const Triangle& tri);
  bool bounded_by_triangle_multisets(const Triangle& tri);
  void check_area_sum(int t, const Frame& f);
  void check_overlaps(int t, const Frame& f);
  bool separated(int p, int q, const Frame& f) const;
  // diagram_equidistance.cpp: (3).
  void check_equidistance(int t);
  void equidistance_present(int t, int p);
  void equidistance_near(int t, int p, const Near& near);
  void report_unequal(int t, const SymbolicVertex& q, int i, int closer, int equidistant);
  // diagram_samples.cpp: (1).
  void check_samples(int t, const Triangle& tri, const Frame& f);
  std::string sample_problem(int i, int t, const Triangle& tri, const Frame& f);
  bool contains_point(int p, const ExactVertex& x, const Frame& f);

  int local_of(int p, int k) const { return of_[first_[p - begin_] + k]; }
  const ExactVertex& vertex(int p, int k) const { return local_[local_of(p, k)]; }
  const FrameVertex* frame_vertices(int p) const { return frame_.data() + first_[p - begin_]; }
  bool usable(int p) const { return usable_[p - begin_]; }
  Sign& area(int p) { return area_sign_[p - begin_]; }

  DiagramInput& in_;
  const Diagram& d_;
  TriangleChunk& out_;
  int begin_ = 0, end_ = 0;  // the triangle's polygons

  // The triangle's distinct vertices (its corners first), each with what the checks ask of it once.
  struct LocalVertex {
    std::uint64_t key = 0;     // corner_key / edge_key / irregular_key, when edges != 0
    std::uint8_t edges = 0;    // the triangle's edges it lies on by definition (FrameVertex::edges)
    std::uint8_t kind = 0;     // kMeshVertex, kTypeB, kTypeC (defined by this triangle), else other
    bool defined = false;      // a point of this triangle by definition (defined_on_triangle)
    std::int8_t inside = -1;   // exactly inside the triangle: 1, 0, or -1 not yet decided
    bool ends_side = false;    // type B: ends a usable polygon's side along its edge
  };
  static constexpr std::uint8_t kMeshVertex = 1, kTypeB = 2, kTypeC = 3;
  std::vector<SymbolicVertex> local_q_;
  std::vector<ExactVertex> local_;  // the points of local_q_ (and some left from earlier triangles)
  std::vector<LocalVertex> info_;
  TriangleEnclosures enclosures_;
  std::vector<int> lookup_;  // with many distinct vertices: an open-addressing table of local ids
  std::vector<int> of_;      // per polygon vertex of the triangle: its local id, -1 if malformed
  std::vector<int> first_;   // per polygon of the triangle: where its vertices start in of_ and frame_
  std::vector<FrameVertex> frame_;
  std::vector<char> usable_;
  std::vector<Sign> area_sign_;
  std::array<FrameVertex, 3> corner_frame_;
  std::array<const ExactVertex*, 3> corner_{};

  std::vector<const ExactVertex*> points_;
  struct DirectedEdge {
    int from, to;                // local ids, from < to
    int from_vertex, to_vertex;  // indices into Diagram::vertices
    int direction;               // +1 if a polygon runs from -> to, -1 if to -> from
    std::uint8_t edges;          // the triangle's edges both ends lie on by definition
  };
  std::vector<DirectedEdge> edges_;
  std::vector<std::array<int, 3>> along_bc_;
  // bounded_by_triangle: the sides' counts per pair of vertices and their flow along each edge;
  // with many vertices, the sides off the mesh edges by direction, the starts and ends along each.
  static constexpr std::size_t kCountsUpTo = 32;
  std::array<int, kCountsUpTo * kCountsUpTo> net_{};
  std::array<int, 3 * kCountsUpTo> flow_{};
  std::vector<std::size_t> touched_;
  std::vector<std::uint64_t> forward_, backward_;
  std::array<std::vector<int>, 3> from_, to_;
  // check_equidistance: the cells with a usable polygon in the triangle, e_j(q) for each local
  // vertex q and cell j (made on first use), the cells a vertex is compared with (with many
  // cells).
  std::vector<int> present_;
  std::vector<std::uint32_t> labels_;  // per local vertex: the bits of present_ that are its labels
  std::vector<Interval> e_;
  std::vector<std::uint32_t> e_made_;
  std::uint32_t stamp_ = 0;
  std::vector<int> compared_;
  // check_overlaps: the polygons to compare; above kAllPairsUpTo of them, their boxes in the frame.
  struct FrameBox {
    int polygon;
    double u_lo, u_hi, v_lo, v_hi;
    bool apart(const FrameBox& o) const { return u_hi < o.u_lo || o.u_hi < u_lo || v_hi < o.v_lo || o.v_hi < v_lo; }
  };
  std::vector<int> candidates_;
  std::vector<FrameBox> boxes_;
  std::vector<std::pair<int, int>> pairs_;
  std::vector<std::array<int, 5>> along_;  // list_sides: the polygon sides along the triangle's edges
};

//! Above this many polygons (or cells) in a triangle, (3) and (4) compare only the pairs a
//! certified bound does not tell apart.
constexpr std::size_t kAllPairsUpTo = 16;

//! Whether the interval filters alone show the polygon (its n vertices in the frame) strictly convex
//! and counterclockwise; false leaves the decision to the exact test. \pre the rounding mode is upward.
bool strictly_convex(const FrameVertex* fv, int n, const Frame& f);

//! Equal to SymbolicVertex::mesh_vertex(q.v[0]), field by field.
inline bool is_mesh_vertex(const SymbolicVertex& q) {
  return q.type == SymbolicVertex::Type::A && q.v[1] == -1 && q.v[2] == -1 && q.label[0] == -1 && q.label[1] == -1 &&
         q.label[2] == -1;
}

//! A symbolic vertex whose indices are in range and whose labels are distinct.
bool well_formed(const SymbolicVertex& q, int vertex_count, int sample_count);

}  // namespace lrvd::verify_detail
