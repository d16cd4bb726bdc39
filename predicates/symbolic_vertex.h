// Symbolic vertices of clipped restricted-Voronoi polygons (paper §3.4, §3.6, after [8]): a mesh
// vertex, a mesh edge ∩ bisector, or a triangle ∩ two bisectors; their side tests and birth rule.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "predicates/predicates.h"
#include "predicates/vec3.h"

namespace lrvd {

//! A polygon vertex stored by what defines it, never by coordinates. Labels are sample ids
//! (== Site::id). Unused fields are -1, so == compares the defining data exactly; two polygons
//! in the same triangle (or across a mesh edge, for type B) that share a vertex build equal ones.
struct SymbolicVertex {
  enum class Type : std::uint8_t {
    A,  //!< mesh vertex v[0]
    B,  //!< mesh edge (v[0] < v[1]) ∩ bisector(label[0] < label[1])
    C   //!< plane of triangle (v[0], v[1], v[2]) in the triangle's own order ∩ bisectors of
        //!< label[0] < label[1] < label[2] (the point equidistant from all three)
  };

  Type type = Type::A;
  std::array<int, 3> v{{-1, -1, -1}};
  std::array<int, 3> label{{-1, -1, -1}};

  static SymbolicVertex mesh_vertex(int vertex);
  //! Edge endpoints and labels in any order; they are stored sorted.
  static SymbolicVertex on_edge(int v0, int v1, int a, int b);
  //! Triangle corners in the triangle's order; labels in any order (stored sorted).
  static SymbolicVertex in_triangle(const std::array<int, 3>& triangle, int a, int b, int c);

  int num_labels() const { return type == Type::A ? 0 : (type == Type::B ? 2 : 3); }
  bool has_label(int s) const {
    return (type != Type::A && (label[0] == s || label[1] == s)) || (type == Type::C && label[2] == s);
  }
  //! True if the vertex lies on mesh edge {a, b} (type A at a or b, or type B on that edge).
  bool on_mesh_edge(int a, int b) const;
};

inline bool operator==(const SymbolicVertex& a, const SymbolicVertex& b) {
  // Field by field (std::array's == calls memcmp).
  return a.v[0] == b.v[0] && a.v[1] == b.v[1] && a.v[2] == b.v[2] && a.label[0] == b.label[0] &&
         a.label[1] == b.label[1] && a.label[2] == b.label[2] && a.type == b.type;
}
inline bool operator!=(const SymbolicVertex& a, const SymbolicVertex& b) { return !(a == b); }

//! What the symbolic predicates read: mesh vertex positions by vertex index and sites by sample
//! id (sites[s].id == s).
struct SymbolicContext {
  const Vec3* vertices = nullptr;
  const Site* sites = nullptr;
  //! Every vertex and site is predicates::in_filter_range (checked_context sets it): the side
  //! tests then skip the range check on each call.
  bool in_range = false;
};

//! The context of `vertex_count` vertices and `site_count` sites, with in_range checked once.
SymbolicContext checked_context(const Vec3* vertices, std::size_t vertex_count, const Site* sites,
                                std::size_t site_count);

//! side(q; i, l): Positive when q is strictly closer (perturbed power distance) to site i than to
//! site l, Negative when closer to l. Never Zero for i != l unless l is one of q's labels (then q
//! lies on bisector(i, l) and the answer is Zero). The answer does not depend on which of q's
//! labels is i: the point is equidistant from all of them.
//! \pre type A: any i. Types B and C: q.has_label(i).
Sign side(const SymbolicVertex& q, int i, int l, const SymbolicContext& ctx);

//! The birth rule: the vertex where edge (u, w) of cell i's polygon inside `triangle` (its corners
//! in the triangle's order) is cut by bisector(i, l). If u and w lie on one mesh edge of the
//! triangle, the new vertex is type B on that edge with labels {i, l}; otherwise the edge lies on
//! bisector(i, m), m the label u and w share besides i, and the new vertex is type C {i, m, l}.
//! \throw std::logic_error if (u, w) is on no mesh edge and u, w share no label besides i.
SymbolicVertex intersect(const SymbolicVertex& u, const SymbolicVertex& w, int i, int l,
                         const std::array<int, 3>& triangle);

//! Whether u and w, two vertices on one mesh edge with a label in common (the ends of a polygon
//! side along the edge), are one point of the unperturbed geometry: a side of positive length in
//! the perturbed diagram that has length zero in its limit. Exact, no perturbation.
//! \pre u and w lie on one mesh edge; two type B vertices share a label.
bool coincide_unperturbed(const SymbolicVertex& u, const SymbolicVertex& w, const SymbolicContext& ctx);

//! Whether a polygon of a triangle (its `count` vertices in order) has zero area in the
//! unperturbed geometry: a sliver of the perturbed diagram that collapses to a segment or a point.
//! Exact, in rational arithmetic (predicates/exact.cpp): for the few polygons of triangles whose
//! clipping met an exact tie.
bool zero_area_unperturbed(const SymbolicVertex* v, int count, const SymbolicContext& ctx);

//! For each of the `count` vertices, an upper bound on the squared distance from `center` to its
//! exact (unperturbed) position, from its interval enclosure (predicates/exact.h); +infinity when
//! it cannot be enclosed. With predicates::ball_clear_of_bisector they tell that a clip by
//! bisector(i, l) would keep every vertex of a polygon of cell i (side() evaluates at those
//! positions), so Sutherland-Hodgman would return the polygon as it was.
void distance_bounds2(const SymbolicVertex* v, int count, const Vec3& center, const SymbolicContext& ctx, double* bound2);

//! Double position for output and integration. Type B: parameter F1/(F1 - F2) clamped to [0, 1];
//! type C: Cramer's rule; falls back to the rounded exact position when doubles overflow or the
//! double system is singular.
Vec3 position(const SymbolicVertex& q, const SymbolicContext& ctx);

//! Hash for unordered containers of vertices.
struct SymbolicVertexHash {
  std::size_t operator()(const SymbolicVertex& q) const {
    std::size_t h = static_cast<std::size_t>(q.type);
    for (int x : q.v) h = h * 1000003u ^ std::hash<int>()(x);
    for (int x : q.label) h = h * 1000003u ^ std::hash<int>()(x);
    return h;
  }
};

//! Distinct symbolic vertices, numbered in the order first seen: an open-addressing table (linear
//! probing, at most half full) over the vertices' list, for the passes that meet each vertex in
//! several polygons (output, verification).
class SymbolicVertexIndex {
 public:
  //! Room for n distinct vertices without regrowing.
  void reserve(std::size_t n);
  //! The number of q: a new one (size() before the call) the first time q is seen.
  int insert(const SymbolicVertex& q);
  std::size_t size() const { return vertices_.size(); }
  const SymbolicVertex& operator[](int id) const { return vertices_[id]; }
  const std::vector<SymbolicVertex>& vertices() const { return vertices_; }

 private:
  void rehash(std::size_t slots);

  std::vector<int> slots_;  // an id into vertices_, or -1; a power of two of them
  std::vector<SymbolicVertex> vertices_;
};

}  // namespace lrvd
