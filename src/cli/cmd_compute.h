// `lrvd compute` and `lrvd verify`: one diagram (LRVD, RVD, LRPD, RPD) of samples on a mesh, its
// cells as a PLY and its verification as a JSON report.
#pragma once

#include <CLI/CLI.hpp>

#include "cli/commands.h"

namespace lrvd::cli {

Action add_compute_command(CLI::App& app);  //!< `lrvd compute`
Action add_verify_command(CLI::App& app);  //!< `lrvd verify`

}  // namespace lrvd::cli
