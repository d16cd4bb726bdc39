// JSON and text forms of verification results.
#include <fmt/format.h>

#include "verification/diagram_check.h"

namespace lrvd {

void PropertyResult::fail(const std::string& offender) {
  passed = false;
  ++violations;
  if (first_offenders.size() < 10) first_offenders.push_back(offender);
}

namespace {
nlohmann::json property_json(const PropertyResult& p) {
  return {{"passed", p.passed}, {"promised", p.promised}, {"checked", p.checked},
          {"violations", p.violations}, {"first_offenders", p.first_offenders}};
}
}  // namespace

nlohmann::json DiagramVerification::to_json() const {
  return {{"passed", passed},
          {"time_s", time_s},
          {"cells_with_multiple_components", cells_with_multiple_components},
          {"properties",
           {{"sample_in_cell", property_json(sample_in_cell)},
            {"connected", property_json(connected)},
            {"equidistant", property_json(equidistant)},
            {"disjoint", property_json(disjoint)},
            {"coverage", property_json(coverage)},
            {"conforming", property_json(conforming)}}}};
}

std::string DiagramVerification::summary() const {
  std::string out;
  auto add = [&](const char* name, const PropertyResult& p) {
    if (p.passed) return;
    out += fmt::format("{}{}: {} violation(s){}, first: {}\n", name, p.promised ? "" : " (not promised)",
                       p.violations, "", p.first_offenders.empty() ? "-" : p.first_offenders.front());
  };
  add("sample_in_cell", sample_in_cell);
  add("connected", connected);
  add("equidistant", equidistant);
  add("disjoint", disjoint);
  add("coverage", coverage);
  add("conforming", conforming);
  return out;
}

}  // namespace lrvd
