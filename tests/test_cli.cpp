// The `lrvd` command line: exit codes (0 done, 2 bad input, 3 a promised property failed), one-line
// errors, and the report keys the issue texts promise.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "io/mesh_io.h"
#include "io/mesh_writers.h"
#include "mesh/closest_point.h"
#include "remesh/remesh_pipeline.h"
#include "test_meshes.h"

using nlohmann::json;

namespace {

const std::string kCli = LRVD_CLI_PATH;
const std::string kData = LRVD_CGAL_DATA_DIR;
const std::string kOut = std::string(LRVD_BINARY_DIR) + "/test_cli_";

struct Run {
  int status;
  std::string err, out;
};

std::string take_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  in.close();
  std::remove(path.c_str());
  return text.str();
}

Run run(const std::string& args) {
  // CTest runs test cases in parallel, each in its own process: one stderr and stdout file per process.
  const std::string err_path = kOut + "stderr_" + std::to_string(getpid()) + ".txt";
  const std::string out_path = kOut + "stdout_" + std::to_string(getpid()) + ".txt";
  const int raw = std::system((kCli + " " + args + " > " + out_path + " 2> " + err_path).c_str());
  const std::string err = take_file(err_path), out = take_file(out_path);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, err, out};
}

json read_json(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  return json::parse(in);
}

int lines(const std::string& s) {
  int count = 0;
  for (char c : s) count += c == '\n';
  return count;
}

}  // namespace

TEST_CASE("lrvd compute writes cells and a report with the promised keys", "[cli]") {
  const std::string report = kOut + "compute.json", cells = kOut + "cells.ply";
  const Run r = run("compute " + kData + "/elk.off -n 100 --seed 3 -o " + cells + " --report " + report);
  REQUIRE(r.status == 0);
  const json j = read_json(report);
  for (const char* key : {"vertices", "triangles", "area", "bbox_diagonal"}) REQUIRE(j["input"].contains(key));
  for (const char* key : {"kind", "samples", "polygons", "cells_with_multiple_components", "time_s",
                          "connectivity_rounds", "forbidden_labels", "pinned_labels"})
    REQUIRE(j["diagram"].contains(key));
  for (const char* key : {"calls", "filter_failures", "exact", "perturbations"}) REQUIRE(j["predicates"].contains(key));
  REQUIRE(j["verification"]["passed"] == true);
  for (const char* key : {"sample_in_cell", "connected", "equidistant", "disjoint", "coverage", "conforming"})
    REQUIRE(j["verification"]["properties"][key]["passed"] == true);
  REQUIRE(j["diagram"]["samples"] == 100);
  REQUIRE(j["diagram"]["cells_with_multiple_components"] == 0);
  std::ifstream ply(cells);
  std::string header;
  std::getline(ply, header);
  REQUIRE(header == "ply");
}

TEST_CASE("lrvd compute says when it refined again because a cell was in pieces, and reports it", "[cli]") {
  // A box folded flat (six corners in the plane x = 0): on the automatic refinement's triangles
  // the LRVD of these samples leaves a cell in pieces (docs/algorithms/lrvd.md).
  const std::string mesh = kOut + "folded_box.off", report = kOut + "folded_box.json";
  {
    std::ofstream off(mesh);
    off << "OFF\n8 12 0\n0 10.25 47\n0 0 -256\n0 257 256\n0 192 0\n192 0 0\n0 0 257\n256 0 5\n0 256 1\n"
           "3 0 1 2\n3 0 2 3\n3 4 5 6\n3 4 6 7\n3 0 3 5\n3 0 5 4\n3 3 2 6\n3 3 6 5\n3 2 1 7\n3 2 7 6\n"
           "3 1 0 4\n3 1 4 7\n";
  }
  const Run r = run("compute " + mesh + " -n 16 --seed 7 --report " + report);
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("refined again, the edges halved once") != std::string::npos);
  CHECK(r.out.find("verification: passed") != std::string::npos);
  const json j = read_json(report);
  CHECK(j["input"]["refined"]["halved_for_connected_cells"] == 1);
  CHECK(j["diagram"]["cells_with_multiple_components"] == 0);
  // Refined as the user says, it is computed once and judged as it is.
  const Run given = run("compute " + mesh + " -n 16 --seed 7 --refine 200");
  CHECK(given.out.find("refined again") == std::string::npos);
  std::remove(mesh.c_str());
  std::remove(report.c_str());
}

TEST_CASE("Point and weight files: a byte-order mark and comments are read, stray columns and NUL bytes named", "[cli]") {
  const std::string cube = kOut + "pw_cube.off", points = kOut + "pw.xyz", weights = kOut + "pw_w.txt";
  std::ofstream(cube) << "OFF\n8 12 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
                         "3 0 2 3\n3 0 3 1\n3 4 5 7\n3 4 7 6\n3 2 6 7\n3 2 7 3\n3 0 4 6\n3 0 6 2\n3 1 3 7\n3 1 7 5\n"
                         "3 0 1 5\n3 0 5 4\n";
  std::ofstream(points) << "\xEF\xBB\xBF" "0.5 0.5 0\n0.5 0.5 1\n# a comment\n0.5 0 0.5\n";
  std::ofstream(weights) << "# weights\n0.01\n\n0.02\n0.03\n";
  const Run ok = run("compute " + cube + " --points " + points + " --weights " + weights + " --diagram rpd");
  INFO(ok.err);
  REQUIRE(ok.status == 0);
  std::ofstream(weights) << "0.01 0.02\n0.03\n";
  const Run two = run("compute " + cube + " --points " + points + " --weights " + weights + " --diagram rpd");
  REQUIRE(two.status == 2);
  REQUIRE(lines(two.err) == 1);
  CHECK(two.err.find("pw_w.txt:1: expected one weight a line, got '0.02' after it") != std::string::npos);
  std::ofstream(weights) << "0.01\n0.02\n";
  const Run few = run("compute " + cube + " --points " + points + " --weights " + weights + " --diagram rpd");
  REQUIRE(few.status == 2);
  CHECK(few.err.find("pw_w.txt: 2 weights were given for the 3 points of") != std::string::npos);
  std::ofstream(points, std::ios::binary) << std::string("0.5 0.5 0\n0\0 1 1\n", 17);
  const Run nul = run("compute " + cube + " --points " + points);
  REQUIRE(nul.status == 2);
  REQUIRE(lines(nul.err) == 1);
  CHECK(nul.err.find("pw.xyz:2: '0\\x00' is not a number") != std::string::npos);
}

TEST_CASE("lrvd refuses bad input with one line and exit status 2", "[cli]") {
  const std::string points = kOut + "far.xyz";
  std::ofstream(points) << "0 0 1000\n";
  // A tetrahedron 1e77 across: its squared distances overflow in the exact predicates' filters.
  const std::string huge = kOut + "huge.off", huge_points = kOut + "huge.xyz", a_file = kOut + "not_a_folder";
  std::ofstream(huge) << "OFF\n4 4 0\n0 0 0\n1e77 0 0\n0 1e77 0\n0 0 1e77\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  std::ofstream(huge_points) << "2e76 2e76 6e76\n";
  std::ofstream(a_file) << "x\n";
  for (const std::string& args :
       {std::string("compute ") + kData + "/missing.off -n 10", "compute " + kData + "/elk.off -n 0",
        "compute " + kData + "/elk.off --points " + points, "compute " + kData + "/elk.off -n 10 --diagram lrpd",
        "compute " + kData + "/elk.off -n 10 --refine banana", "remesh " + kData + "/elk.off -n 10",
        // The elk is a torus: no triangle mesh of it has fewer than 7 vertices.
        "remesh " + kData + "/elk.off -n 6 -o " + kOut + "elk_6.off",
        // More than memory allows: refused before sampling or refining, not an exhausted machine.
        "compute " + kData + "/elk.off -n 100000000", "compute " + kData + "/elk.off -n 1000 --refine 0.001",
        std::string("stress nosuchmesh -o x.off"), std::string("nosuchcommand"),
        "verify " + huge + " --points " + huge_points, "compute " + huge + " -n 10",
        "compute " + kData + "/elk.off -n 10 --seed -1", "compute " + kData + "/elk.off -n 10 --seed 99999999999999999999999",
        "mps " + kData + "/elk.off --radius 1e154 -o " + kOut + "huge_radius.xyz",
        "stress --report " + a_file + " --scale 0.05",
        // Outputs that could not be written are refused before the work, not after it.
        "remesh " + kData + "/elk.off -n 200 -o " + kOut + "elk.stl",
        "remesh " + kData + "/elk.off -n 200 -o " + kOut + "no_such_folder/elk.off",
        "compute " + kData + "/elk.off -n 20 -o " + kOut + "cells.off",
        "mps " + kData + "/elk.off --radius 0.05 -o " + kOut + "same.json --report " + kOut + "same.json"}) {
    const Run r = run(args);
    INFO(args << "\n" << r.err);
    REQUIRE(r.status == 2);
    REQUIRE(r.err.find("lrvd: error:") != std::string::npos);
    REQUIRE(lines(r.err) >= 1);
    if (args.rfind("nosuch", 0) != 0) REQUIRE(lines(r.err) == 1);
  }
  // A model whose coordinates step too coarsely for its size (1/16 at 3e14, on a sphere 40
  // across): refused before any point is constructed on it, by the command line's check; the
  // refinement's own message for such a case (a zero-area triangle from rounded midpoints, naming
  // the splitting) is tested on the library in test_surface_mesh.cpp.
  {
    const lrvd::SurfaceMesh sphere = lrvd::test::icosphere(3);
    std::vector<lrvd::Vec3> far = sphere.positions();
    for (lrvd::Vec3& p : far) p = p * 20.0 + lrvd::Vec3{3e14, 3e14, 3e14};
    const std::string far_sphere = kOut + "far_sphere.off";
    lrvd::write_mesh(far_sphere, far, sphere.triangles());
    for (const std::string& args : {"remesh " + far_sphere + " -n 50 --refine 0.3 -o " + kOut + "far_remesh.off",
                                    "mps " + far_sphere + " --radius 0.00375 -o " + kOut + "far_mps.xyz"}) {
      const Run r = run(args);
      INFO(args << "\n" << r.err);
      REQUIRE(r.status == 2);
      REQUIRE(lines(r.err) == 1);
      REQUIRE(r.err.find("doubles step by 0.0625") != std::string::npos);
      REQUIRE(r.err.find("move the model nearer the origin") != std::string::npos);
    }
  }
}

TEST_CASE("lrvd words the command line's mistakes itself, in one line", "[cli]") {
  const std::string points = kOut + "words.xyz";
  std::ofstream(points) << "0 0 1000\n";
  REQUIRE(run("nosuchcommand").err.find("unknown subcommand 'nosuchcommand'") != std::string::npos);
  REQUIRE(run("--threads 1 compute " + kData + "/elk.off -n 10 --threads 2").err ==
          "lrvd: error: --threads is given 2 times; give it once (see --help)\n");
  // Text or an overflowing count for -n: one line of lrvd's, not CLI11's "Could not convert".
  // Text for a number option: lrvd's words, not CLI11's "Could not convert: --radius = abc".
  REQUIRE(run("mps " + kData + "/elk.off --radius abc -o " + kOut + "x.xyz").err ==
          "lrvd: error: --radius takes a number, not 'abc' (see --help)\n");
  REQUIRE(run("compute " + kData + "/elk.off -n abc").err.find("a sample count (-n) is a whole number, not 'abc'") !=
          std::string::npos);
  REQUIRE(run("compute " + kData + "/elk.off -n 99999999999").err.find("99999999999 samples are more than lrvd takes") !=
          std::string::npos);
  REQUIRE(run("quality " + kData + "/elk.off").err.find("give the mesh to measure after the reference") !=
          std::string::npos);
  // CLI11's wording where it read oddly: the words it did not expect in their order, a value
  // missing, a thread count that is no number.
  REQUIRE(run("verify " + kData + "/elk.off --points " + points + " --seed 3").err ==
          "lrvd: error: unexpected arguments: --seed 3 (this command does not take them) (see --help)\n");
  REQUIRE(run("compute " + kData + "/elk.off -n").err == "lrvd: error: --samples needs a value (see --help)\n");
  REQUIRE(run("--threads abc compute " + kData + "/elk.off -n 3").err.find("a thread count is a whole number") !=
          std::string::npos);
  REQUIRE(run("verify " + kData + "/elk.off --points " + kData).err.find("is a folder") != std::string::npos);
}

TEST_CASE("lrvd checks where its outputs go before the work: not the console's file, not an unwritable one", "[cli]") {
  // The report on the console's own file: the two would overwrite each other.
  const Run console = run("compute " + kData + "/elk.off -n 10 --no-verify --report /dev/stdout");
  REQUIRE(console.status == 2);
  REQUIRE(console.err.find("is where lrvd's console lines go too") != std::string::npos);
  // /dev/null for every output and for the console lines, as a benchmark discards them: nothing
  // there can overwrite anything, so nothing is refused.
  REQUIRE(std::system((kCli + " mps " + kData + "/elk.off --radius 0.05 -o /dev/null --report /dev/null > /dev/null 2>&1")
                          .c_str()) == 0);
  // A report no one can write (not even root, under /proc): refused before the remesh, whose mesh
  // is then not written either.
  const std::string unwritten = kOut + "unwritten.off";
  std::remove(unwritten.c_str());
  const Run proc = run("remesh " + kData + "/elk.off -n 300 -o " + unwritten + " --report /proc/lrvd_report.json");
  REQUIRE(proc.status == 2);
  REQUIRE(proc.err.find("cannot be written") != std::string::npos);
  REQUIRE_FALSE(std::ifstream(unwritten).good());
}

TEST_CASE("lrvd refuses an output on a file it reads, also through a link, and leaves that file as it was", "[cli]") {
  const std::string mesh = kOut + "own_input.off", points = kOut + "own_points.xyz", link = kOut + "own_link.off";
  const std::string elk_text = [&] {
    std::ifstream in(kData + "/elk.off");
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }();
  std::ofstream(mesh) << elk_text;
  std::ofstream(points) << "0.5 0.5 0.5\n";
  const std::string json_link = kOut + "own_link.json";
  for (const std::string& l : {link, json_link}) {
    std::remove(l.c_str());
    std::filesystem::create_symlink(std::filesystem::path(mesh).filename(), l);
  }
  struct Case {
    std::string args, expected;
  };
  for (const Case& c :
       {Case{"remesh " + mesh + " -n 100 -o " + mesh, "-o " + mesh + " is the input mesh, which it would overwrite"},
        Case{"remesh " + link + " -n 100 -o " + mesh, "is the input mesh"},
        Case{"remesh " + mesh + " -n 100 -o " + link, "is the input mesh"},
        Case{"verify " + mesh + " --points " + points + " --report " + points, "is the --points file"},
        Case{"mps " + mesh + " --radius 0.05 -o " + kOut + "own.xyz --remesh " + mesh, "is the input mesh"},
        Case{"quality " + kData + "/elk.off " + mesh + " --report " + json_link, "is the measured mesh"}}) {
    const Run r = run(c.args);
    INFO(c.args << "\n" << r.err);
    REQUIRE(r.status == 2);
    REQUIRE(lines(r.err) == 1);
    REQUIRE(r.err.find(c.expected) != std::string::npos);
  }
  std::ifstream in(mesh);
  std::stringstream after;
  after << in.rdbuf();
  REQUIRE(after.str() == elk_text);
  // A link to an output that is not there yet is that output.
  const std::string target = kOut + "own_target.xyz", report_link = kOut + "own_report_link.json";
  std::remove(target.c_str());
  std::remove(report_link.c_str());
  std::filesystem::create_symlink(std::filesystem::path(target).filename(), report_link);
  const Run both = run("mps " + kData + "/elk.off --radius 0.05 -o " + target + " --report " + report_link);
  REQUIRE(both.status == 2);
  REQUIRE(both.err.find("is also another output of this command") != std::string::npos);
  // A report through a link to a file not made yet goes to that file, and the link stays; a run
  // refused after the checks leaves neither the file nor a changed link.
  const Run refused = run("mps " + kData + "/missing.off --radius 0.05 -o " + kOut + "own_s.xyz --report " + report_link);
  REQUIRE(refused.status == 2);
  REQUIRE(std::filesystem::is_symlink(report_link));
  REQUIRE_FALSE(std::filesystem::exists(target));
  const Run through = run("mps " + kData + "/elk.off --radius 0.05 -o " + kOut + "own_s.xyz --report " + report_link);
  REQUIRE(through.status == 0);
  REQUIRE(std::filesystem::is_symlink(report_link));
  REQUIRE(read_json(target)["samples"].get<int>() > 0);
}

namespace {

// A tetrahedron's OFF text: the header and vertices, and the faces.
const std::string kTetrahedron = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
const std::string kTetrahedronFaces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

// A tetrahedron whose faces end with colours, and its file with a comment and a blank line: what
// the OFF reader takes. Named by the test case (CTest runs them in parallel, each its own file).
std::string coloured_tetrahedron(const std::string& name) {
  const std::string path = kOut + name + ".off";
  std::ofstream(path) << kTetrahedron << "3 0 2 1 255 0 0\n3 0 1 3 0.5 0.5 0.5 1\n3 0 3 2\n3 1 2 3\n# the end\n\n";
  return path;
}

}  // namespace

TEST_CASE("lrvd refuses what it would otherwise drop without a word", "[cli]") {
  const std::string& tet = kTetrahedron;
  const std::string& faces = kTetrahedronFaces;
  // A header that declares fewer faces than the file has: CGAL's reader stops at the count.
  const std::string short_header = kOut + "short_header.off", word = kOut + "word_after_face.off";
  const std::string coloured = coloured_tetrahedron("coloured"), bom = kOut + "bom.off";
  std::ofstream(short_header) << "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n" << faces;
  std::ofstream(word) << tet << "3 0 2 1 extra\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  std::ofstream(bom) << "\xef\xbb\xbf" << tet << faces;
  const std::string truncated_stl = kOut + "truncated.stl";
  std::ofstream(truncated_stl) << "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n";
  const std::string empty_weights = kOut + "empty_weights.txt", corners = kOut + "corners.xyz";
  std::ofstream(empty_weights) << "";
  std::ofstream(corners) << "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  // Weights: a word for one, the weights given twice, a weight that is no number, a line of two values.
  const std::string word_weights = kOut + "word_weights.txt", four_weights = kOut + "four_weights.txt";
  const std::string weighted_corners = kOut + "weighted_corners.xyz", nan_corners = kOut + "nan_corners.xyz";
  const std::string two_values = kOut + "two_values.xyz";
  std::ofstream(word_weights) << "0.1\nabc\n0.1\n0.1\n";
  std::ofstream(four_weights) << "0.1\n0.1\n0.1\n0.1\n";
  std::ofstream(weighted_corners) << "0 0 0 0.1\n1 0 0 0.1\n0 1 0 0.1\n0 0 1 0.1\n";
  std::ofstream(nan_corners) << "0 0 0 0.1\n1 0 0 nan\n0 1 0 0.1\n0 0 1 0.1\n";
  std::ofstream(two_values) << "0 0 0\n1 0\n";
  // Outputs: a folder, a report named as a mesh, a folder where the part file would go.
  const std::string folder = kOut + "output_folder", blocked = kOut + "blocked.ply";
  std::filesystem::create_directories(folder);
  std::filesystem::create_directories(blocked + ".lrvd-part");
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"compute " + short_header + " -n 10", "more than its 1 declared faces"},
      {"compute " + word + " -n 10", "'extra' after its 3 vertex indices"},
      {"compute " + bom + " -n 10", "byte-order mark"},
      {"compute " + coloured + " -n 10 -o ''", "--output: a file name may not be empty"},
      {"compute " + coloured + " -n 10 --report ''", "--report: a file name may not be empty"},
      {"mps " + coloured + " --radius 0.2 -o " + kOut + "m.xyz --remesh ''", "--remesh: a file name may not be empty"},
      {"compute " + coloured + " --points " + corners + " --weights " + empty_weights + " --diagram lrpd",
       "holds no weights"},
      {"stress --report " + kOut + "no_such_folder/report", "does not exist"},
      {"compute " + truncated_stl + " -n 5", "no complete facet"},
      {"compute " + coloured + " --points " + corners + " --weights " + word_weights + " --diagram lrpd",
       "word_weights.txt:2: 'abc' is not a finite number"},
      {"compute " + coloured + " --points " + weighted_corners + " --weights " + four_weights + " --diagram lrpd",
       "the weights are given twice: in the 4th column of " + weighted_corners + " and in --weights " + four_weights},
      {"compute " + coloured + " --points " + nan_corners + " --diagram lrpd",
       "nan_corners.xyz: point 1 (line 2) has a non-finite weight"},
      {"compute " + coloured + " --points " + two_values, "two_values.xyz:2: expected 'x y z' or 'x y z w', got 2 values"},
      {"compute " + coloured + " --points " + weighted_corners + " --diagram rvd",
       "weights were given but --diagram rvd is not a power diagram (use lrpd or rpd)"},
      {"compute " + coloured + " -n 4 --weights " + four_weights,
       "weights were given but --diagram lrvd is not a power diagram"},
      {"mps " + coloured + " --radius 0.2 -o " + folder, "-o " + folder + " is a folder, not a file"},
      {"compute " + coloured + " -n 4 --report " + kOut + "report.off",
       "--report " + kOut + "report.off: this output is not a mesh, and a '.off' file would pass for one"},
      {"compute " + coloured + " -n 4 -o " + blocked,
       "a folder " + std::filesystem::path(blocked).filename().string() +
           ".lrvd-part is where its part file (written first, then renamed) goes; remove or rename it"}};
  for (const auto& [args, reason] : refused) {
    const Run r = run(args);
    INFO(args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(lines(r.err) == 1);
    CHECK(r.err.find(reason) != std::string::npos);
  }
  CHECK(run("compute " + coloured + " -n 10").status == 0);  // colours after the indices, comments after the faces
  CHECK(run("compute " + coloured + " --points " + weighted_corners + " --diagram lrpd").status == 0);  // the weighted corners --diagram rvd refuses above, as a power diagram
  CHECK_FALSE(std::filesystem::exists(kOut + "report.off"));
  std::filesystem::remove_all(folder);
  std::filesystem::remove_all(blocked + ".lrvd-part");
}

// A vertex no face uses is left out with a line that says so (it would otherwise widen the
// bounding box, the unit of mps --radius, without a word).
TEST_CASE("lrvd leaves out a vertex no face uses, with a line that says so", "[cli]") {
  const std::string stray = kOut + "stray_vertex.off", coloured = coloured_tetrahedron("coloured_stray");
  std::ofstream(stray) << "OFF\n5 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n5 5 5\n" << kTetrahedronFaces;
  const Run left_out = run("compute " + stray + " -n 10 --report " + kOut + "stray.json");
  CHECK(left_out.status == 0);
  CHECK(left_out.out.find("input: left out 1 vertex that no face uses") != std::string::npos);
  CHECK(read_json(kOut + "stray.json")["input"]["vertices"] == 4);
  CHECK(run("compute " + coloured + " -n 10").out.find("left out") == std::string::npos);
}

TEST_CASE("lrvd shows the lines it quotes from files safely", "[cli]") {
  const std::string coloured = coloured_tetrahedron("coloured_quoted");
  // A control character read from a file is shown escaped; a huge token does not make a huge line.
  const std::string escape = kOut + "escape.xyz", long_token = kOut + "long_token.xyz";
  std::ofstream(escape) << "0.1\x1b[31mRED 0 0\n";
  std::ofstream(long_token) << std::string(100000, 'x') << " 0 0\n";
  const Run esc = run("verify " + coloured + " --points " + escape);
  CHECK(esc.status == 2);
  CHECK(esc.err.find('\x1b') == std::string::npos);
  CHECK(esc.err.find("\\x1b[31mRED") != std::string::npos);
  // So is a byte that is no UTF-8 (a flipped bit in a number); a UTF-8 name is shown as it is.
  const std::string binary = kOut + "binary.xyz", named = kOut + "mod\xc3\xa8le.xyz";
  std::ofstream(binary) << "0.1\xff\xc3 0 0\n";
  const Run bin = run("verify " + coloured + " --points " + binary);
  CHECK(bin.status == 2);
  CHECK(bin.err.find('\xff') == std::string::npos);
  CHECK(bin.err.find("0.1\\xff\\xc3") != std::string::npos);
  const Run missing = run("verify " + coloured + " --points " + named);
  CHECK(missing.status == 2);
  CHECK(missing.err.find("mod\xc3\xa8le.xyz") != std::string::npos);
  const Run longer = run("verify " + coloured + " --points " + long_token);
  CHECK(longer.status == 2);
  CHECK(lines(longer.err) == 1);
  CHECK(longer.err.size() < 500);
}

TEST_CASE("lrvd's outputs replace the old file whole: nothing is left beside it", "[cli]") {
  const std::string coloured = coloured_tetrahedron("coloured_replaced"), out = kOut + "replaced.off";
  std::ofstream(out) << "old\n";
  REQUIRE(run("remesh " + coloured + " -n 8 -o " + out).status == 0);
  CHECK(lrvd::read_mesh(out).mesh.vertex_count() == 8);
  CHECK_FALSE(std::ifstream(out + ".lrvd-part").good());
}

TEST_CASE("lrvd remesh gives exactly N vertices and reports quality and verification", "[cli][remesh]") {
  const std::string report = kOut + "remesh.json", out = kOut + "remesh.off";
  const Run r = run("remesh " + kData + "/ellipsoid.off -n 200 -o " + out + " --report " + report);
  REQUIRE(r.status == 0);
  const json j = read_json(report);
  REQUIRE(j["output"]["vertices"] == 200);
  for (const char* key : {"Qmin", "Qavg", "theta_min", "theta_max", "pct_triangles_below_30", "hausdorff_pct", "rms_pct",
                          "closed_manifold", "genus_preserved", "self_intersections"})
    REQUIRE(j["quality"].contains(key));
  REQUIRE(j["verification"]["passed"] == true);
  for (const char* key : {"iterations", "energy", "time_s"}) REQUIRE(j.contains(key));
  REQUIRE(j["kept_to_sheets"] == false);  // valid at the first run: no second run with samples kept to sheets
  REQUIRE(j["runs"] == 1);
  REQUIRE(j["reallocation_tried"] == 0);
  REQUIRE(j["lloyd_rounds"] == false);  // no defects left, so no runs again with Lloyd rounds
  REQUIRE(j["density_eased"] == false);  // no repair rounds, so no density to ease back
  REQUIRE(j["priority"] == "distance");
  REQUIRE(j["relaxed"]["rounds"] == 0);
  REQUIRE(j["relaxed"]["moved"] == 0);
  // The CPU time by stage: each second in one stage, so the stages add up to the total; the first
  // CVT and the metrics took some, the repair rounds (there were none) none.
  const json& cpu = j["time_cpu_s"];
  double stages = 0;
  for (const char* key : {"prepare", "first_cvt", "repair_round_cvts", "duals_and_defects", "untangle_in_rounds",
                          "polish_and_ease", "fit", "untangle", "other", "checks", "metrics"}) {
    REQUIRE(cpu[key].get<double>() >= 0);
    stages += cpu[key].get<double>();
  }
  REQUIRE(stages == Approx(cpu["total"].get<double>()).epsilon(1e-6));
  REQUIRE(cpu["first_cvt"].get<double>() > 0);
  REQUIRE(cpu["metrics"].get<double>() > 0);
  REQUIRE(j["repair_rounds"] == 0);
  REQUIRE(cpu["repair_round_cvts"].get<double>() == 0);
  // The quality command measures the written file on its own.
  const std::string quality = kOut + "quality.json";
  REQUIRE(run("quality " + kData + "/ellipsoid.off " + out + " --report " + quality).status == 0);
  REQUIRE(read_json(quality)["quality"]["Qmin"] == j["quality"]["Qmin"]);
}

TEST_CASE("lrvd remesh --priority shape raises the worst triangle and says how many vertices it moved", "[cli][remesh]") {
  const std::string report = kOut + "shape.json", out = kOut + "shape.off";
  const std::string distance_report = kOut + "distance.json";
  REQUIRE(run("remesh " + kData + "/ellipsoid.off -n 200 -o " + out + " --report " + distance_report).status == 0);
  const Run r = run("remesh " + kData + "/ellipsoid.off -n 200 --priority shape -o " + out + " --report " + report);
  REQUIRE(r.status == 0);
  const json j = read_json(report), d = read_json(distance_report);
  REQUIRE(j["verification"]["passed"] == true);
  REQUIRE(j["priority"] == "shape");
  REQUIRE(j["relaxed"]["rounds"] == 5);
  CHECK(j["relaxed"]["moved"].get<int>() > 0);
  // The same CVT; only the vertices of the worst triangles moved before the fitting.
  CHECK(j["diagram_evaluations"] == d["diagram_evaluations"]);
  CHECK(j["quality"]["Qmin"].get<double>() > d["quality"]["Qmin"].get<double>());
  const Run bad = run("remesh " + kData + "/ellipsoid.off -n 200 --priority speed -o " + out);
  CHECK(bad.status == 2);
  CHECK(lines(bad.err) == 1);
}

TEST_CASE("lrvd quality says a closed manifold only of a closed reference", "[cli]") {
  const std::string square = kOut + "square.off";
  {
    std::ofstream file(square);
    file << "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
  }
  const Run open = run("quality " + square + " " + square);
  REQUIRE(open.status == 0);
  REQUIRE(open.out.find("manifold (open, as the reference): yes") != std::string::npos);
  REQUIRE(open.out.find("closed manifold") == std::string::npos);
  const Run closed = run("quality " + kData + "/ellipsoid.off " + kData + "/ellipsoid.off");
  REQUIRE(closed.status == 0);
  REQUIRE(closed.out.find("closed manifold: yes") != std::string::npos);
  // A mesh that fails a check (the square is open, the ellipsoid closed): exit 3, report written.
  const std::string report = kOut + "quality_failed.json";
  const Run failed = run("quality " + kData + "/ellipsoid.off " + square + " --report " + report);
  REQUIRE(failed.status == 3);
  REQUIRE(failed.out.find("closed manifold: no") != std::string::npos);
  REQUIRE(failed.out.find("verification: FAILED") != std::string::npos);
  REQUIRE(read_json(report)["verification"]["passed"] == false);
  // A mesh in another unit: its distances are said to measure that, in the console and the report.
  const std::string big = kOut + "square_big.off", big_report = kOut + "quality_big.json";
  std::ofstream(big) << "OFF\n4 2 0\n0 0 0\n1000 0 0\n1000 1000 0\n0 1000 0\n3 0 1 2\n3 0 2 3\n";
  const Run scaled = run("quality " + square + " " + big + " --report " + big_report);
  REQUIRE(scaled.status == 0);  // a valid mesh: the distances are metrics, not checks
  REQUIRE(scaled.out.find("warning: the mesh's bounding box has 1e+03 times the reference's diagonal") !=
          std::string::npos);
  REQUIRE(read_json(big_report)["frame_warning"].get<std::string>().find("one unit and frame") != std::string::npos);
  REQUIRE(open.out.find("warning") == std::string::npos);
  REQUIRE(closed.out.find("warning") == std::string::npos);
  // A vertex no triangle uses fails the vertex count, but the distances do not read it, and nor
  // does the frame: no warning for a stray vertex far away.
  const std::string stray = kOut + "square_stray.off";
  std::ofstream(stray) << "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n500 500 500\n3 0 1 2\n3 0 2 3\n";
  const Run strayed = run("quality " + square + " " + stray);
  REQUIRE(strayed.status == 3);
  REQUIRE(strayed.out.find("used by no triangle") != std::string::npos);
  REQUIRE(strayed.out.find("warning") == std::string::npos);
}

TEST_CASE("lrvd remesh exits 3 and still writes the output when the remesh fails a check", "[cli][remesh]") {
  // The comb's fingers at 100 vertices: too few samples to wrap every finger (paper Fig. 13).
  const std::string comb = kOut + "comb.off", out = kOut + "comb_100.off", report = kOut + "comb.json";
  REQUIRE(run("stress comb -o " + comb + " --scale 0.5").status == 0);
  const Run r = run("remesh " + comb + " -n 100 -o " + out + " --report " + report);
  REQUIRE(r.status == 3);
  const json j = read_json(report);
  REQUIRE(j["verification"]["passed"] == false);
  REQUIRE(j["kept_to_sheets"].is_boolean());  // both runs failed; the one with fewer defects is written
  std::ifstream written(out);
  REQUIRE(written.good());
  // Where the repair gave up: output vertices whose samples lie on the comb, named in the report and
  // in the console's last line.
  const json& left = j["defects_left"];
  const int count = left["topological"]["count"].get<int>() + left["crossing"]["count"].get<int>() +
                    left["cell_topology"]["count"].get<int>();
  REQUIRE((count > 0 || left["euler_characteristic_ok"] == false));
  const lrvd::BoundingBox box = lrvd::read_mesh(comb).mesh.bounding_box();
  const double slack = 1e-9 * box.diagonal();  // samples lie on the surface up to the closest point's rounding
  for (const char* kind : {"topological", "crossing", "cell_topology"}) {
    REQUIRE(left[kind]["first"].size() <= 10);
    REQUIRE(left[kind]["first"].size() <= left[kind]["count"].get<size_t>());
    for (const json& d : left[kind]["first"]) {
      REQUIRE(d["vertex"].get<int>() >= 0);
      REQUIRE(d["vertex"].get<int>() < 100);
      for (int c = 0; c < 3; ++c) {
        REQUIRE(d["position"][c].get<double>() >= box.min[c] - slack);
        REQUIRE(d["position"][c].get<double>() <= box.max[c] + slack);
      }
    }
  }
  REQUIRE(r.out.find("repair: ") != std::string::npos);
  REQUIRE(r.out.find(left["summary"].get<std::string>()) != std::string::npos);
  REQUIRE(r.out.find("more vertices") != std::string::npos);  // what to try next
  // The narrowest part a ring of cells wraps: a finger, whose section is 0.1 x 0.2, so no loop
  // round it is shorter than 0.6; the cells' boundaries zigzag round it within a cell's width
  // (about 0.2 at 100 vertices). Three cells round it at a uniform density need more than 100.
  const json& rings = left["rings"];
  REQUIRE(rings["count"].get<int>() > 0);
  const double around = rings["narrowest"]["around_pct"].get<double>() / 100 * box.diagonal();
  CHECK(around >= 0.6);
  CHECK(around < 0.8);
  const long long needed = rings["narrowest"]["uniform_vertices"].get<long long>();
  CHECK(needed > 100);
  REQUIRE(r.out.find(fmt::format("a uniform density fits three cells round it from about {} vertices (100 given)",
                                 needed)) != std::string::npos);
  // And how to see where: the command it names draws the failed remesh with its defects coloured.
  const std::string picture = kOut + "comb_100_defects.png";
  const std::string see = "see where: lrvd render " + out + " --color defects -o " + picture + "\n";
  REQUIRE(r.out.find(see) != std::string::npos);
  const Run drawn = run("render " + out + " --color defects -o " + picture + " --size 64x64");
  REQUIRE(drawn.status == 0);
  // The comb's failure is non-manifold edges (the report's manifold check): they are coloured.
  const std::size_t at = drawn.out.find(" on non-manifold edges");
  REQUIRE(at != std::string::npos);
  const std::size_t from = drawn.out.rfind(", ", at);
  REQUIRE(std::stoi(drawn.out.substr(from + 2, at - from - 2)) > 0);
  std::remove(picture.c_str());
}

TEST_CASE("lrvd remesh with too few vertices for a mesh at all exits 3 with the checks, not a crash", "[cli][remesh]") {
  // 7 vertices on the elk (a torus) is the bound, but the CVT's dual of 7 cells has no triangle.
  const std::string out = kOut + "elk_7.off", report = kOut + "elk_7.json";
  const Run r = run("remesh " + kData + "/elk.off -n 7 -o " + out + " --report " + report);
  INFO(r.err);
  REQUIRE(r.status == 3);
  const json j = read_json(report);
  REQUIRE(j["verification"]["passed"] == false);
  REQUIRE(j["quality"].is_null());
  REQUIRE(j["output"]["triangles"] == 0);
  // lrvd quality checks that output as it checks any other: exit 3, the same verdict, no metrics;
  // written as OBJ too, whose reader in CGAL refuses a file without faces.
  const std::string obj = kOut + "elk_7.obj";
  REQUIRE(run("remesh " + kData + "/elk.off -n 7 -o " + obj).status == 3);
  const Run q_obj = run("quality " + kData + "/elk.off " + obj);
  INFO(q_obj.err);
  REQUIRE(q_obj.status == 3);
  REQUIRE(q_obj.out.find("quality: not measured (the mesh has no triangles)") != std::string::npos);
  const std::string quality_report = kOut + "elk_7_quality.json";
  const Run q = run("quality " + kData + "/elk.off " + out + " --report " + quality_report);
  INFO(q.err);
  REQUIRE(q.status == 3);
  REQUIRE(q.out.find("7 vertices, 0 triangles") != std::string::npos);
  REQUIRE(q.out.find("quality: not measured (the mesh has no triangles)") != std::string::npos);
  REQUIRE(q.out.find("closed manifold: no") != std::string::npos);
  const json qj = read_json(quality_report);
  REQUIRE(qj["quality"].is_null());
  REQUIRE(qj["verification"]["passed"] == false);
  // A file of vertices alone is still no input to remesh.
  REQUIRE(run("remesh " + out + " -n 7 -o " + kOut + "elk_7_again.off").status == 2);
}

TEST_CASE("lrvd stress lists and writes the stress meshes", "[cli]") {
  REQUIRE(run("stress --list").status == 0);
  const std::string out = kOut + "plate.obj";
  REQUIRE(run("stress thin_plate -o " + out).status == 0);
  std::ifstream in(out);
  REQUIRE(in.good());
  REQUIRE(run("--version").status == 0);
}

TEST_CASE("lrvd refuses a triangle soup naming --repair, and --repair welds it", "[cli]") {
  const std::string soup = std::string(LRVD_SOURCE_DIR) + "/tests/data/soup.off";
  const Run refused = run("compute " + soup + " -n 10");
  REQUIRE(refused.status == 2);
  REQUIRE(refused.err.find("--repair") != std::string::npos);
  REQUIRE(lines(refused.err) == 1);
  const std::string report = kOut + "soup.json";
  REQUIRE(run("compute " + soup + " -n 10 --repair --report " + report).status == 0);
  REQUIRE(read_json(report)["input"]["closed"] == true);
  // What the repair changed, as the console's "repair:" line says it, is in the report too.
  REQUIRE(read_json(report)["input"]["repair_changes"] == json::array({"merged 18 vertices"}));

  // Corners a rounding apart: refused naming --weld, which implies --repair and welds them.
  const std::string jittered = std::string(LRVD_SOURCE_DIR) + "/tests/data/soup_jittered.off";
  const Run near = run("compute " + jittered + " -n 10");
  REQUIRE(near.status == 2);
  REQUIRE(lines(near.err) == 1);
  REQUIRE(near.err.find("rerun with --repair --weld 1e-09") != std::string::npos);
  const Run welded = run("compute " + jittered + " -n 10 --weld 1e-9 --report " + report);
  INFO(welded.err);
  REQUIRE(welded.status == 0);
  REQUIRE(welded.out.find("repair: welded 18 vertices") != std::string::npos);
  REQUIRE(read_json(report)["input"]["closed"] == true);
  REQUIRE(read_json(report)["input"]["vertices"] == 6);
  for (const char* bad : {"0", "-1e-6", "x", "inf"}) REQUIRE(run("compute " + jittered + " -n 10 --weld " + bad).status == 2);
}

TEST_CASE("lrvd gives the same output with one thread and with several", "[cli][remesh]") {
  // The diagram clips triangles in parallel and integrates cells in parallel, but every decision
  // and every sum is made in a fixed order.
  const std::string one = kOut + "threads1.off", two = kOut + "threads2.off";
  REQUIRE(run("--threads 1 remesh " + kData + "/elk.off -n 200 -o " + one).status == 0);
  REQUIRE(run("remesh " + kData + "/elk.off -n 200 -o " + two + " --threads 2").status == 0);
  std::ifstream a(one), b(two);
  std::stringstream ta, tb;
  ta << a.rdbuf();
  tb << b.rdbuf();
  REQUIRE(!ta.str().empty());
  REQUIRE(ta.str() == tb.str());
  const Run bad = run("remesh " + kData + "/elk.off -n 200 -o " + one + " --threads 0");
  REQUIRE(bad.status == 2);
  REQUIRE(lines(bad.err) == 1);
}

TEST_CASE("remesh_to (the library call) gives the mesh that lrvd remesh writes also with several components", "[cli][remesh]") {
  // Two spheres side by side: each component gets its share of the samples in both.
  const lrvd::SurfaceMesh two = lrvd::test::merge(lrvd::test::icosphere(3), lrvd::test::icosphere(2), {3, 0, 0});
  REQUIRE(two.component_count() == 2);
  lrvd::write_mesh(kOut + "two_spheres.off", two);
  for (const auto& [path, n] : {std::pair<std::string, int>{kData + "/elk.off", 300}, {kOut + "two_spheres.off", 90}}) {
    INFO(path);
    const lrvd::SurfaceMesh input = lrvd::read_mesh(path).mesh;
    const lrvd::RemeshResult library = lrvd::remesh_to(input, n);
    lrvd::write_mesh(kOut + "remesh_to.off", library.dual.positions, library.dual.triangles);
    const Run cli = run("remesh " + path + " -n " + std::to_string(n) + " -o " + kOut + "remesh_cli.off");
    REQUIRE(cli.status == 0);
    CHECK(take_file(kOut + "remesh_to.off") == take_file(kOut + "remesh_cli.off"));
  }
  REQUIRE_THROWS_AS(lrvd::remesh_to(two, 7), lrvd::InputError);  // two spheres need 4 vertices each
  // Fewer vertices than components: the command names the fewest a remesh has (8), not one each.
  for (const char* n : {"1", "7"}) {
    const Run few = run(std::string("remesh ") + kOut + "two_spheres.off -n " + n + " -o " + kOut + "remesh_cli.off");
    REQUIRE(few.status == 2);
    REQUIRE(lines(few.err) == 1);
    CHECK(few.err.find("has fewer than 8") != std::string::npos);
  }
  REQUIRE_THROWS_WITH(lrvd::remesh_to(two, 4'000'000), Catch::Contains("use fewer vertices"));  // ~16M triangles
  // 2 n overflowed an int past 1.07e9 and the refinement looked unneeded: memory ran out instead.
  REQUIRE_THROWS_WITH(lrvd::remesh_to(two, std::numeric_limits<int>::max()), Catch::Contains("use fewer vertices"));
}

TEST_CASE("docs/guide/library.md shows docs/guide/library_example.cpp as it is", "[cli]") {
  auto read = [](const std::string& name) {  // (take_file would delete it)
    std::ifstream in(std::string(LRVD_SOURCE_DIR) + "/docs/guide/" + name);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  };
  const std::string example = read("library_example.cpp");
  const std::string page = read("library.md");
  REQUIRE_FALSE(example.empty());
  CHECK(page.find("```cpp\n" + example + "```\n") != std::string::npos);
}

TEST_CASE("lrvd fills holes smaller than the cells on request, and lrvd quality measures against the filled reference", "[cli][remesh]") {
  // CGAL's ChineseDragon-10kv has two holes of three edges, 0.15 around at most on a diagonal of
  // 169: a remesh to 200 vertices must keep them and fails after 72 rounds, naming the holes and
  // the --fill-holes fraction that closes them. Filled, the dragon is closed and its remesh valid.
  const std::string dragon = kData + "/ChineseDragon-10kv.off", out = kOut + "dragon_200.off",
                    report = kOut + "dragon_200.json";
  const Run failed = run("remesh " + dragon + " -n 200 --threads 2 -o " + out + " --report " + report);
  REQUIRE(failed.status == 3);
  REQUIRE(failed.out.find("repair: 2 holes are met by fewer than three cells") != std::string::npos);
  const json holes = read_json(report)["defects_left"]["closed_over_holes"];
  REQUIRE(holes["count"] == 2);
  REQUIRE(holes["fillable"] == 2);  // tried on the input
  REQUIRE(holes["longest"].get<double>() == Approx(0.150195).epsilon(1e-5));
  const double fraction = holes["fill_holes"].get<double>();
  REQUIRE(fraction * 169 > 0.150195);
  REQUIRE(fraction < 0.001);
  REQUIRE(failed.out.find(fmt::format("--fill-holes {:.2g} closes them and 0 other holes", fraction)) != std::string::npos);
  const Run r = run("remesh " + dragon + " -n 200 --fill-holes " + fmt::format("{:.2g}", fraction) + " -o " + out +
                    " --report " + report);
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  REQUIRE(r.out.find("repair: filled 2 holes") != std::string::npos);
  const json j = read_json(report);
  REQUIRE(j["input"]["closed"] == true);
  REQUIRE(j["input"]["repair"].size() == 1);
  REQUIRE(j["verification"]["passed"] == true);
  // Against the file as it is, the remesh has lost the two holes; against the filled one it has not.
  REQUIRE(run("quality " + dragon + " " + out).status == 3);
  REQUIRE(run("quality " + dragon + " " + out + " --fill-holes 0.01").status == 0);  // any fraction above the holes
  // A fraction below the holes' size fills nothing and says so.
  const Run none = run("compute " + dragon + " -n 100 --fill-holes 0.0001 --no-verify");
  REQUIRE(none.status == 0);
  REQUIRE(none.out.find("no hole filled: the shortest of the 2 boundary loops is") != std::string::npos);
  // mps takes it too, and its report says what was filled.
  const std::string mps_report = kOut + "holes_mps.json", samples = kOut + "holes_mps.xyz";
  REQUIRE(run("mps " + kData + "/holes.off --radius 0.05 --fill-holes 0.5 -o " + samples + " --report " + mps_report)
              .status == 0);
  const json m = read_json(mps_report);
  REQUIRE(m["input"]["repair"].size() == 1);
  REQUIRE(m["input"]["repair"][0].get<std::string>().find("filled 5 holes") == 0);
  std::remove(samples.c_str());
  for (const char* bad : {"0", "-1", "abc", "nan"}) {
    const Run refused = run("remesh " + dragon + " -n 200 --fill-holes " + std::string(bad) + " -o " + out);
    REQUIRE(refused.status == 2);
    REQUIRE(lines(refused.err) == 1);
  }
  std::remove(out.c_str());
}

TEST_CASE("lrvd verify says when it moved the given points onto the surface, and by how much", "[cli]") {
  // The octahedron |x| + |y| + |z| = 1: two points on it, one 0.02 above a face (along its normal).
  const std::string mesh = kOut + "points_octahedron.off", on = kOut + "points_on.xyz", off = kOut + "points_off.xyz";
  std::ofstream(mesh) << "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
                         "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";
  std::ofstream(on) << "0.25 0.25 0.5\n-0.5 -0.25 -0.25\n";
  const double lift = 0.02 / std::sqrt(3.0);
  std::ofstream(off) << "0.25 0.25 0.5\n" << fmt::format("{:.17g} {:.17g} {:.17g}\n", -0.5 - lift, -0.25 - lift, -0.25 - lift);
  const std::string on_report = kOut + "points_on.json", off_report = kOut + "points_off.json";
  const Run quiet = run("verify " + mesh + " --points " + on + " --report " + on_report);
  REQUIRE(quiet.status == 0);
  REQUIRE(quiet.out.find("points:") == std::string::npos);
  REQUIRE(read_json(on_report)["input"]["points"]["count"] == 2);
  REQUIRE(read_json(on_report)["input"]["points"]["max_move"].get<double>() < 1e-12);
  const Run moved = run("verify " + mesh + " --points " + off + " --report " + off_report);
  REQUIRE(moved.status == 0);
  REQUIRE(moved.out.find("points: 1 of 2 points moved onto the surface, the farthest by 0.02") != std::string::npos);
  const json points = read_json(off_report)["input"]["points"];
  REQUIRE(points["moved"] == 1);
  REQUIRE(points["max_move"].get<double>() == Approx(0.02));
}

TEST_CASE("lrvd refuses a refinement that would pass its triangle limit on a needle, and suggests --refine off", "[cli]") {
  // Splitting the long sides of a needle to the samples' edge length gives pieces as thin as the
  // needle: without a limit on the count itself the split ran until memory was gone.
  const std::string needle = kOut + "needle.off";
  {
    std::ofstream out(needle);
    out << "OFF\n4 4 0\n0 0 0\n1e-9 0 0\n0 1e-9 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
  }
  const Run refused = run("compute " + needle + " -n 4 --threads 2");
  CHECK(refused.status == 2);
  CHECK(lines(refused.err) == 1);
  CHECK_THAT(refused.err, Catch::Contains("far longer than they are wide") && Catch::Contains("--refine off"));
  const Run unrefined = run("compute " + needle + " -n 4 --refine off --threads 2");
  CHECK(unrefined.status == 0);
  std::remove(needle.c_str());
}

TEST_CASE("lrvd works on a tiny model far from the origin and refuses one whose coordinates are too coarse", "[cli]") {
  // A tetrahedron 1e-6 across at 1000 (ten million steps of the doubles across it) remeshes as it
  // does at the origin; a unit one at 1e15, where doubles step by 0.125, gave a "valid" remesh 25 %
  // of its size away from it, and is refused, as by every command that constructs points.
  const std::string tiny = kOut + "tet_tiny_far.off", coarse = kOut + "tet_coarse_far.off", out = kOut + "tet_far_remesh.off";
  {
    std::ofstream a(tiny), b(coarse);
    a << "OFF\n4 4 0\n1000 1000 1000\n1000.000001 1000 1000\n1000 1000.000001 1000\n1000 1000 1000.000001\n"
         "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    b << "OFF\n4 4 0\n1e15 1e15 1e15\n1000000000000001 1e15 1e15\n1e15 1000000000000001 1e15\n1e15 1e15 1000000000000001\n"
         "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  }
  const Run ok = run("remesh " + tiny + " -n 20 --threads 2 -o " + out);
  CHECK(ok.status == 0);
  for (const std::string& command : {"remesh " + coarse + " -n 20 -o " + out, "compute " + coarse + " -n 20",
                                    "mps " + coarse + " --radius 0.1 -o " + kOut + "tet_far.xyz",
                                    "quality " + coarse + " " + tiny}) {
    INFO(command);
    const Run refused = run(command);
    CHECK(refused.status == 2);
    CHECK(lines(refused.err) == 1);
    CHECK_THAT(refused.err, Catch::Contains("doubles step by 0.125") && Catch::Contains("nearer the origin"));
  }
  for (const std::string& f : {tiny, coarse, out}) std::remove(f.c_str());
}

TEST_CASE("lrvd render draws a mesh or a diagram's cells as a PNG, and refuses bad views with one line", "[cli]") {
  // The PNG's size from its header: the IHDR chunk's width and height, big-endian, at bytes 16-23.
  auto png_size = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string head(24, '\0');
    in.read(head.data(), 24);
    REQUIRE(in.gcount() == 24);
    REQUIRE(head.substr(1, 3) == "PNG");
    auto word = [&](int at) {
      unsigned value = 0;
      for (int k = 0; k < 4; ++k) value = value << 8 | static_cast<unsigned char>(head[at + k]);
      return static_cast<int>(value);
    };
    return std::make_pair(word(16), word(20));
  };
  const std::string mesh_png = kOut + "render_mesh.png", cells_png = kOut + "render_cells.png";
  Run r = run("render " + kData + "/elk.off -o " + mesh_png + " --size 320x240 --view 10,30 --up z --edges");
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE(r.out.find("render: 3290 triangles, 320 x 240") != std::string::npos);
  REQUIRE(png_size(mesh_png) == std::make_pair(320, 240));
  r = run("render " + kData + "/elk.off -n 120 --diagram rvd -o " + cells_png + " --size 200x100");
  REQUIRE(r.status == 0);
  REQUIRE(r.out.find("120 rvd cells") != std::string::npos);
  REQUIRE(png_size(cells_png) == std::make_pair(200, 100));
  // A mesh lrvd would not take for a diagram (two tetrahedra sharing an edge: not manifold) is drawn as it is.
  const std::string pinched = kOut + "render_pinched.off";
  std::ofstream(pinched) << "OFF\n6 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n1 0 -1\n"
                            "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 4 1\n3 0 1 5\n3 0 5 4\n3 1 4 5\n";
  REQUIRE(run("compute " + pinched + " -n 5").status == 2);
  r = run("render " + pinched + " --color quality -o " + mesh_png + " --size 64x64");
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE(r.out.find("8 triangles coloured by quality (worst Q") != std::string::npos);
  r = run("render " + pinched + " --color defects -o " + mesh_png + " --size 64x64");
  REQUIRE(r.status == 0);
  REQUIRE(r.out.find("4 on non-manifold edges") != std::string::npos);
  // The cells lrvd compute writes are drawn in their colours.
  const std::string cells_ply = kOut + "render_cells.ply";
  REQUIRE(run("compute " + kData + "/elk.off -n 50 -o " + cells_ply).status == 0);
  r = run("render " + cells_ply + " -o " + mesh_png + " --size 64x64");
  REQUIRE(r.status == 0);
  REQUIRE(r.out.find("in the file's face colours") != std::string::npos);
  std::remove(cells_ply.c_str());
  std::remove(pinched.c_str());
  std::remove(mesh_png.c_str());
  std::remove(cells_png.c_str());
  for (const std::string& args :
       {"render " + kData + "/elk.off -o " + kOut + "r.png --size 100", "render " + kData + "/elk.off -o " + kOut + "r.png --size 9000x100",
        "render " + kData + "/elk.off -o " + kOut + "r.png --view 30", "render " + kData + "/elk.off -o " + kOut + "r.png --view 0,95",
        "render " + kData + "/elk.off -o " + kOut + "r.png --up w", "render " + kData + "/elk.off -o " + kOut + "r.jpg",
        "render " + kData + "/elk.off -n 10 --diagram lrpd -o " + kOut + "r.png",
        "render " + kData + "/elk.off -n 10 --color quality -o " + kOut + "r.png",
        // Options of a diagram without samples are refused, not dropped.
        "render " + kData + "/elk.off -n 0 -o " + kOut + "r.png", "render " + kData + "/elk.off --diagram rvd -o " + kOut + "r.png",
        "render " + kData + "/elk.off --weights " + kOut + "none.txt -o " + kOut + "r.png",
        // A name the folder takes, but not with the part file's suffix: refused before the work.
        "render " + kData + "/elk.off -o " + kOut + std::string(240, 'a') + ".png"}) {
    const Run bad = run(args);
    INFO(args << "\n" << bad.err);
    REQUIRE(bad.status == 2);
    REQUIRE(lines(bad.err) == 1);
    REQUIRE(!std::filesystem::exists(kOut + "r.png"));
  }
}

TEST_CASE("An output is never written through a part file planted as a link to another file", "[cli]") {
  const std::string victim = kOut + "victim.off", out = kOut + "planted.png";
  lrvd::write_mesh(victim, lrvd::test::octahedron());
  const std::string before = [&] { std::ifstream in(victim); std::stringstream t; t << in.rdbuf(); return t.str(); }();
  std::filesystem::remove(out + ".lrvd-part");
  std::filesystem::create_symlink(victim, out + ".lrvd-part");
  const Run r = run("render " + kData + "/elk.off -o " + out + " --size 64x64");
  INFO(r.err);
  REQUIRE(r.status == 0);
  std::ifstream in(victim);
  std::stringstream after;
  after << in.rdbuf();
  REQUIRE(after.str() == before);
  REQUIRE(std::filesystem::is_regular_file(std::filesystem::symlink_status(out)));
  REQUIRE(!std::filesystem::exists(std::filesystem::symlink_status(out + ".lrvd-part")));
  std::remove(victim.c_str());
  std::remove(out.c_str());
}

TEST_CASE("An output through a symbolic link replaces the file it leads to whole, and the link stays", "[cli]") {
  namespace fs = std::filesystem;
  const std::string folder = kOut + "link_target_dir", target = folder + "/target.png", link = kOut + "link_out.png";
  fs::remove_all(folder);
  fs::create_directory(folder);
  fs::remove(link);
  { std::ofstream(target) << "old picture"; }
  fs::create_symlink(fs::path(folder).filename() / "target.png", link);  // relative to the link's folder
  struct stat before {};
  REQUIRE(::stat(target.c_str(), &before) == 0);
  const Run r = run("render " + kData + "/elk.off -o " + link + " --size 64x64");
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE(fs::is_symlink(link));
  struct stat after {};
  REQUIRE(::stat(target.c_str(), &after) == 0);
  CHECK(after.st_ino != before.st_ino);  // replaced by its part file, not rewritten in place
  std::ifstream in(target, std::ios::binary);
  std::string head(8, '\0');
  in.read(head.data(), 8);
  CHECK(head == "\x89PNG\r\n\x1a\n");
  CHECK_FALSE(fs::exists(fs::symlink_status(target + ".lrvd-part")));
  CHECK_FALSE(fs::exists(fs::symlink_status(link + ".lrvd-part")));
  // A link to a file not made yet: the file is made there, by the library's writers too.
  const std::string dangling = kOut + "link_dangling.off", made = folder + "/made.off";
  fs::remove(dangling);
  fs::create_symlink(fs::path(folder).filename() / "made.off", dangling);
  lrvd::write_mesh(dangling, lrvd::test::octahedron());
  REQUIRE(fs::is_symlink(dangling));
  CHECK(lrvd::read_mesh(made).mesh.triangle_count() == 8);
  fs::remove(link);
  fs::remove(dangling);
  fs::remove_all(folder);
}

TEST_CASE("Outputs: one new file under two spellings is refused, links that lead nowhere are named, permissions stay", "[cli]") {
  namespace fs = std::filesystem;
  const std::string dir = kOut + "spellings";
  fs::remove_all(dir);
  fs::create_directories(dir + "/s");
  // Run from inside `dir`, so that a bare name is relative to it.
  auto run_in = [&](const std::string& args) {
    const std::string err_path = dir + "/stderr.txt";
    const int raw = std::system(("cd " + dir + " && " + kCli + " " + args + " > /dev/null 2> " + err_path).c_str());
    return Run{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, take_file(err_path), ""};
  };
  const std::string mps = "mps " + kData + "/elk.off --radius 0.05 -o n.xyz --report ";
  for (const std::string& report : {std::string("./n.xyz"), dir + "/n.xyz", std::string("s/../n.xyz")}) {
    const Run r = run_in(mps + report);
    INFO(report << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("is also another output of this command") != std::string::npos);
  }
  fs::create_symlink("../n.xyz", dir + "/s/rep.json");  // the report through a link to the samples' file
  const Run linked = run_in(mps + "s/rep.json");
  CHECK(linked.status == 2);
  CHECK(linked.err.find("is also another output of this command") != std::string::npos);
  CHECK_FALSE(fs::exists(dir + "/n.xyz"));
  // A loop of links, and a link into a folder that is not there.
  fs::create_symlink("b.png", dir + "/a.png");
  fs::create_symlink("a.png", dir + "/b.png");
  const Run loop = run_in("render " + kData + "/elk.off --size 32x32 -o a.png");
  CHECK(loop.status == 2);
  CHECK(loop.err.find("-o a.png is a loop of symbolic links") != std::string::npos);
  fs::create_symlink("nowhere/x.png", dir + "/far.png");
  const Run far = run_in("render " + kData + "/elk.off --size 32x32 -o far.png");
  CHECK(far.status == 2);
  CHECK(far.err.find("-o far.png is a symbolic link to nowhere/x.png, whose folder does not exist") != std::string::npos);
  // A file replaced keeps its permissions.
  { std::ofstream(dir + "/private.png") << "old"; }
  fs::permissions(dir + "/private.png", fs::perms::owner_read | fs::perms::owner_write);
  const Run kept = run_in("render " + kData + "/elk.off --size 32x32 -o private.png");
  CHECK(kept.status == 0);
  CHECK(fs::status(dir + "/private.png").permissions() == (fs::perms::owner_read | fs::perms::owner_write));
  fs::remove_all(dir);
}

TEST_CASE("lrvd stress --report writes the RVD-vs-LRVD tables and a picture of each diagram", "[cli]") {
  const std::string dir = kOut + "stress_report_dir";
  std::filesystem::remove_all(dir);
  const Run r = run("stress --report " + dir + " --scale 0.2 --seeds 2");
  INFO(r.err);
  REQUIRE(r.status == 0);  // every LRVD verified
  std::ifstream md_file(dir + "/stress_report.md");
  std::stringstream md;
  md << md_file.rdbuf();
  REQUIRE(md.str().find("## Pictures") != std::string::npos);
  const json j = read_json(dir + "/stress_report.json");
  REQUIRE(j["rows"].size() >= 8);
  REQUIRE(j["seeds"] == 2);
  for (const json& row : j["rows"]) {
    REQUIRE(row["seeds"] == 2);
    REQUIRE(row["lrvd_verified"] == 2);  // each of the two diagrams verified
  }
  for (const std::string name : {"thin_plate", "folded_sheet", "open_cup", "flat_ellipsoid", "knot_tube", "comb",
                                  "interpenetrating_spheres", "thin_tube"})
    for (const char* kind : {"lrvd", "rvd"}) {
      const std::string png = name + "_" + kind + ".png";
      INFO(png);
      REQUIRE(md.str().find("(" + png + ")") != std::string::npos);
      std::ifstream in(dir + "/" + png, std::ios::binary);
      std::string head(8, '\0');
      in.read(head.data(), 8);
      REQUIRE(head == std::string("\x89PNG\r\n\x1a\n", 8));
    }
  std::filesystem::remove_all(dir);
}

TEST_CASE("lrvd compute takes --weights for random samples and names both counts when they differ", "[cli]") {
  const std::string twenty = kOut + "weights_20.txt", nineteen = kOut + "weights_19.txt", report = kOut + "weights_n.json";
  {
    std::ofstream a(twenty), b(nineteen);
    for (int i = 0; i < 20; ++i) a << 0.001 * (i % 3) << "\n";
    for (int i = 0; i < 19; ++i) b << "0\n";
  }
  const Run ok = run("compute " + kData + "/elk.off -n 20 --weights " + twenty + " --diagram lrpd --report " + report);
  INFO(ok.err);
  REQUIRE(ok.status == 0);
  REQUIRE(ok.out.find("verification: passed") != std::string::npos);
  const json j = read_json(report);
  REQUIRE(j["diagram"]["kind"] == "lrpd");
  REQUIRE(j["diagram"]["samples"] == 20);
  REQUIRE(j["verification"]["passed"] == true);
  const Run few = run("compute " + kData + "/elk.off -n 20 --weights " + nineteen + " --diagram lrpd");
  REQUIRE(few.status == 2);
  REQUIRE(few.err == "lrvd: error: " + nineteen + ": 19 weights were given for 20 samples\n");
  for (const std::string& f : {twenty, nineteen, report}) std::remove(f.c_str());
}

TEST_CASE("lrvd remesh refuses weighted samples from a 4th column and takes no --weights option", "[cli][remesh]") {
  // 30 of the ellipsoid's vertices, more than the fewest a sphere's remesh needs (4), each with a
  // weight: loaded and located, then refused, since a CVT's samples have none.
  const lrvd::SurfaceMesh ellipsoid = lrvd::read_mesh(kData + "/ellipsoid.off").mesh;
  const std::string weighted = kOut + "weighted30.xyz", plain = kOut + "plain30.xyz", out = kOut + "weighted30.off";
  {
    std::ofstream w(weighted), p(plain);
    for (int v = 0; v < 30; ++v) {
      const lrvd::Vec3& q = ellipsoid.position(v);
      w << fmt::format("{:.17g} {:.17g} {:.17g} 0.001\n", q.x, q.y, q.z);
      p << fmt::format("{:.17g} {:.17g} {:.17g}\n", q.x, q.y, q.z);
    }
  }
  std::remove(out.c_str());
  const Run refused = run("remesh " + kData + "/ellipsoid.off --points " + weighted + " -o " + out);
  REQUIRE(refused.status == 2);
  REQUIRE(refused.err ==
          "lrvd: error: remesh computes a CVT of unweighted samples: weights (--weights or a 4th column in --points) "
          "do not apply\n");
  REQUIRE_FALSE(std::filesystem::exists(out));
  // The same points without the column remesh (30 vertices, as many as the points).
  const Run ok = run("remesh " + kData + "/ellipsoid.off --points " + plain + " -o " + out);
  INFO(ok.err);
  REQUIRE(ok.status == 0);
  REQUIRE(lrvd::read_mesh(out).mesh.vertex_count() == 30);
  // --weights is not a remesh option at all: the parser refuses it before anything is read.
  const Run option = run("remesh " + kData + "/ellipsoid.off --points " + plain + " --weights " + plain + " -o " + out);
  REQUIRE(option.status == 2);
  REQUIRE(lines(option.err) == 1);
  REQUIRE(option.err.find("unexpected arguments: --weights") != std::string::npos);
  for (const std::string& f : {weighted, plain, out}) std::remove(f.c_str());
}

TEST_CASE("lrvd remesh uses and reports --optimizer lloyd and --density curvature and --iterations and --no-fit", "[cli][remesh]") {
  const std::string ellipsoid = kData + "/ellipsoid.off", out = kOut + "options.off";
  const lrvd::SurfaceMesh input = lrvd::read_mesh(ellipsoid).mesh;
  const lrvd::ClosestPointIndex surface(input);
  const double diagonal = input.bounding_box().diagonal();
  // The output's vertices and its farthest vertex from the input surface, from one run of 150.
  auto remesh = [&](const std::string& options) {
    const std::string report = kOut + "options.json";
    const Run r = run("remesh " + ellipsoid + " -n 150 " + options + " -o " + out + " --report " + report);
    INFO(options << "\n" << r.err);
    REQUIRE(r.status == 0);
    const lrvd::SurfaceMesh written = lrvd::read_mesh(out).mesh;
    REQUIRE(written.vertex_count() == 150);
    double farthest = 0;
    for (const lrvd::Vec3& p : written.positions()) farthest = std::max(farthest, surface.query(p).distance);
    json j = read_json(report);
    j["test_farthest"] = farthest / diagonal;
    REQUIRE(j["output"]["vertices"] == 150);
    REQUIRE(j["verification"]["passed"] == true);
    return j;
  };
  const json base = remesh("");
  REQUIRE(base["optimizer"] == "lbfgs");
  REQUIRE(base["density"] == "uniform");
  REQUIRE(base["polished"] == true);  // L-BFGS ends with a Lloyd step
  REQUIRE(base["iterations"].get<int>() > 10);
  REQUIRE(base["fit"]["enabled"] == true);
  REQUIRE(base["fit"]["moved"].get<int>() > 0);
  REQUIRE(base["test_farthest"].get<double>() > 1e-4);  // fitted off the surface, to the cells' planes
  // Lloyd: no L-BFGS, so no Lloyd step after it, and another CVT.
  const json lloyd = remesh("--optimizer lloyd");
  CHECK(lloyd["optimizer"] == "lloyd");
  CHECK(lloyd["polished"] == false);
  CHECK(lloyd["energy"] != base["energy"]);
  // Curvature: the energy is under another density, from the same initial samples.
  const json curvature = remesh("--density curvature");
  CHECK(curvature["density"] == "curvature");
  CHECK(curvature["initial_energy"] != base["initial_energy"]);
  // An iteration cap of 3: 3 L-BFGS iterations and the Lloyd step (no repair rounds here).
  const json capped = remesh("--iterations 3");
  CHECK(capped["repair_rounds"] == 0);
  CHECK(capped["iterations"].get<int>() <= 4);
  // No fitting: the same CVT, its vertices the samples, on the input surface.
  const json unfitted = remesh("--no-fit");
  CHECK(unfitted["fit"]["enabled"] == false);
  CHECK(unfitted["fit"]["moved"] == 0);
  CHECK(unfitted["fit"]["max_displacement_pct"] == 0.0);
  CHECK(unfitted["energy"] == base["energy"]);
  CHECK(unfitted["test_farthest"].get<double>() < 1e-9);
  std::remove(out.c_str());
  std::remove((kOut + "options.json").c_str());
}

TEST_CASE("lrvd mps uses and reports --gap-update lrpd and --exact and --max-radius-ratio", "[cli]") {
  const std::string samples = kOut + "mps_options.xyz", report = kOut + "mps_options.json";
  auto mps = [&](const std::string& options) {
    const Run r = run("mps " + kData + "/elk.off " + options + " -o " + samples + " --report " + report);
    INFO(options << "\n" << r.err);
    REQUIRE(r.status == 0);
    const json j = read_json(report);
    REQUIRE(j["maximal"] == true);
    REQUIRE(j["min_distance_ok"] == true);
    return j;
  };
  const json base = mps("--radius 0.1");
  REQUIRE(base["gap_update"] == "local");
  // Local updates: the first gaps from the power diagrams of the disks reaching each triangle; an
  // LRPD only for pieces no dart fitted (none on the elk at a uniform radius).
  REQUIRE(base["lrpd_evaluations"] == 0);
  // The paper's loop: a new LRPD after every round of darts.
  const json paper = mps("--radius 0.1 --gap-update lrpd");
  CHECK(paper["gap_update"] == "lrpd");
  CHECK(paper["lrpd_evaluations"].get<int>() > 1);
  // The same samples, every vertex of the maximality check decided with rationals.
  const json exact = mps("--radius 0.1 --exact");
  CHECK(exact["samples"] == base["samples"]);
  CHECK(exact["mps_verification"]["exact_vertex_tests"].get<long long>() >
        base["mps_verification"]["exact_vertex_tests"].get<long long>());
  // Adaptive radii up to 1.2 times r_min (the default, 2, gives 1.69 times here).
  const json capped = mps("--radius 0.05 --adaptive --max-radius-ratio 1.2");
  const double r_min = capped["radius"]["absolute"].get<double>(), r_max = capped["radius"]["max_absolute"].get<double>();
  CHECK(capped["radius"]["adaptive"] == true);
  CHECK(r_max > r_min);
  CHECK(r_max <= 1.2 * r_min * (1 + 1e-12));
  std::remove(samples.c_str());
  std::remove(report.c_str());
}

TEST_CASE("lrvd render --no-samples draws the same cells without the samples' dots", "[cli]") {
  const std::string with = kOut + "dots.png", again = kOut + "dots_again.png", without = kOut + "no_dots.png";
  const std::string cells = "render " + kData + "/elk.off -n 30 --size 96x96 -o ";
  for (const std::string& args : {cells + with, cells + again, cells + without + " --no-samples"}) {
    const Run r = run(args);
    INFO(args << "\n" << r.err);
    REQUIRE(r.status == 0);
    REQUIRE(r.out.find("30 lrvd cells") != std::string::npos);
  }
  const std::string a = take_file(with), b = take_file(again), c = take_file(without);
  REQUIRE(a.size() > 8);
  const bool repeated = a == b, dotted = a != c;  // (not the PNGs' bytes in a failure's message)
  REQUIRE(repeated);  // the picture is the same from run to run
  REQUIRE(dotted);
}

TEST_CASE("An output that cannot be written whole fails with one line and leaves no part file", "[cli]") {
  // /dev/full takes the file and fails the write: a big one (the samples) at a write, a small one
  // (a report, in the buffer until closed) at the close.
  const Run samples = run("mps " + kData + "/elk.off --radius 0.1 -o /dev/full");
  CHECK(samples.status == 1);  // a failed write is not bad input
  CHECK(samples.err == "lrvd: error: /dev/full: write failed\n");
  const Run report = run("compute " + kData + "/elk.off -n 20 --report /dev/full");
  CHECK(report.status == 1);
  CHECK(report.err == "lrvd: error: /dev/full: write failed\n");
  // A regular file past the size limit (ulimit -f, in kB, with SIGXFSZ ignored so that the write
  // fails rather than the process): the part file goes, and no file is left under either name.
  auto limited = [](const std::string& args, int kilobytes) {
    const std::string err_path = kOut + "limited_stderr_" + std::to_string(getpid()) + ".txt";
    const int raw = std::system(("(trap '' XFSZ; ulimit -f " + std::to_string(kilobytes) + "; exec " + kCli + " " +
                                 args + ") > /dev/null 2> " + err_path)
                                    .c_str());
    return Run{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, take_file(err_path), ""};
  };
  const std::string mesh = kOut + "limited.off", json_report = kOut + "limited.json";
  for (const std::string& f : {mesh, json_report}) {
    std::filesystem::remove(f);
    std::filesystem::remove(f + ".lrvd-part");
  }
  // The remesh (about 8 kB) fails at a write, past 4 kB.
  const Run big = limited("remesh " + kData + "/ellipsoid.off -n 100 -o " + mesh, 4);
  CHECK(big.status == 1);
  CHECK(big.err == "lrvd: error: " + mesh + ": write failed\n");
  CHECK_FALSE(std::filesystem::exists(std::filesystem::symlink_status(mesh)));
  CHECK_FALSE(std::filesystem::exists(std::filesystem::symlink_status(mesh + ".lrvd-part")));
  // The report (about 2 kB) fails at the close, past 1 kB.
  const Run small = limited("compute " + kData + "/elk.off -n 20 --report " + json_report, 1);
  CHECK(small.status == 1);
  CHECK(small.err == "lrvd: error: " + json_report + ": write failed\n");
  CHECK_FALSE(std::filesystem::exists(std::filesystem::symlink_status(json_report)));
  CHECK_FALSE(std::filesystem::exists(std::filesystem::symlink_status(json_report + ".lrvd-part")));
}

TEST_CASE("A report that cannot be written exits 1 and removes the outputs it went with", "[cli]") {
  // A failed write is not bad input (exit 2): exit 1, one line; the -o file written before the
  // report is removed, not left without its report.
  const std::string tetra = kOut + "report_full.off";
  std::ofstream(tetra) << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::string remeshed = kOut + "report_full_remesh.off", samples = kOut + "report_full.xyz",
                    lrrt = kOut + "report_full_lrrt.off";
  const Run remesh = run("remesh " + kData + "/ellipsoid.off -n 60 -o " + remeshed + " --report /dev/full");
  CHECK(remesh.status == 1);
  CHECK(remesh.err == "lrvd: error: /dev/full: write failed\n");
  CHECK_FALSE(std::filesystem::exists(remeshed));
  const Run mps = run("mps " + kData + "/ellipsoid.off --radius 0.3 -o " + samples + " --remesh " + lrrt +
                      " --report /dev/full");
  CHECK(mps.status == 1);
  CHECK(mps.err == "lrvd: error: /dev/full: write failed\n");
  CHECK_FALSE(std::filesystem::exists(samples));
  CHECK_FALSE(std::filesystem::exists(lrrt));
}

TEST_CASE("lrvd refuses inputs that are not regular files at once, with one line and exit 2", "[cli]") {
  // A FIFO blocked for ever, /dev/zero grew memory without bound: refused before they are opened.
  const std::string fifo = kOut + "input_fifo.off", zero = kOut + "input_zero.stl";
  std::filesystem::remove(fifo);
  std::filesystem::remove(zero);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::filesystem::create_symlink("/dev/zero", zero);
  for (const std::string& mesh : {fifo, zero}) {
    const Run r = run("compute " + mesh + " -n 10");
    CHECK(r.status == 2);
    CHECK(r.err == "lrvd: error: " + mesh +
                       ": is not a regular file but a device, a pipe or a socket; lrvd reads its inputs from regular "
                       "files\n");
  }
  const Run points = run("compute " + kData + "/ellipsoid.off --points /dev/urandom");
  CHECK(points.status == 2);
  CHECK(lines(points.err) == 1);
  CHECK(points.err.find("point file '/dev/urandom' is not a regular file") != std::string::npos);
}

TEST_CASE("lrvd reads a PLY with integer coordinates (CGAL's reader crashed on it)", "[cli]") {
  const std::string ply = kOut + "int_tetra.ply";
  std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 4\nproperty int x\nproperty int y\nproperty int z\n"
                        "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n10 0 0\n0 10 0\n"
                        "0 0 10\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  for (const std::string command : {"compute", "mps"}) {
    const Run r = run(command + " " + ply + (command == "mps" ? " --radius 2 -o " + kOut + "int_tetra.xyz" : " -n 10"));
    INFO(r.err);
    CHECK(r.status == 0);
  }
}

TEST_CASE("An outlier vertex costs bounded work: refused with one line naming it", "[cli]") {
  // An octahedron with one vertex drawn to (-1e6, 0, 0): its four needle triangles split into 2.1
  // million triangles for 20 samples (7-11 s, 1.1 GB), and remesh -n 12 ran for minutes.
  const std::string needle = kOut + "outlier_octahedron.off";
  std::ofstream(needle) << "OFF\n6 8 0\n-1e6 0 0\n1 0 0\n0 -1 0\n0 1 0\n0 0 -1\n0 0 1\n3 0 2 5\n3 0 5 3\n3 0 3 4\n"
                           "3 0 4 2\n3 1 5 2\n3 1 3 5\n3 1 4 3\n3 1 2 4\n";
  for (const std::string command : {"compute " + needle + " -n 20", "remesh " + needle + " -n 12 -o " + kOut +
                                                                         "outlier_remesh.off"}) {
    const Run r = run(command);
    INFO(command << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(lines(r.err) == 1);
    CHECK(r.err.find("far from the others") != std::string::npos);
    CHECK(r.err.find("(-1e+06, 0, 0)") != std::string::npos);
  }
  // Without the refinement the diagram is made at once.
  CHECK(run("compute " + needle + " -n 20 --refine off").status == 0);
  // Distances to a vertex 1e24 away: every closest-point query visited every triangle (77 s).
  const std::string tetra = kOut + "outlier_tetra.off", far = kOut + "outlier_tetra_far.off";
  std::ofstream(tetra) << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  std::ofstream(far) << "OFF\n4 4 0\n-1e24 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const Run quality = run("quality " + tetra + " " + far);
  CHECK(quality.status == 2);
  CHECK(quality.err.rfind("lrvd: error: vertex 0 of the remesh at (-1e+24, 0, 0) is ", 0) == 0);
  const Run reverse = run("quality " + far + " " + tetra);
  CHECK(reverse.status == 2);
  CHECK(reverse.err.rfind("lrvd: error: vertex 0 of the reference at (-1e+24, 0, 0) is ", 0) == 0);
}

TEST_CASE("The remesh of issue 51's pulled cube corner ends as documented (its fitting read out of bounds)", "[cli]") {
  // A cube with one corner of one triangle pulled out to (-1, -1, -1): the fitting's closest-point
  // query found no triangle for an input sample and indexed -1 (silent in a release build; the
  // sanitized build, make sanitize, aborts on it).
  const std::string cube = kOut + "pulled_cube.off";
  std::ofstream(cube) << "OFF 9 12 0\n0 0 0\n0 1 0\n1 1 0\n1 0 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n-1 -1 -1\n3 0 1 2\n"
                         "3 0 2 3\n3 4 5 6\n3 4 6 7\n3 0 3 5\n3 0 5 4\n3 3 2 6\n3 3 8 5\n3 2 1 7\n3 2 7 6\n3 1 0 4\n"
                         "3 1 4 7\n";
  const Run r = run("--threads 1 remesh " + cube + " -n 12 --seed 2 -o " + kOut + "pulled_cube_remesh.off");
  INFO(r.err);
  CHECK((r.status == 0 || r.status == 3));
}

TEST_CASE("lrvd refuses a --weld that leaves no faces in one line with exit 2", "[cli]") {
  const std::string tetra = kOut + "weld_all.off";
  std::ofstream(tetra) << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const Run r = run("mps " + tetra + " --radius 0.2 --weld 10 -o " + kOut + "weld_all.xyz");
  REQUIRE(r.status == 2);
  REQUIRE(lines(r.err) == 1);
  REQUIRE(r.err.find("weld_all.off: has no faces left after --weld 10 joined their corners: --weld 10 collapsed") !=
          std::string::npos);
}

TEST_CASE("mps and quality with --repair list each change in the report and on the console", "[cli]") {
  // A unit cube of five quads (the x = 1 one turned inwards) and a top of two triangles, one of them
  // twice, and a zero-area triangle on the bottom's front edge through a vertex no other face uses.
  const std::string messy = kOut + "messy_cube.off", clean = kOut + "clean_cube.off";
  std::ofstream(messy) << "OFF\n9 9 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n0.5 0 0\n"
                          "4 0 3 2 1\n3 4 5 6\n3 4 6 7\n4 0 1 5 4\n4 5 6 2 1\n4 2 3 7 6\n4 3 0 4 7\n"
                          "3 4 5 6\n3 0 8 1\n";
  std::ofstream(clean) << "OFF\n8 12 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                          "3 0 3 2\n3 0 2 1\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n3 1 2 6\n3 1 6 5\n"
                          "3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n";
  const json expected = json::array({"removed 1 degenerate face", "removed 1 duplicate face",
                                     "removed 1 unreferenced vertex", "reoriented 2 faces",
                                     "triangulated 5 polygons"});
  const std::string console = "repair: removed 1 degenerate face, removed 1 duplicate face, removed 1 unreferenced "
                              "vertex, reoriented 2 faces, triangulated 5 polygons\n";
  const std::string mps_report = kOut + "messy_mps.json", quality_report = kOut + "messy_quality.json";
  const Run mps = run("mps " + messy + " --radius 0.2 --repair -o " + kOut + "messy.xyz --report " + mps_report);
  INFO(mps.err);
  REQUIRE(mps.status == 0);
  REQUIRE(mps.out.find(console) != std::string::npos);
  REQUIRE(read_json(mps_report)["input"]["repair_changes"] == expected);
  const Run quality = run("quality " + messy + " " + clean + " --repair --report " + quality_report);
  INFO(quality.err);
  REQUIRE(quality.status == 0);
  REQUIRE(quality.out.find(console) != std::string::npos);
  REQUIRE(read_json(quality_report)["reference_repair_changes"] == expected);
  // The clean cube, repaired, has nothing to change: an empty list.
  REQUIRE(run("quality " + clean + " " + clean + " --repair --report " + quality_report).status == 0);
  REQUIRE(read_json(quality_report)["reference_repair_changes"] == json::array());
}
