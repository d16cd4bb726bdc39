// Exact clipping of a mesh triangle by bisectors (paper §3.4): the polygon of one cell among a
// list of candidate cells, by Sutherland-Hodgman on symbolic vertices with exact side tests.
#pragma once

#include <cstdint>
#include <vector>

#include "predicates/symbolic_vertex.h"

namespace lrvd {

class SurfaceMesh;

//! The part of triangle t closer to cell k than to every other cell of `others` (k itself is
//! skipped if listed). Result in `polygon` (counterclockwise, possibly empty); `scratch` is reused.
void clip_triangle(const SurfaceMesh& mesh, int t, int k, const int* others, int other_count,
                   const SymbolicContext& ctx, std::vector<SymbolicVertex>& polygon,
                   std::vector<SymbolicVertex>& scratch);

//! The edges of `triangle` (bit e: edge (corner e, corner e+1)) that vertex q lies on: two for a
//! mesh vertex at one of its corners, one for a type B vertex on one of its edges, none otherwise.
inline unsigned edge_mask(const SymbolicVertex& q, const std::array<int, 3>& triangle) {
  unsigned mask = 0;
  if (q.type == SymbolicVertex::Type::A) {
    for (int c = 0; c < 3; ++c)
      if (triangle[c] == q.v[0]) mask = (1u << c) | (1u << ((c + 2) % 3));
  } else if (q.type == SymbolicVertex::Type::B) {
    // Edge e joins corners e and e + 1: find the corners of the vertex's edge.
    int c0 = -1, c1 = -1;
    for (int c = 0; c < 3; ++c) {
      if (triangle[c] == q.v[0]) c0 = c;
      if (triangle[c] == q.v[1]) c1 = c;
    }
    if (c0 >= 0 && c1 >= 0) mask = 1u << ((c0 + 1) % 3 == c1 ? c0 : c1);
  }
  return mask;
}

//! Edges of `triangle` that a polygon reaches (`reach`: some vertex on the edge) and that it has a
//! side along (`along`: two consecutive vertices on the edge, a segment of positive length).
struct PolygonEdges {
  unsigned reach = 0, along = 0;
};
inline PolygonEdges polygon_edges(const SymbolicVertex* v, int count, const std::array<int, 3>& triangle) {
  PolygonEdges out;
  if (count == 0) return out;
  const unsigned first = edge_mask(v[0], triangle);
  unsigned previous = first;
  for (int k = 1; k <= count; ++k) {
    const unsigned current = k == count ? first : edge_mask(v[k], triangle);
    out.reach |= current;
    out.along |= previous & current;
    previous = current;
  }
  return out;
}

//! polygon_edges(...).along of the unperturbed geometry: the edges the polygon has a side of
//! positive exact length along. A side whose ends coincide there (coincide_unperturbed, only ever
//! at an exact tie the perturbation resolved) counts for none.
unsigned along_in_the_limit(const SymbolicVertex* v, int count, const std::array<int, 3>& triangle,
                            const SymbolicContext& ctx);

//! Clips an existing polygon of cell k in triangle t by bisector(k, l), in place.
void clip_by_bisector(const std::array<int, 3>& triangle, int k, int l, const SymbolicContext& ctx,
                      std::vector<SymbolicVertex>& polygon, std::vector<SymbolicVertex>& scratch);

//! One cell's polygon among the polygons of a triangle: the cell, the end of its vertices in the
//! triangle's vertex list (the previous polygon's end, or 0, is their start) and its edges.
struct TrianglePolygon {
  int cell = -1;
  int end = 0;
  std::uint8_t reach = 0, along = 0;  //!< polygon_edges() of the polygon (the LRVD may take them in
                                      //!< the limit after a tie, and mark along kZeroAreaInTheLimit)
};

//! A bit of TrianglePolygon::along (and of Diagram::polygon_along) beside the three edges': the
//! polygon has zero area in the unperturbed geometry, a sliver of the perturbed diagram that is no
//! piece of its cell. Only the LRVD's triangles whose clipping met an exact tie are looked at.
constexpr std::uint8_t kZeroAreaInTheLimit = 8;

//! A polygon vertex as CellClipper stores it, five bytes instead of a SymbolicVertex's 28: what
//! defines it, relative to its triangle. A large mesh's diagram (MPS computes one of 650k
//! triangles) holds millions of them until it is flattened.
struct PackedVertex {
  SymbolicVertex::Type type;
  std::uint8_t where;     //!< type A: the corner; type B: the edge (corner where, corner where + 1)
  std::uint8_t label[3];  //!< types B and C: indices into the triangle's candidate list, increasing
};

//! Writes into `out` (as default-constructed) the SymbolicVertex of a packed vertex of `triangle`,
//! whose candidate list is `labels`. In place: a vertex assembled field by field elsewhere and
//! then copied stalls the copy (its wide loads cannot take the narrow stores' data).
inline void unpack(const PackedVertex& q, const std::array<int, 3>& triangle, const int* labels, SymbolicVertex& out) {
  out.type = q.type;
  switch (q.type) {
    case SymbolicVertex::Type::A:
      out.v[0] = triangle[q.where];
      break;
    case SymbolicVertex::Type::B: {
      const int a = triangle[q.where], b = triangle[q.where == 2 ? 0 : q.where + 1];
      out.v[0] = a < b ? a : b;
      out.v[1] = a < b ? b : a;
      out.label[0] = labels[q.label[0]];
      out.label[1] = labels[q.label[1]];
      break;
    }
    case SymbolicVertex::Type::C:
      out.v = triangle;
      out.label = {labels[q.label[0]], labels[q.label[1]], labels[q.label[2]]};
      break;
  }
}

//! The polygons of all candidate cells of one triangle, with storage reused from call to call
//! (one clipper per thread). Cell k's polygon is the one clip_triangle gives with the whole list
//! as `others`, vertex for vertex; but a vertex that several cells' polygons share (a mesh
//! corner, a point on a mesh edge or inside the triangle) is tested against a bisector once, and
//! each later test reuses the sign: side() does not depend on which of the vertex's labels asks
//! (a corner's answer for (l, k) is the negation of its answer for (k, l)).
class CellClipper {
 public:
  //! Most candidates the clipper packs: more take the per-cell path, which writes to `wide`.
  static constexpr int kMaxLabels = 16;

  //! Appends, for each cell k of `labels` (m of them, sorted, distinct) in order whose polygon in
  //! triangle t is not empty, its vertices to `verts` (packed against `labels`) and the polygon to
  //! `polygons`. A single candidate's polygon is the whole triangle and gets no vertices: a polygon
  //! without vertices stands for the triangle's corners. More than kMaxLabels candidates take the
  //! per-cell path, which writes every vertex unpacked, to `wide` instead.
  void clip(const SurfaceMesh& mesh, int t, const int* labels, int m, const SymbolicContext& ctx,
            std::vector<TrianglePolygon>& polygons, std::vector<PackedVertex>& verts,
            std::vector<SymbolicVertex>& wide);

 private:
  static constexpr int kMaxVertices = 40;  // a convex polygon cut by at most 15 bisectors: 18

  // A polygon vertex during clipping, eight bytes: labels as indices into the triangle's label
  // list.
  struct LocalVertex {
    SymbolicVertex::Type type;
    std::uint8_t mask;      // edge_mask bits
    std::uint8_t where;     // type A: corner; type B: edge (corner where, corner where + 1)
    std::uint8_t label[3];  // types B and C: local labels, increasing; unused ones 0xff
    std::uint16_t key;      // memo slot of l = 0: type B ((where m + a) m + b) m, type C ((a m + b) m + c) m
  };
  // One Sutherland-Hodgman step's input or output.
  struct LocalPolygon {
    int n = 0;
    LocalVertex v[kMaxVertices];
  };

  void begin_triangle(const std::array<int, 3>& tri, const int* labels, int m, const SymbolicContext& ctx);
  const predicates::BoundedPowerDistance& corner_distance(int a, int c);
  Sign corner_side(int c, int k, int l);
  void clip_two(std::vector<TrianglePolygon>& polygons, std::vector<PackedVertex>& verts);
  void clip_many(const std::array<int, 3>& tri, int k, const int* labels, int m, const SymbolicContext& ctx);
  Sign side_of(const LocalVertex& q, int k, int l, const std::int8_t* corner_signs);
  Sign evaluate_corner(int c, int k, int l);
  Sign evaluate_vertex(const LocalVertex& q, int k, int l);
  void clip_local(const LocalPolygon& in, int k, int l, LocalPolygon& out);
  LocalVertex intersection(const LocalVertex& u, const LocalVertex& w, int k, int l) const;

  // The triangle being clipped.
  const std::array<int, 3>* triangle_ = nullptr;
  const int* labels_ = nullptr;
  int m_ = 0;
  const Vec3* vertices_ = nullptr;
  bool in_range_ = false;  // SymbolicContext::in_range of the triangle's context
  const Site* site_[kMaxLabels];    // by local label
  const Vec3* corner_[3];           // corner positions
  int edge_lo_[3], edge_hi_[3];     // edge e's end points, lower vertex index first
  // Memo of the side tests: corner c for cells (k, l) at corner_sign_[3 (k m + l) + c] (0 while
  // unknown); a type B or C vertex against l at edge_sign_ or inner_sign_[key + l], valid when
  // the entry's high bits hold the current epoch_ (low two bits: sign + 1).
  std::int8_t corner_sign_[3 * kMaxLabels * kMaxLabels];
  // Corner c's bounded power distance to cell a at corner_distance_[3 a + c], valid where bit
  // 3 a + c of corner_distance_known_ is set: each corner test reads two of them (side1 with the
  // distances shared between the cell pairs of the triangle).
  predicates::BoundedPowerDistance corner_distance_[3 * kMaxLabels];
  std::uint64_t corner_distance_known_ = 0;
  predicates::CallTally tally_;  // side1 and side2 calls decided in doubles, added to the counters per clip()
  std::vector<std::uint32_t> edge_sign_, inner_sign_;
  std::uint32_t epoch_ = 0;
  LocalPolygon polygon_, scratch_;
  std::vector<SymbolicVertex> fallback_polygon_, fallback_scratch_;
  std::vector<double> reach2_, next_reach2_;  // clip_many: each vertex's squared distance bound
};

}  // namespace lrvd
