// Loading inputs and writing reports for the subcommands.
#include "cli/common.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/error.h"
#include "common/text.h"
#include "io/mesh_file_diagnosis.h"
#include "io/mesh_writers.h"
#include "predicates/predicates.h"

namespace lrvd::cli {

namespace {

// -n: a whole number; CLI11 alone says "Could not convert: --samples = abc". Zero and negative
// counts pass here and get their own message with the other sample checks.
CLI::Validator count_validator() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool digits = text.size() > (text[0] == '-' ? 1u : 0u) &&
                            text.find_first_not_of("0123456789", text[0] == '-' ? 1 : 0) == std::string::npos;
        if (!digits) return "a sample count (-n) is a whole number, not '" + text + "'";
        errno = 0;
        const long long n = std::strtoll(text.c_str(), nullptr, 10);
        if (errno == ERANGE || n > kMaxSamples)
          return fmt::format("{} samples are more than lrvd takes (limit {})", text, kMaxSamples);
        return std::string();
      },
      "INT");
}

}  // namespace

CLI::Validator seed_validator() {
  // CLI11 would take "-1" as 2^64 - 1 and clamp a longer number: only decimal digits that fit.
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        errno = 0;
        if (digits) std::strtoull(text.c_str(), nullptr, 10);
        if (!digits || errno == ERANGE) return "a seed is a whole number from 0 to 18446744073709551615, not '" + text + "'";
        return std::string();
      },
      "UINT64");
}

namespace {

// A positive, finite fraction of the bounding-box diagonal.
CLI::Validator fraction_validator() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !(value > 0) || !std::isfinite(value))
          return "a positive fraction of the bounding-box diagonal, not '" + text + "'";
        return std::string();
      },
      "FRACTION");
}

}  // namespace

void add_repair_options(CLI::App* cmd, ReadOptions& read, const std::string& what) {
  cmd->add_flag("--repair", read.repair,
                fmt::format("Weld, clean, orient and stitch {} before use (a triangle soup, non-manifold edges)", what));
  cmd->add_option("--weld", read.weld,
                  fmt::format("Repair {}, first welding every vertex to an earlier one closer than this fraction of "
                              "its bounding-box diagonal (e.g. 1e-6: a soup whose corners were written with "
                              "rounding noise)",
                              what))
      ->check(fraction_validator())
      ->each([&read](const std::string&) { read.repair = true; });
  cmd->add_option("--fill-holes", read.fill_holes,
                  fmt::format("Fill every hole of {} whose boundary is at most this fraction of its bounding-box "
                              "diagonal long (e.g. 0.05); the other holes are kept",
                              what))
      ->check(fraction_validator());
}

void print_repair(const RepairReport& r, const ReadOptions& read) {
  if (read.repair) {
    const std::vector<std::string> changes = repair_changes(r);
    std::printf("repair: %s\n", changes.empty() ? "nothing to change" : fmt::format("{}", fmt::join(changes, ", ")).c_str());
  }
  // Dropped even without --repair: say so, since they leave the counts and the bounding box (the
  // unit of a relative radius) as the faces have them, not as the file lists its vertices.
  if (!read.repair && r.removed_unreferenced_vertices > 0)
    std::printf("input: left out %s that no face uses\n",
                counted(r.removed_unreferenced_vertices, "vertex", "vertices").c_str());
  if (!read.repair && !(read.fill_holes > 0)) return;
  for (const std::string& note : r.notes) std::printf("repair: %s\n", note.c_str());
}

void add_input_options(CLI::App* cmd, InputOptions& opt, bool allow_count, bool allow_weights) {
  cmd->add_option("mesh", opt.mesh_path, "Input mesh (.off, .obj, .ply, .stl)")->required()->check(path_validator());
  add_repair_options(cmd, opt.read);
  CLI::Option* points =
      cmd->add_option("--points", opt.points_path,
                      allow_weights ? "Sample points, one 'x y z [w]' per line" : "Sample points, one 'x y z' per line")
          ->check(path_validator());
  if (allow_count) {
    CLI::Option* n =
        cmd->add_option("-n,--samples", opt.count, "Number of random samples (uniform by area)")->check(count_validator());
    n->excludes(points);
    // The seed draws the random samples: with --points there are none.
    cmd->add_option("--seed", opt.seed, "Seed of the random samples")
        ->check(seed_validator())
        ->capture_default_str()
        ->excludes(points);
  } else {
    points->required();
  }
  if (allow_weights)
    cmd->add_option("--weights", opt.weights_path, "Weights of the samples, one per line (power diagrams)")
        ->check(path_validator());
  cmd->add_option("--refine", opt.refine,
                  "Split long edges first: 'auto' (when the samples would crowd the triangles), 'off', or a "
                  "maximum edge length")
      ->capture_default_str();
}

CLI::Validator path_validator() {
  return CLI::Validator(
      [](std::string& text) -> std::string { return text.empty() ? "a file name may not be empty" : std::string(); },
      "PATH");
}


LoadedMesh load_mesh(const InputOptions& opt) {
  LoadedMesh loaded = read_mesh(opt.mesh_path, opt.read);
  // Before any point is located on it: distances of a model outside this range overflow or vanish.
  require_workable_model(loaded.mesh, "lrvd");
  print_repair(loaded.repair, opt.read);
  return loaded;
}

Input load_input(const InputOptions& opt) {
  Input input;
  input.loaded = load_mesh(opt);
  input.repair_requested = opt.read.repair;
  PointFile points;
  if (!opt.points_path.empty()) points = read_xyz(opt.points_path);
  if (!opt.weights_path.empty()) {
    if (!points.weights.empty())
      throw InputError(fmt::format("the weights are given twice: in the 4th column of {} and in --weights {}",
                                   opt.points_path, opt.weights_path));
    points.weights = read_weights(opt.weights_path);
    if (!opt.points_path.empty() && points.weights.size() != points.points.size())
      throw InputError(fmt::format("{}: {} weights were given for the {} points of {}", opt.weights_path,
                                   points.weights.size(), points.points.size(), opt.points_path));
  }
  SampleRequest request;
  request.points_given = !opt.points_path.empty();
  request.points = std::move(points);
  request.count = opt.count;
  request.seed = opt.seed;
  request.refine = opt.refine;
  request.mesh_name = opt.mesh_path;
  request.points_name = opt.points_path;
  request.weights_name = opt.weights_path;
  request.check_count = opt.check_count;
  request.on_progress = progress;
  prepare_samples(input, request);
  // The diagram is of the moved points: say so when a move is more than rounding (a point
  // written on a triangle comes back from its closest point a few ulps away).
  if (input.points_moved > 0) {
    const double diagonal = input.mesh.bounding_box().diagonal();
    std::printf("points: %d of %s moved onto the surface, the farthest by %.3g (%.2g of the bounding-box "
                "diagonal); the diagram is of the moved points\n",
                input.points_moved, counted(input.samples.size(), "point", "points").c_str(), input.points_max_move,
                input.points_max_move / diagonal);
  }
  return input;
}

std::vector<ReadFile> read_files(const InputOptions& input) {
  return {{input.mesh_path, "the input mesh"}, {input.points_path, "the --points file"},
          {input.weights_path, "the --weights file"}};
}

namespace {

// A path as it is once the links of its folders are followed, for a file not made yet too.
std::filesystem::path resolved(std::filesystem::path p) {
  namespace fs = std::filesystem;
  std::error_code error;
  // A link to a file not made yet is followed too (weakly_canonical stops at it).
  p = written_file(p.string());
  // Absolute first: weakly_canonical leaves a relative path to a file not made yet relative, and
  // `n.xyz` would not equal `./n.xyz` or its absolute spelling.
  const fs::path absolute = fs::absolute(p, error).lexically_normal();
  const fs::path canonical = fs::weakly_canonical(absolute, error);
  return error ? absolute : canonical;
}

// One file under two names: the same file on disk (a link, another spelling), or, for a file
// not made yet, the same path once the links of its folders are followed.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code error;
  return std::filesystem::equivalent(a, b, error) || resolved(a) == resolved(b);
}

// The output's name: a file (not a folder) of an extension lrvd writes, in a folder that exists,
// through links that lead somewhere.
void check_output_name(const PlannedOutput& out) {
  namespace fs = std::filesystem;
  const fs::path path(out.path);
  std::error_code error;
  if (fs::is_directory(path, error))
    throw InputError(fmt::format("{} {} is a folder, not a file", out.option, out.path));
  const std::string ext = lowercase_extension(out.path);
  auto listed = [&](const std::vector<std::string>& list) { return std::find(list.begin(), list.end(), ext) != list.end(); };
  if (!out.extensions.empty() && !listed(out.extensions)) {
    std::string known;
    for (const std::string& e : out.extensions) known += (known.empty() ? "" : ", ") + e;
    throw InputError(fmt::format("{} {}: {}; {} {} there", out.option, out.path,
                                 ext.empty() ? "no extension" : fmt::format("lrvd does not write '{}' files", ext),
                                 ext.empty() ? "lrvd writes" : "it writes", known));
  }
  if (listed(out.refused))
    throw InputError(fmt::format("{} {}: this output is not a mesh, and a '{}' file would pass for one; use another "
                                 "extension",
                                 out.option, out.path, ext));
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  if (!fs::is_directory(folder, error))
    throw InputError(fmt::format("{} {}: the folder {} does not exist", out.option, out.path, folder.string()));
  // Through a symbolic link: the file the link leads to is the one written (mesh_writers.cpp).
  const fs::path file(written_file(out.path));
  if (fs::is_symlink(file, error))
    throw InputError(fmt::format("{} {} is a loop of symbolic links, or a chain of more than 40", out.option,
                                 out.path));
  const fs::path file_folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  if (file != path && !fs::is_directory(file_folder, error))
    throw InputError(fmt::format("{} {} is a symbolic link to {}, whose folder does not exist", out.option,
                                 out.path, file.string()));
}

// Writable: an existing file opened for appending (nothing changes), a new one made and removed,
// so that a long run does not end on a file it cannot write; and the part file beside it.
void probe_output(const PlannedOutput& out, bool device) {
  namespace fs = std::filesystem;
  const fs::path path(out.path);
  const fs::path file(written_file(out.path));
  std::error_code error;
  // The console's own file (--report /dev/stdout with stdout sent to a file): the report and
  // the console lines would overwrite each other.
  struct stat target {}, console {};
  if (!device && ::stat(out.path.c_str(), &target) == 0)
    for (int fd : {STDOUT_FILENO, STDERR_FILENO})
      if (::fstat(fd, &console) == 0 && console.st_dev == target.st_dev && console.st_ino == target.st_ino)
        throw InputError(fmt::format("{} {} is where lrvd's console lines go too; write it to a file of its own",
                                     out.option, out.path));
  // A device or a named pipe is written as it is, unprobed: opening a pipe to probe it would
  // block without a reader, or end the reader's input.
  if (fs::exists(path, error) && !fs::is_regular_file(path, error)) return;
  // Through a link to a file not made yet, the probe makes the link's target: that goes again,
  // the link stays.
  const bool existed = fs::exists(path, error);
  if (!std::ofstream(out.path, std::ios::app))
    throw InputError(fmt::format("{} {}: the file cannot be written there", out.option, out.path));
  if (!existed) fs::remove(file, error);
  // The writer's part file beside it, or beside the file a link there leads to (mesh_writers.cpp):
  // its longer name may pass the folder's limit.
  const std::string part = file.string() + ".lrvd-part";
  if (fs::is_directory(fs::symlink_status(part, error)))
    throw InputError(fmt::format("{} {}: a folder {} is where its part file (written first, then renamed) goes; "
                                 "remove or rename it",
                                 out.option, out.path, fs::path(part).filename().string()));
  if (!fs::exists(fs::symlink_status(part, error))) {
    if (!std::ofstream(part))
      throw InputError(fmt::format("{} {}: its part file {} (written first, then renamed) cannot be made there ({})",
                                   out.option, out.path, fs::path(part).filename().string(), std::strerror(errno)));
    fs::remove(part, error);
  }
}

}  // namespace

void check_outputs(const std::vector<PlannedOutput>& outputs, const std::vector<ReadFile>& inputs) {
  namespace fs = std::filesystem;
  std::vector<fs::path> seen;
  for (const PlannedOutput& out : outputs) {
    if (out.path.empty()) continue;
    const fs::path path(out.path);
    check_output_name(out);
    std::error_code error;
    for (const ReadFile& in : inputs)
      if (!in.path.empty() && same_file(path, in.path))
        throw InputError(fmt::format("{} {} is {}, which it would overwrite: write to another file", out.option,
                                     out.path, in.what));
    // A character device (/dev/null, a terminal) takes each write as it comes, at no offset: two
    // outputs there, or an output and the console lines, cannot overwrite each other
    // (`-o /dev/null --report /dev/null > /dev/null` keeps nothing, as asked).
    const bool device = fs::is_character_file(path, error);
    for (const fs::path& other : seen)
      if (!device && same_file(path, other))
        throw InputError(fmt::format("{} {} is also another output of this command", out.option, out.path));
    seen.push_back(path);
    probe_output(out, device);
  }
}

std::string shell_word(const std::string& text) {
  const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::string_view("_./+-=:,@%").find(c) != std::string_view::npos;
  });
  if (plain) return text;
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void check_diagram_samples(const Input& input, const std::string& kind) {
  check_diagram_weights(input.samples, kind);
  if (input.refined_from >= 0)
    progress(fmt::format("refined the mesh from {} to {} triangles", input.refined_from, input.mesh.triangle_count()));
}

void write_json(const std::string& path, const nlohmann::json& report) { write_text_file(path, report.dump(2) + '\n'); }

void write_report(const std::string& path, const nlohmann::json& report, const std::vector<std::string>& written) {
  try {
    write_json(path, report);
  } catch (const std::exception&) {
    for (const std::string& output : written) {
      std::error_code error;
      if (!output.empty() && std::filesystem::is_regular_file(written_file(output), error))
        std::filesystem::remove(written_file(output), error);
    }
    throw;
  }
}

void print_quality(const QualityMetrics* quality, bool of_angles) {
  if (!quality) {
    std::printf("quality: not measured (the remesh has no triangles)\n");
    return;
  }
  std::printf("quality: Qmin %.3f Qavg %.3f theta %.1f/%.1f, %.2f%% %s < 30 deg, Hausdorff %.3f%%\n", quality->q_min,
              quality->q_avg, quality->theta_min, quality->theta_max,
              of_angles ? quality->pct_angles_below_30 : quality->pct_triangles_below_30, of_angles ? "angles" : "triangles",
              quality->hausdorff_pct);
}

void progress(const std::string& message) {
  // LRVD_PROGRESS decides when it is set: on unless empty or "0"; else on a terminal only.
  static const bool enabled = [] {
    const char* env = std::getenv("LRVD_PROGRESS");
    if (env) return *env != '\0' && std::string(env) != "0";
    return isatty(STDERR_FILENO) != 0;
  }();
  if (enabled) std::fprintf(stderr, "lrvd: %s\n", message.c_str());
}

}  // namespace lrvd::cli
