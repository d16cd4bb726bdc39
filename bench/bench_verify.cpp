// The judge's cost against the diagram's: one LRVD on the geodesic sphere of bench_fig9 (samples
// uniform by area, seed 9), then verify_diagram on it; prints one JSON line with the CPU seconds
// (all threads) and wall seconds of each, and the verdict. bench/verify_sphere.py runs it per case
// under /usr/bin/time for the peak memory.
//
//   bench_verify --row SAMPLES TRIANGLES [--threads T] [--runs R]
//
// Exit status 1 when the verification failed, 2 on bad usage.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "bench/bench_sphere.h"
#include "bench/bench_util.h"
#include "samples/samples.h"
#include "verification/diagram_check.h"
#include "voronoi/lrvd.h"

namespace {

constexpr std::uint64_t kSeed = 9;  // bench_fig9's

struct Options {
  int samples = 0, triangles = 0;
  int threads = 0;  // 0: every core
  int runs = 1;     // each timing is the minimum over the runs
};

[[noreturn]] void usage() {
  std::fputs("usage: bench_verify --row SAMPLES TRIANGLES [--threads T] [--runs R]\n", stderr);
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  auto number = [&](int& i) {
    if (i + 1 >= argc) usage();
    char* end = nullptr;
    const long v = std::strtol(argv[++i], &end, 10);
    if (*end != '\0' || v < 0 || v > (1 << 30)) usage();
    return static_cast<int>(v);
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--row") {
      o.samples = number(i);
      o.triangles = number(i);
    } else if (a == "--threads") {
      o.threads = number(i);
    } else if (a == "--runs") {
      o.runs = std::max(1, number(i));
    } else {
      usage();
    }
  }
  if (o.samples <= 0 || o.triangles <= 0) usage();
  return o;
}

struct Timing {
  double cpu_s = 1e300, wall_s = 1e300;
  template <class F>
  void measure(F f) {
    const double cpu = lrvd::bench::cpu_seconds();
    const auto wall = std::chrono::steady_clock::now();
    f();
    cpu_s = std::min(cpu_s, lrvd::bench::cpu_seconds() - cpu);
    wall_s = std::min(wall_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count());
  }
};

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const int threads = o.threads > 0 ? o.threads : static_cast<int>(tbb::this_task_arena::max_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const lrvd::SurfaceMesh mesh = lrvd::bench::geodesic_sphere(lrvd::bench::segments_for(o.triangles));
  const lrvd::Samples samples = lrvd::sample_uniform(mesh, o.samples, kSeed);
  Timing diagram_time, verify_time;
  lrvd::Diagram diagram;
  lrvd::DiagramVerification check;
  for (int r = 0; r < o.runs; ++r) diagram_time.measure([&] { diagram = lrvd::compute_lrvd(mesh, samples); });
  for (int r = 0; r < o.runs; ++r) verify_time.measure([&] { check = lrvd::verify_diagram(mesh, samples, diagram); });
  const nlohmann::json out = {{"samples", o.samples},
                              {"triangles", mesh.triangle_count()},
                              {"threads", threads},
                              {"diagram_cpu_s", diagram_time.cpu_s},
                              {"diagram_wall_s", diagram_time.wall_s},
                              {"verify_cpu_s", verify_time.cpu_s},
                              {"verify_wall_s", verify_time.wall_s},
                              {"passed", check.passed},
                              {"distinct_vertices", check.distinct_vertices},
                              {"rational_points", check.rational_points},
                              {"summary", check.summary()}};
  fmt::print("{}\n", out.dump());
  return check.passed ? 0 : 1;
}
