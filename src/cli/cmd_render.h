// `lrvd render`: a PNG of a mesh, or of the cells of a diagram of samples on it (stray pieces
// hatched, so an RVD's broken cells show beside the LRVD's whole ones).
#pragma once

#include <CLI/CLI.hpp>

#include "cli/commands.h"

namespace lrvd::cli {

Action add_render_command(CLI::App& app);

}  // namespace lrvd::cli
