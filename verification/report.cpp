// JSON and text forms of verification results.
#include "verification/report.h"

#include <fmt/format.h>

namespace lrvd {

void PropertyResult::fail(const std::string& offender) {
  passed = false;
  ++violations;
  if (first_offenders.size() < 10) first_offenders.push_back(offender);
}

nlohmann::json PropertyResult::to_json() const {
  return {{"passed", passed}, {"promised", promised}, {"checked", checked}, {"violations", violations},
          {"first_offenders", first_offenders}};
}

std::string PropertyResult::summary_line(const std::string& name) const {
  if (passed) return "";
  return fmt::format("{}{}: {} violation(s), first: {}\n", name, promised ? "" : " (not promised)", violations,
                     first_offenders.empty() ? "-" : first_offenders.front());
}

nlohmann::json DiagramVerification::to_json() const {
  return {{"passed", passed},
          {"time_s", time_s},
          {"cells_with_multiple_components", cells_with_multiple_components},
          {"distinct_vertices", distinct_vertices},
          {"rational_points", rational_points},
          {"properties",
           {{"sample_in_cell", sample_in_cell.to_json()},
            {"connected", connected.to_json()},
            {"equidistant", equidistant.to_json()},
            {"disjoint", disjoint.to_json()},
            {"coverage", coverage.to_json()},
            {"conforming", conforming.to_json()}}}};
}

std::string DiagramVerification::summary() const {
  return sample_in_cell.summary_line("sample_in_cell") + connected.summary_line("connected") +
         equidistant.summary_line("equidistant") + disjoint.summary_line("disjoint") +
         coverage.summary_line("coverage") + conforming.summary_line("conforming");
}

}  // namespace lrvd
