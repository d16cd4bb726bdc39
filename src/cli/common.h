// Shared pieces of the subcommands: loading the mesh and the samples, refinement, JSON reports.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "io/mesh_io.h"
#include "metrics/quality.h"
#include "report/report.h"
#include "samples/samples.h"
#include "verification/remesh_check.h"

namespace lrvd::cli {

//! Options every command that reads a mesh and samples shares.
struct InputOptions {
  std::string mesh_path;
  ReadOptions read;           //!< --repair, --weld, --fill-holes
  int count = 0;              //!< -n: random samples
  std::string points_path;    //!< --points: samples from a file
  std::string weights_path;   //!< --weights: one weight per line (or 4th column of --points)
  std::uint64_t seed = 1;
  std::string refine = "auto";  //!< auto | off | a maximum edge length
  //! Called with the mesh as read and the sample count, before refining and sampling: a command's
  //! own bound on the count (remesh: the fewest vertices a mesh of the surface's topology has).
  std::function<void(const SurfaceMesh&, int)> check_count;
};

//! A path as a shell reads it back as one word: as it is when it holds only letters, digits and
//! _ . / + - = : , @ %, else in single quotes (a quote inside as '\'').
std::string shell_word(const std::string& text);

//! The mesh, its repair options, the samples (--points, and with `allow_count` -n and --seed),
//! --weights when the command takes weighted samples (`allow_weights`), --refine.
void add_input_options(CLI::App* cmd, InputOptions& opt, bool allow_count, bool allow_weights = true);
//! --repair, --weld (which implies --repair) and --fill-holes for the mesh file called `what`.
void add_repair_options(CLI::App* cmd, ReadOptions& read, const std::string& what = "the mesh");
//! What --repair, --weld and --fill-holes changed, one "repair: ..." line each (nothing when none is given).
void print_repair(const RepairReport& report, const ReadOptions& read);
//! --seed: decimal digits that fit in 64 bits (CLI11 alone wraps "-1" and clamps longer numbers).
CLI::Validator seed_validator();
//! Refuses an empty file name (`-o ""`), which would otherwise read as "not given".
CLI::Validator path_validator();

//! Reads (and with the repair options repairs) the mesh, checks that doubles can measure it and
//! prints what the repair changed. \throw InputError on any bad input.
LoadedMesh load_mesh(const InputOptions& opt);

//! Reads the mesh, refines it when the samples would crowd its triangles, and makes or reads the
//! samples. \throw InputError on any bad input.
Input load_input(const InputOptions& opt);

//! Weights given for a power diagram (--diagram lrpd, rpd) and only then; says on the progress
//! line when the mesh was refined. \throw InputError otherwise.
void check_diagram_samples(const Input& input, const std::string& kind);

void write_json(const std::string& path, const nlohmann::json& report);
//! write_json for a command's --report, after its outputs `written` (empty paths skipped): when the
//! report cannot be written whole, the regular files among them are removed first (an output
//! without its report is not kept), then the error goes on.
void write_report(const std::string& path, const nlohmann::json& report, const std::vector<std::string>& written);

//! An output file a command will write, with the option that names it and the extensions it may
//! have (none listed: any but those of `refused`).
struct PlannedOutput {
  std::string path;
  const char* option;
  std::vector<std::string> extensions;
  std::vector<std::string> refused = {};
};
//! A file a command reads, with what the user calls it ("the input mesh", "--points").
struct ReadFile {
  std::string path;
  const char* what;
};
//! Refuses, before any work, outputs that could not be written at the end: an extension the
//! writer does not know, a folder that does not exist, a path that is a folder, two outputs on
//! one file, or an output on a file the command reads (also through a link). Empty paths
//! (outputs not asked for, inputs not given) are skipped.
void check_outputs(const std::vector<PlannedOutput>& outputs, const std::vector<ReadFile>& inputs = {});
//! The files of `input` a command reads: the mesh, --points and --weights.
std::vector<ReadFile> read_files(const InputOptions& input);
//! The console line of a remesh's quality, or that it was not measured (null: the remesh has no
//! triangles). The share under 30 degrees is of the angles (`of_angles`) or of the triangles.
void print_quality(const QualityMetrics* quality, bool of_angles);

//! Progress on stderr for long work (when LRVD_PROGRESS is set to anything but "" or "0"; when it is unset, only on a terminal).
void progress(const std::string& message);

}  // namespace lrvd::cli
