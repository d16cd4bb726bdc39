// What the subcommands of `lrvd` (each added by its cli/cmd_*.h) share: the action that runs one, and
// the exit statuses of main.cpp's error handling (2 on bad input, 3 when a promised property fails, 1 when a write fails).
#pragma once

#include <functional>

namespace lrvd::cli {

//! Exit status of a subcommand.
//! A failed write (WriteError) exits 1 as an internal error does: the input was not at fault.
enum ExitStatus { kOk = 0, kInternalError = 1, kWriteFailed = 1, kBadInput = 2, kCheckFailed = 3 };

//! A subcommand registers its options and returns the action that runs it.
using Action = std::function<int()>;

}  // namespace lrvd::cli
