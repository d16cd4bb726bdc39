// `lrvd mps`: maximal Poisson-disk sampling (paper §4.2), its independent verification on a
// fresh LRPD, and optionally the LRRT remesh of the samples, checked like any remesh.
#pragma once

#include <CLI/CLI.hpp>

#include "cli/commands.h"

namespace lrvd::cli {

Action add_mps_command(CLI::App& app);

}  // namespace lrvd::cli
