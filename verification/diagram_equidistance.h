// (3) Every polygon vertex is (power-)equidistant from its cell and from as many other cells of its
// triangle as its type says, and no cell of the triangle is nearer: a check of verify_diagram's triangle pass.
#pragma once

#include <cstdint>
#include <vector>

#include "verification/diagram_polygons.h"

namespace lrvd::verify_detail {

class Near;  // diagram_equidistance.cpp: the sites near a vertex, with many cells in the triangle

//! (3) on the triangle's vertices.
class EquidistanceChecks : protected PolygonChecks {
 protected:
  using PolygonChecks::PolygonChecks;

  void check_equidistance(int t);

 private:
  void equidistance_present(int t, int p);
  void equidistance_near(int t, int p, const Near& near);
  void report_unequal(int t, const SymbolicVertex& q, int i, int closer, int equidistant);

  // The cells with a usable polygon in the triangle, e_j(q) for each local vertex q and cell j
  // (made on first use), the cells a vertex is compared with (with many cells).
  std::vector<int> present_;
  std::vector<std::uint32_t> labels_;  // per local vertex: the bits of present_ that are its labels
  std::vector<Interval> e_;
  std::vector<std::uint32_t> e_made_;
  std::uint32_t stamp_ = 0;
  std::vector<int> compared_;
};

}  // namespace lrvd::verify_detail
