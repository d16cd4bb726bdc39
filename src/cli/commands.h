// The subcommands of the `lrvd` tool. Each adds itself to the CLI11 app and runs through the
// shared error handling of main.cpp (exit 2 on bad input, 3 when a promised property fails, 1 when a write fails).
#pragma once

#include <functional>
#include <memory>

#include <CLI/CLI.hpp>

namespace lrvd::cli {

//! Exit status of a subcommand.
//! A failed write (WriteError) exits 1 as an internal error does: the input was not at fault.
enum ExitStatus { kOk = 0, kInternalError = 1, kWriteFailed = 1, kBadInput = 2, kCheckFailed = 3 };

//! A subcommand registers its options and returns the action that runs it.
using Action = std::function<int()>;

Action add_stress_command(CLI::App& app);
Action add_compute_command(CLI::App& app);
Action add_verify_command(CLI::App& app);
Action add_remesh_command(CLI::App& app);
Action add_quality_command(CLI::App& app);
Action add_mps_command(CLI::App& app);
Action add_render_command(CLI::App& app);

}  // namespace lrvd::cli
