// `lrvd remesh` (CVT on the LRVD, output the dual with exactly N vertices, checked) and
// `lrvd quality` (the metrics alone, for any remesher's output).
#pragma once

#include <CLI/CLI.hpp>

#include "cli/commands.h"

namespace lrvd::cli {

Action add_remesh_command(CLI::App& app);  //!< `lrvd remesh`
Action add_quality_command(CLI::App& app);  //!< `lrvd quality`

}  // namespace lrvd::cli
