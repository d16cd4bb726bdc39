// lrvd: localized restricted Voronoi diagrams on triangle meshes, remeshing and sampling.
#include <cstdio>
#include <exception>
#include <map>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "cli/commands.h"
#include "common/error.h"

namespace {

// An error line as the terminal should show it: control characters (an escape sequence read from a
// file) written as \xNN, and a line longer than a screen or two (a 200 kB token echoed from a
// file) shortened in the middle.
std::string printable(const std::string& message) {
  constexpr std::size_t kLongest = 400, kHead = 300, kTail = 80;
  std::string out;
  for (unsigned char c : message) {
    if (c < 0x20 || c == 0x7f) out += fmt::format("\\x{:02x}", c);
    else out += static_cast<char>(c);
  }
  if (out.size() > kLongest)
    out = out.substr(0, kHead) + fmt::format(" [... {} characters ...] ", out.size() - kHead - kTail) +
          out.substr(out.size() - kTail);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lrvd::cli;
  CLI::App app{"lrvd: exact localized restricted Voronoi diagrams (LRVD) of points on triangle meshes"};
  app.set_version_flag("--version", std::string("lrvd ") + LRVD_VERSION);
  app.require_subcommand(1);
  int threads = 0;
  app.add_option("--threads", threads,
                 "Worker threads (default: every core); results do not depend on it")
      ->check(CLI::Range(1, 4096));
  app.fallthrough();  // --threads may also follow the subcommand
  std::map<CLI::App*, Action> actions;
  auto add = [&](Action (*adder)(CLI::App&)) {
    const size_t before = app.get_subcommands({}).size();
    Action action = adder(app);
    actions[app.get_subcommands({})[before]] = std::move(action);
  };
  add(add_compute_command);
  add(add_verify_command);
  add(add_remesh_command);
  add(add_quality_command);
  add(add_mps_command);
  add(add_stress_command);
  for (CLI::App* command : app.get_subcommands({}))
    command->footer("--threads N, before or after the subcommand, limits the worker threads (default: every core); "
                    "the results do not depend on it.");

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // A misspelt subcommand reaches CLI11 as a missing one: name the word it did not know.
    if (app.get_subcommands().empty())
      for (const std::string& extra : app.remaining())
        if (!extra.empty() && extra[0] != '-') {
          std::fprintf(stderr, "lrvd: error: unknown subcommand '%s': compute, verify, remesh, quality, mps or stress (see --help)\n",
                       printable(extra).c_str());
          return kBadInput;
        }
    // CLI11 says "--samples: At Most 1 required but received 2" for an option given twice.
    std::string message = e.what();
    const std::string repeated = ": At Most 1 required but received ";
    if (const auto at = message.find(repeated); at != std::string::npos)
      message = message.substr(0, at) + " is given " + message.substr(at + repeated.size()) + " times; give it once";
    std::fprintf(stderr, "lrvd: error: %s (see --help)\n", printable(message).c_str());
    return kBadInput;
  }
  std::unique_ptr<tbb::global_control> thread_limit;
  if (threads > 0)
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  try {
    for (auto& [command, action] : actions)
      if (command->parsed()) return action();
  } catch (const lrvd::InputError& e) {
    std::fprintf(stderr, "lrvd: error: %s\n", printable(e.what()).c_str());
    return kBadInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "lrvd: error: out of memory\n");
    return kInternalError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lrvd: internal error: %s\n", printable(e.what()).c_str());
    return kInternalError;
  }
  return kInternalError;
}
