// The results of the checks, and their JSON and text forms: one property's outcome (PropertyResult,
// also in the remesh and MPS checks' results) and a diagram's verification (DiagramVerification).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace lrvd {

//! The outcome of one property check.
struct PropertyResult {
  bool passed = true;
  bool promised = true;           //!< the diagram's kind guarantees this property
  std::int64_t checked = 0;       //!< how many elements were checked
  std::int64_t violations = 0;
  std::vector<std::string> first_offenders;  //!< up to 10, each naming triangle / cell / vertex
  void fail(const std::string& offender);    //!< records one violation
  nlohmann::json to_json() const;            //!< {passed, promised, checked, violations, first_offenders}
  //! "name: N violation(s), first: ...\n" when failed ("(not promised)" after the name if so), else "".
  std::string summary_line(const std::string& name) const;
};

struct DiagramVerification {
  bool passed = true;  //!< every promised property holds
  double time_s = 0;
  PropertyResult sample_in_cell;  //!< (1) x_i lies in cell i
  PropertyResult connected;       //!< (2) each cell is one connected region (edge segments join polygons)
  PropertyResult equidistant;     //!< (3) boundary vertices between i and j are (power-)equidistant
  PropertyResult disjoint;        //!< (4) polygons of a triangle are interior-disjoint
  PropertyResult coverage;        //!< (5) polygons of a triangle cover it
  PropertyResult conforming;      //!< (6) both sides of a mesh edge split it alike
  int cells_with_multiple_components = 0;
  std::int64_t distinct_vertices = 0;  //!< distinct symbolic vertices of the polygons and the mesh
  //! Points (distinct vertices and samples) whose rational coordinates or edge parameter some check
  //! needed: an interval enclosure decided every sign of the others.
  std::int64_t rational_points = 0;

  nlohmann::json to_json() const;
  //! One line per failed property, empty when all passed.
  std::string summary() const;
};

}  // namespace lrvd
