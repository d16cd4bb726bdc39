// lrvd: localized restricted Voronoi diagrams on triangle meshes, remeshing and sampling.
// The program's entry point: no header.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "cli/cmd_compute.h"
#include "cli/cmd_mps.h"
#include "cli/cmd_remesh.h"
#include "cli/cmd_render.h"
#include "cli/cmd_stress.h"
#include "cli/commands.h"
#include "common/error.h"
#include "io/mesh_writers.h"

namespace {

// Length of the well-formed UTF-8 sequence that starts at s[i] (1 to 4 bytes), or 0 when none does
// (a byte of a binary file, a Latin-1 letter): a terminal would show that as a replacement mark,
// or a pipe reading UTF-8 would fail on it.
std::size_t utf8_length(const std::string& s, std::size_t i) {
  const unsigned char c = s[i];
  const std::size_t n = c < 0x80 ? 1 : c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(s[i + k]) & 0xc0) != 0x80) return 0;
  const unsigned char second = s[i + (n > 1 ? 1 : 0)];
  if ((c == 0xe0 && second < 0xa0) || (c == 0xed && second >= 0xa0) || (c == 0xf0 && second < 0x90) ||
      (c == 0xf4 && second >= 0x90))
    return 0;  // an overlong form, a surrogate, or beyond U+10FFFF
  return n;
}

// An error line as the terminal should show it, in well-formed UTF-8: control characters (an escape
// sequence read from a file) and bytes that are no UTF-8 written as \xNN, and a line longer than a
// screen or two (a 200 kB token echoed from a file) shortened in the middle, never inside a
// character.
std::string printable(const std::string& message) {
  constexpr std::size_t kLongest = 400, kHead = 300, kTail = 80;
  std::string out;
  for (std::size_t i = 0; i < message.size();) {
    const unsigned char c = message[i];
    const std::size_t n = utf8_length(message, i);
    if (n == 0 || c < 0x20 || c == 0x7f) {
      out += fmt::format("\\x{:02x}", c);
      ++i;
    } else {
      out.append(message, i, n);
      i += n;
    }
  }
  if (out.size() > kLongest) {
    auto continuation = [&](std::size_t at) { return (static_cast<unsigned char>(out[at]) & 0xc0) == 0x80; };
    std::size_t head = kHead, tail = out.size() - kTail;
    while (head > 0 && continuation(head)) --head;
    while (tail < out.size() && continuation(tail)) ++tail;
    out = out.substr(0, head) + fmt::format(" [... {} characters ...] ", tail - head) + out.substr(tail);
  }
  return out;
}

// CLI11's wording, where it reads oddly: "--samples: At Most 1 required but received 2" for an
// option given twice, "--samples: 1 required INT:INT missing" for one without its value, and the
// words it did not expect listed last first.
std::string plain_parse_error(std::string message) {
  const std::string repeated = ": At Most 1 required but received ";
  const std::string unexpected = "The following arguments were not expected: ",
                    unexpected_one = "The following argument was not expected: ";
  if (const auto at = message.find(repeated); at != std::string::npos) {
    message = message.substr(0, at) + " is given " + message.substr(at + repeated.size()) + " times; give it once";
  } else if (message.find(": 1 required ") != std::string::npos && message.size() > 8 &&
             message.compare(message.size() - 8, 8, " missing") == 0) {
    message = message.substr(0, message.find(": 1 required ")) + " needs a value";
  } else if (const std::string convert = "Could not convert: "; message.rfind(convert, 0) == 0 &&
                                                                 message.find(" = ") != std::string::npos) {
    // "Could not convert: --radius = abc": a number option given text.
    const std::size_t equals = message.find(" = ");
    message = fmt::format("{} takes a number, not '{}'", message.substr(convert.size(), equals - convert.size()),
                          message.substr(equals + 3));
  } else if (message.rfind(unexpected, 0) == 0 || message.rfind(unexpected_one, 0) == 0) {
    std::vector<std::string> words;
    std::istringstream rest(message.substr(message.find(": ") + 2));
    for (std::string word; rest >> word;) words.push_back(word);
    std::reverse(words.begin(), words.end());
    std::string listed;
    for (const std::string& word : words) listed += (listed.empty() ? "" : " ") + word;
    message = fmt::format("unexpected argument{}: {} (this command does not take {})", words.size() == 1 ? "" : "s",
                          listed, words.size() == 1 ? "it" : "them");
  }
  return message;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lrvd::cli;
  lrvd::remove_part_files_on_signals();  // an interrupted write leaves no part file beside the old one
  CLI::App app{"lrvd: exact localized restricted Voronoi diagrams (LRVD) of points on triangle meshes"};
  app.set_version_flag("--version", std::string("lrvd ") + LRVD_VERSION);
  app.require_subcommand(1);
  int threads = 0;
  app.add_option("--threads", threads,
                 "Worker threads (default: every core); results do not depend on it")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            // CLI11's range check calls "abc" a value out of range.
            const bool digits = !text.empty() && text.size() <= 4 &&
                                text.find_first_not_of("0123456789") == std::string::npos;
            if (!digits || std::stoi(text) < 1 || std::stoi(text) > 4096)
              return "a thread count is a whole number from 1 to 4096, not '" + text + "'";
            return std::string();
          },
          "INT in [1 - 4096]"));
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
  add(add_render_command);
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
          std::fprintf(stderr, "lrvd: error: unknown subcommand '%s': compute, verify, remesh, quality, mps, stress or render (see --help)\n",
                       printable(extra).c_str());
          return kBadInput;
        }
    const std::string message = plain_parse_error(e.what());
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
  } catch (const lrvd::WriteError& e) {
    std::fprintf(stderr, "lrvd: error: %s\n", printable(e.what()).c_str());
    return kWriteFailed;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "lrvd: error: out of memory\n");
    return kInternalError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lrvd: internal error: %s\n", printable(e.what()).c_str());
    return kInternalError;
  }
  return kInternalError;
}
