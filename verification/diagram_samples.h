// (1) Each sample lies in its own cell's polygon in its triangle, exactly: a check of
// verify_diagram's triangle pass, with the triangle's vertices at hand.
#pragma once

#include <string>

#include "verification/diagram_equidistance.h"

namespace lrvd::verify_detail {

//! (1) for the samples located on the triangle, after (4) and (5) have set its polygons' area signs.
class SampleChecks : protected EquidistanceChecks {
 protected:
  using EquidistanceChecks::EquidistanceChecks;

  void check_samples(int t, const Triangle& tri, const Frame& f);

 private:
  std::string sample_problem(int i, int t, const Triangle& tri, const Frame& f);
  bool contains_point(int p, const ExactVertex& x, const Frame& f);
};

}  // namespace lrvd::verify_detail
