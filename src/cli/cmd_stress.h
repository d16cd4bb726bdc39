// `lrvd stress`: list and write the stress meshes (nearby sheets, thin walls, tubes, ...).
#pragma once

#include <CLI/CLI.hpp>

#include "cli/commands.h"

namespace lrvd::cli {

Action add_stress_command(CLI::App& app);

}  // namespace lrvd::cli
