// Exact geometry for the diagram verification (internal to verification/): rational positions of
// the symbolic vertices, computed once per distinct vertex, with interval enclosures used only as a
// filter in front of exact rational sign evaluations. Nothing here uses a tolerance.
#pragma once

#include <array>
#include <string>
#include <unordered_map>
#include <vector>

#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>

#include "mesh/surface_mesh.h"
#include "predicates/exact.h"
#include "verification/diagram_check.h"

namespace lrvd::verify_detail {

using Q = CGAL::Gmpq;
//! Unprotected intervals: every function that computes with them sets the rounding mode once
//! (CGAL::Protect_FPU_rounding) instead of once per operation.
using Interval = CGAL::Interval_nt<false>;

//! A point with its exact rational coordinates and an interval enclosure of each.
struct ExactVertex {
  bool valid = false;  //!< false when the symbolic vertex names no point (its definition is degenerate)
  ExactPoint p;
  std::array<Interval, 3> box;
  Q edge_parameter;  //!< type B only: position along its edge, 0 at v[0], 1 at v[1]
};

//! An exact point, enclosed.
ExactVertex make_exact_vertex(const ExactPoint& p);
const Q& coordinate(const ExactPoint& p, int axis);

//! Exact positions of the distinct symbolic vertices of one diagram, computed on first sight.
class ExactVertices {
 public:
  explicit ExactVertices(const SymbolicContext& ctx) : ctx_(ctx) {}
  //! Index of q, computing its exact position the first time q is seen.
  int index(const SymbolicVertex& q);
  const ExactVertex& operator[](int id) const { return points_[id]; }
  const SymbolicVertex& symbolic(int id) const { return symbolic_[id]; }

 private:
  SymbolicContext ctx_;
  std::unordered_map<SymbolicVertex, int, SymbolicVertexHash> index_;
  std::vector<ExactVertex> points_;
  std::vector<SymbolicVertex> symbolic_;
};

//! A triangle's own 2D frame: the coordinate plane that drops `drop`, where the triangle has
//! non-zero area, and the orientation the projection gives to the triangle's normal.
struct Frame {
  int u = 0, v = 1;  //!< kept axes (drop + 1) % 3, (drop + 2) % 3
  int sign = 1;      //!< +1 if the triangle's corners are counterclockwise in (u, v), else -1
  bool valid = false;
};
//! \pre corners[c] is the exact vertex of the triangle's corner c.
Frame triangle_frame(const SurfaceMesh& mesh, int t, const std::array<const ExactVertex*, 3>& corners);

//! Exact orientation of a, b, c projected into the frame, relative to the triangle's normal:
//! Positive for a counterclockwise turn seen from the normal.
Sign orient(const ExactVertex& a, const ExactVertex& b, const ExactVertex& c, const Frame& f);

//! Exact twice signed area of the projected polygon, relative to the triangle's normal.
Q twice_area(const std::vector<const ExactVertex*>& polygon, const Frame& f);

//! Exact sign of d_a(q) - d_b(q), the power distances to sites a and b (Negative: q closer to a).
Sign compare_power_distance(const ExactVertex& q, const Site& a, const Site& b);

//! "A(5)", "B(edge 3-9, cells 2|7)", "C(triangle 1-2-3, cells 2|7|9)".
std::string describe(const SymbolicVertex& q);

//! Indices of the exact vertices of each diagram vertex (parallel to Diagram::vertices).
struct VertexIndex {
  ExactVertices exact;
  std::vector<int> of_diagram_vertex;
};

//! (2) connectedness and (6) conformity, from the polygons' segments along mesh edges.
//! polygon_ok: the polygon's cell and vertices are valid (both checks use it); piece: it also has
//! positive area (only those make up a cell's region: a zero-area polygon is the unperturbed
//! limit of an infinitesimal sliver at a degenerate input, no piece of its own).
void check_edges(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram,
                 const std::vector<char>& polygon_ok, const std::vector<char>& piece, VertexIndex& vertices,
                 DiagramVerification& out);

}  // namespace lrvd::verify_detail
