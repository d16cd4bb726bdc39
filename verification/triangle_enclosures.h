// Interval enclosures of the vertices of one triangle's polygons (internal to verification/): the
// same intervals as enclose_position (predicates/exact.h), operation for operation, with the
// terms the vertices of a triangle share evaluated once: the squared distances from the corners
// to the sites, and the triangle's normal.
#pragma once

#include <optional>
#include <vector>

#include <CGAL/Interval_nt.h>

#include "predicates/exact.h"

namespace lrvd::verify_detail {

class TriangleEnclosures {
 public:
  using Interval = CGAL::Interval_nt<false>;

  //! Starts on triangle `tri` (its corners in order) of the context's mesh.
  void reset(const std::array<int, 3>& tri, const SymbolicContext& ctx);
  //! enclose_position(q, ctx), bit for bit, into box and (type B) parameter; false for nullopt.
  //! \pre the rounding mode is upward (CGAL::Protect_FPU_rounding); the indices of q are in range.
  bool enclose(const SymbolicVertex& q, std::array<Interval, 3>& box, Interval& parameter);

  struct V3 {
    Interval x, y, z;
  };

 private:
  struct Distances {  // |corner c - x_s|^2 for the triangle's corners, as bisector_value makes them
    int site;
    std::uint8_t made;  // bit c: d[c] is made
    Interval d[3];
  };
  int corner(int v) const { return v == tri_[0] ? 0 : (v == tri_[1] ? 1 : (v == tri_[2] ? 2 : -1)); }
  int site_index(int site);
  const Interval& distance(int index, int c);
  Interval bisector_value(int c, int a, int b);
  bool on_edge(const SymbolicVertex& q, int c0, int c1, std::array<Interval, 3>& box, Interval& parameter);
  bool in_plane(const SymbolicVertex& q, std::array<Interval, 3>& box);

  std::array<int, 3> tri_{};
  const SymbolicContext* ctx_ = nullptr;
  V3 corner_[3];
  std::optional<V3> normal_;  // cross(corner 1 - corner 0, corner 2 - corner 0)
  std::vector<Distances> distances_;
  std::vector<int> slots_;  // with many sites: an open-addressing table into distances_
};

}  // namespace lrvd::verify_detail
