// `lrvd compute` and `lrvd verify`: one diagram (LRVD, RVD, LRPD, RPD) of samples on a mesh, its
// cells as a PLY and its verification as a JSON report.
#include "cli/cmd_compute.h"

#include <algorithm>
#include <cstdio>

#include <unistd.h>

#include <fmt/format.h>

#include "cli/common.h"
#include "common/error.h"
#include "diagram/cells_output.h"
#include "io/mesh_writers.h"
#include "predicates/predicates.h"
#include "verification/diagram_check.h"
#include "voronoi/lrvd.h"

namespace lrvd::cli {

namespace {

// Memory of a verified diagram per sample (the diagram, its vertices' enclosures and the checks'
// tables), peak RSS on the elk: 5.4 kB at 200,000 samples (773,882 triangles after refinement)
// and at 500,000 (1.9M triangles).
constexpr double kVerifiedBytesPerSample = 6e3;

// Refuses a verification that would need most of the machine's memory: the system would kill the
// process without a word long before it finished (500,000 samples: 2.7 GB).
void require_memory_for_verification(int samples, bool can_skip) {
  const double physical = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  const double needed = kVerifiedBytesPerSample * samples;
  if (physical > 0 && needed > 0.75 * physical)
    throw InputError(fmt::format("verifying the diagram of {} samples needs about {:.0f} GB, more than three "
                                 "quarters of this machine's {:.0f} GB: use fewer samples{}",
                                 samples, needed / 1e9, physical / 1e9, can_skip ? ", or --no-verify" : ""));
}

struct ComputeOptions {
  InputOptions input;
  std::string kind = "lrvd";
  std::string output, report;
  bool no_verify = false;
};

int run_diagram(const ComputeOptions& opt, bool write_cells) {
  const DiagramKind kind = diagram_kind_from_string(opt.kind);
  check_outputs({{write_cells ? opt.output : std::string(), "-o", {".ply"}}, {opt.report, "--report", {}, kMeshReadExtensions}},
                read_files(opt.input));
  Input input = load_input(opt.input);
  if (!opt.no_verify) require_memory_for_verification(input.samples.size(), write_cells);
  check_diagram_samples(input, opt.kind);

  reset_predicate_stats();
  progress(fmt::format("computing the {} of {} samples", opt.kind, input.samples.size()));
  CellComponents components;
  const Diagram diagram = compute_input_diagram(input, kind, &components);
  if (input.connectivity_refinements > 0)
    std::printf("refined again, the edges halved %s (%s): a cell was in pieces on the coarser triangles; the "
                "samples were made again on these\n",
                input.connectivity_refinements == 1 ? "once" : fmt::format("{} times", input.connectivity_refinements).c_str(),
                counted(input.mesh.triangle_count(), "triangle", "triangles").c_str());
  const int multiple = cells_in_pieces(components);
  nlohmann::json report = compute_report(input, opt.input.mesh_path, opt.kind, diagram, components);

  if (write_cells && !opt.output.empty()) write_cells_ply(opt.output, diagram_polygon_mesh(diagram, input.mesh));

  bool passed = true;
  std::string failures;
  if (!opt.no_verify) {
    // About 25 us a sample on one core, 15 on two (the elk at 50,000 samples: 1.2 s against the
    // diagram's 0.3 s; at 200,000, 5.3 s), so a diagram that takes seconds says what it waits for.
    progress(input.samples.size() >= 100000
                 ? fmt::format("verifying the diagram in exact arithmetic, about {:.0f} s (--no-verify skips it)",
                               std::max(1.0, 3e-5 * input.samples.size()))
                 : std::string("verifying"));
    const DiagramVerification check = verify_diagram(input.mesh, input.samples, diagram);
    report["verification"] = check.to_json();
    passed = check.passed;
    failures = check.summary();
  } else {
    report["verification"] = nullptr;
  }
  if (!opt.report.empty()) write_report(opt.report, report, {write_cells ? opt.output : std::string()});

  std::printf("%s: %s on %s, %s, %s in several pieces, %.3f s\n", opt.kind.c_str(),
              counted(input.samples.size(), "sample", "samples").c_str(),
              counted(input.mesh.triangle_count(), "triangle", "triangles").c_str(),
              counted(diagram.polygons.size(), "polygon", "polygons").c_str(), counted(multiple, "cell", "cells").c_str(),
              diagram.stats.time_s);
  if (opt.no_verify) {
    std::printf("verification: skipped (--no-verify)\n");
    return kOk;
  }
  std::printf("verification: %s\n", passed ? "passed" : "FAILED");
  if (!failures.empty()) std::fputs(failures.c_str(), stdout);
  return passed ? kOk : kCheckFailed;
}

void add_diagram_options(CLI::App* cmd, ComputeOptions& opt) {
  cmd->add_option("--diagram", opt.kind, "Diagram: lrvd, rvd, lrpd (power, weighted) or rpd")
      ->check(CLI::IsMember({"lrvd", "rvd", "lrpd", "rpd"}))
      ->capture_default_str();
  cmd->add_option("--report", opt.report, "Write a JSON report")->check(path_validator());
}

}  // namespace

Action add_compute_command(CLI::App& app) {
  auto opt = std::make_shared<ComputeOptions>();
  CLI::App* cmd = app.add_subcommand("compute", "Compute a diagram of samples on a mesh, write its cells, verify it");
  add_input_options(cmd, opt->input, true);
  add_diagram_options(cmd, *opt);
  cmd->add_option("-o,--output", opt->output, "Write the cells as a PLY (face property 'cell' and a colour)")
      ->check(path_validator());
  cmd->add_flag("--no-verify", opt->no_verify, "Skip the verification");
  return [opt]() { return run_diagram(*opt, true); };
}

Action add_verify_command(CLI::App& app) {
  auto opt = std::make_shared<ComputeOptions>();
  CLI::App* cmd = app.add_subcommand("verify", "Compute the diagram of your points and check all its properties");
  add_input_options(cmd, opt->input, false);
  add_diagram_options(cmd, *opt);
  return [opt]() { return run_diagram(*opt, false); };
}

}  // namespace lrvd::cli
