// Paper Fig. 9 (§5 "Efficiency"): LRVD and exact RVD timings on a sphere, (a) a 20k-triangle
// sphere with 2k..100k samples, (b) 10k samples on spheres of 500..140k triangles. Prints one
// markdown table per experiment; every row is also checked (LRVD verification, RVD cell components).
//
//   bench_fig9 [--quick] [--runs N] [--verify-max-samples N] [--json FILE] [--row SAMPLES TRIANGLES]
//
// Exit status 1 when a row threw or its LRVD failed verification (the row says which), 2 on bad usage.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench/bench_sphere.h"
#include "diagram/diagram.h"
#include "mesh/surface_mesh.h"
#include "predicates/predicates.h"
#include "samples/samples.h"
#include "verification/diagram_check.h"
#include "voronoi/lrvd.h"
#include "voronoi/rvd.h"

namespace {

using lrvd::Vec3;
using lrvd::bench::geodesic_sphere;
using lrvd::bench::segments_for;

constexpr std::uint64_t kSeed = 9;

struct DelaunayTiming {
  double time_s = 0;
  double mean_degree = 0;  //!< Delaunay neighbours a sample: the bisectors an RVD clip tests
};

//! The 3D Delaunay triangulation of the samples alone, built as compute_rvd builds it: the part
//! of the RVD time that does not depend on the mesh.
DelaunayTiming delaunay_time(const lrvd::Samples& samples) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
  using Tds = CGAL::Triangulation_data_structure_3<Vb, CGAL::Delaunay_triangulation_cell_base_3<K>>;
  using Dt = CGAL::Delaunay_triangulation_3<K, Tds>;
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::pair<K::Point_3, int>> points;
  points.reserve(samples.size());
  for (int i = 0; i < samples.size(); ++i) {
    const Vec3& q = samples.positions[i];
    points.emplace_back(K::Point_3(q.x, q.y, q.z), i);
  }
  const Dt dt(points.begin(), points.end());
  DelaunayTiming result;
  result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.mean_degree = 2.0 * static_cast<double>(dt.number_of_finite_edges()) / samples.size();
  return result;
}

struct Row {
  std::string experiment;   // "samples" (Fig. 9 left) or "triangles" (Fig. 9 right)
  int samples = 0;
  int triangles = 0;
  double lrvd_s = 0, rvd_s = 0, delaunay_s = 0;  // minimum over the runs
  double lrvd_clips_per_triangle = 0;            // triangle clippings / triangles (1 = no re-clip)
  double lrvd_polygons_per_triangle = 0;
  double rvd_polygons_per_triangle = 0;
  double delaunay_mean_degree = 0;
  double lrvd_predicates_per_triangle = 0;  // side1/2/3 and helper evaluations of one run / triangles
  double rvd_predicates_per_triangle = 0;
  int lrvd_connectivity_rounds = 0;
  int rvd_disconnected_cells = 0;  // cells of more than one component
  std::string lrvd_verification = "skipped";  // "pass", "FAIL: ...", "skipped"
  double verify_s = 0;
  std::string error;  // an exception's message, the row's other fields then partial

  nlohmann::json to_json() const {
    return {{"experiment", experiment}, {"samples", samples}, {"triangles", triangles}, {"lrvd_s", lrvd_s},
            {"rvd_s", rvd_s}, {"rvd_over_lrvd", lrvd_s > 0 ? rvd_s / lrvd_s : 0.0}, {"delaunay_s", delaunay_s},
            {"lrvd_clips_per_triangle", lrvd_clips_per_triangle},
            {"lrvd_polygons_per_triangle", lrvd_polygons_per_triangle},
            {"rvd_polygons_per_triangle", rvd_polygons_per_triangle},
            {"delaunay_mean_degree", delaunay_mean_degree},
            {"lrvd_predicates_per_triangle", lrvd_predicates_per_triangle},
            {"rvd_predicates_per_triangle", rvd_predicates_per_triangle},
            {"lrvd_connectivity_rounds", lrvd_connectivity_rounds}, {"rvd_disconnected_cells", rvd_disconnected_cells},
            {"lrvd_verification", lrvd_verification}, {"verify_s", verify_s}, {"error", error}};
  }
};

struct Options {
  bool quick = false;
  int runs = 3;
  int verify_max_samples = 1 << 30;  // rows with more samples skip the LRVD verification
  std::string json_path;
  int row_samples = 0, row_triangles = 0;  // --row: one row only
};

Row measure(const std::string& experiment, int n, int target_triangles, const Options& options) {
  Row row;
  row.experiment = experiment;
  row.samples = n;
  try {
    const lrvd::SurfaceMesh mesh = geodesic_sphere(segments_for(target_triangles));
    row.triangles = mesh.triangle_count();
    const lrvd::Samples samples = lrvd::sample_uniform(mesh, n, kSeed);
    const double m = mesh.triangle_count();

    // Predicate evaluations of one run (single-threaded, so the counters are exact).
    auto predicate_calls = [] { return static_cast<double>(lrvd::predicate_stats().total.calls); };
    lrvd::Diagram lrvd_diagram, rvd_diagram;
    row.lrvd_s = row.rvd_s = row.delaunay_s = 1e300;
    for (int r = 0; r < options.runs; ++r) {
      lrvd::reset_predicate_stats();
      lrvd_diagram = lrvd::compute_lrvd(mesh, samples);
      row.lrvd_s = std::min(row.lrvd_s, lrvd_diagram.stats.time_s);
      row.lrvd_predicates_per_triangle = predicate_calls() / m;
    }
    for (int r = 0; r < options.runs; ++r) {
      lrvd::reset_predicate_stats();
      rvd_diagram = lrvd::compute_rvd(mesh, samples);
      row.rvd_s = std::min(row.rvd_s, rvd_diagram.stats.time_s);
      row.rvd_predicates_per_triangle = predicate_calls() / m;
    }
    for (int r = 0; r < options.runs; ++r) {
      const DelaunayTiming dt = delaunay_time(samples);
      row.delaunay_s = std::min(row.delaunay_s, dt.time_s);
      row.delaunay_mean_degree = dt.mean_degree;
    }

    row.lrvd_clips_per_triangle = lrvd_diagram.stats.clipped_triangles / m;
    row.lrvd_polygons_per_triangle = lrvd_diagram.polygons.size() / m;
    row.rvd_polygons_per_triangle = rvd_diagram.polygons.size() / m;
    row.lrvd_connectivity_rounds = lrvd_diagram.stats.connectivity_rounds;
    const lrvd::CellComponents components = lrvd::cell_components(rvd_diagram, mesh);
    row.rvd_disconnected_cells =
        static_cast<int>(std::count_if(components.count.begin(), components.count.end(), [](int c) { return c > 1; }));

    if (n <= options.verify_max_samples) {
      const lrvd::DiagramVerification check = lrvd::verify_diagram(mesh, samples, lrvd_diagram);
      row.verify_s = check.time_s;
      row.lrvd_verification = check.passed ? "pass" : "FAIL: " + check.summary();
    }
  } catch (const std::exception& e) {
    row.error = e.what();
  }
  return row;
}

void print_header(const std::string& title) {
  fmt::print("\n### {}\n\n", title);
  fmt::print("| samples | triangles | LRVD s | RVD s | RVD/LRVD | Delaunay s | polys/tri | LRVD clips/tri "
             "| LRVD preds/tri | RVD preds/tri | RVD disconnected cells | LRVD verified |\n");
  fmt::print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
  std::fflush(stdout);
}

void print_row(const Row& r) {
  if (!r.error.empty()) {
    fmt::print("| {} | {} | ERROR: {} ||||||||||\n", r.samples, r.triangles, r.error);
  } else {
    std::string verified = r.lrvd_verification;
    if (r.lrvd_verification == "pass") verified = fmt::format("pass ({:.1f} s)", r.verify_s);
    // The two diagrams have the same polygons unless the RVD has stray pieces.
    std::string polygons = fmt::format("{:.2f}", r.lrvd_polygons_per_triangle);
    if (r.rvd_polygons_per_triangle != r.lrvd_polygons_per_triangle)
      polygons += fmt::format(" / {:.2f}", r.rvd_polygons_per_triangle);
    fmt::print("| {} | {} | {:.3f} | {:.3f} | {:.2f} | {:.3f} | {} | {:.2f} | {:.0f} | {:.0f} | {} | {} |\n", r.samples,
               r.triangles, r.lrvd_s, r.rvd_s, r.rvd_s / r.lrvd_s, r.delaunay_s, polygons, r.lrvd_clips_per_triangle,
               r.lrvd_predicates_per_triangle, r.rvd_predicates_per_triangle, r.rvd_disconnected_cells, verified);
  }
  std::fflush(stdout);
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

[[noreturn]] void usage(int code) {
  std::fprintf(code ? stderr : stdout,
               "usage: bench_fig9 [--quick] [--runs N] [--verify-max-samples N] [--json FILE]\n"
               "                  [--row SAMPLES TRIANGLES]\n"
               "  Paper Fig. 9: LRVD vs exact RVD on a geodesic unit sphere (seed %llu).\n"
               "  --quick                 a subset that runs in well under a minute\n"
               "  --runs N                timings are the minimum of N runs (default 3)\n"
               "  --verify-max-samples N  verify the LRVD only on rows with at most N samples\n"
               "  --json FILE             also write the rows as JSON\n"
               "  --row S T               one row: S samples on a sphere of about T triangles\n",
               static_cast<unsigned long long>(kSeed));
  std::exit(code);
}

Options parse(int argc, char** argv) {
  Options o;
  auto number = [&](int& i) {
    if (i + 1 >= argc) usage(2);
    char* end = nullptr;
    const long v = std::strtol(argv[++i], &end, 10);
    if (*end != '\0' || v < 1) usage(2);
    return static_cast<int>(v);
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") o.quick = true;
    else if (a == "--runs") o.runs = number(i);
    else if (a == "--verify-max-samples") o.verify_max_samples = number(i);
    else if (a == "--row") { o.row_samples = number(i); o.row_triangles = number(i); }
    else if (a == "--json" && i + 1 < argc) o.json_path = argv[++i];
    else if (a == "--help" || a == "-h") usage(0);
    else {
      std::fprintf(stderr, "bench_fig9: unknown or incomplete option '%s'\n", a.c_str());
      usage(2);
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  std::vector<Row> rows;
  bool failed = false;
  auto run = [&](const std::string& experiment, int n, int m) {
    rows.push_back(measure(experiment, n, m, options));
    print_row(rows.back());
    failed |= !rows.back().error.empty() || rows.back().lrvd_verification.rfind("FAIL", 0) == 0;
  };

  fmt::print("# Fig. 9: LRVD vs RVD ({} cores, {}, min of {} runs, seed {})\n", std::thread::hardware_concurrency(),
             cpu_model(), options.runs, kSeed);
  if (options.row_samples > 0) {
    print_header("one row");
    run("row", options.row_samples, options.row_triangles);
  } else {
    const std::vector<int> sample_counts = options.quick ? std::vector<int>{2000, 5000, 10000}
                                                         : std::vector<int>{2000, 5000, 10000, 20000, 50000, 100000};
    const std::vector<int> triangle_counts = options.quick
                                                 ? std::vector<int>{500, 2000, 5000, 10000}
                                                 : std::vector<int>{500, 2000, 5000, 10000, 20000, 40000, 80000, 140000};
    print_header("Fig. 9 left: sphere of 20480 triangles, growing sample count");
    for (int n : sample_counts) run("samples", n, 20480);
    print_header("Fig. 9 right: 10000 samples, growing mesh resolution");
    for (int m : triangle_counts) run("triangles", 10000, m);
  }

  if (!options.json_path.empty()) {
    nlohmann::json out;
    out["cpu"] = cpu_model();
    out["threads"] = std::thread::hardware_concurrency();
    out["runs"] = options.runs;
    out["seed"] = kSeed;
#ifdef NDEBUG
    out["assertions"] = false;
#else
    out["assertions"] = true;
#endif
    out["rows"] = nlohmann::json::array();
    for (const Row& r : rows) out["rows"].push_back(r.to_json());
    std::ofstream file(options.json_path);
    file << out.dump(2) << "\n";
    if (!file) {
      std::fprintf(stderr, "bench_fig9: cannot write %s\n", options.json_path.c_str());
      return 1;
    }
  }
  return failed ? 1 : 0;
}
