// The library call the Python module's lrvd.remesh makes, timed in CPU seconds (user + sys of every
// thread): a mesh from its arrays, the samples, the remesh, its check, quality and report.
// Usage: bench_remesh_call MESH N [SEED] [RUNS] [THREADS]; prints one CPU time a line. bench/python_overhead.py
// alternates it with the Python call.
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <sys/resource.h>
#include <tbb/global_control.h>

#include "io/mesh_io.h"
#include "report/remesh_report.h"

namespace {

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec + 1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_remesh_call MESH N [SEED] [RUNS] [THREADS]\n");
    return 2;
  }
  const lrvd::LoadedMesh file = lrvd::read_mesh(argv[1]);
  const int n = std::atoi(argv[2]);
  const std::uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 1;
  const int runs = argc > 4 ? std::atoi(argv[4]) : 1;
  const int threads = argc > 5 ? std::atoi(argv[5]) : 0;
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  for (int r = 0; r < runs; ++r) {
    const double start = cpu_seconds();
    lrvd::Input input;
    input.loaded.mesh = lrvd::SurfaceMesh(file.mesh.positions(), file.mesh.triangles());
    lrvd::require_workable_model(input.loaded.mesh, "lrvd");
    lrvd::SampleRequest request;
    request.count = n;
    request.seed = seed;
    request.check_count = lrvd::require_remesh_vertex_count;
    lrvd::prepare_samples(input, request);
    const lrvd::RemeshRun run = lrvd::run_remesh(input, {}, true, seed, "", "", nullptr, nullptr);
    const std::string report = run.report.dump();
    std::printf("%.6f %zu %d\n", cpu_seconds() - start, report.size(), run.check.passed ? 1 : 0);
  }
  return 0;
}
