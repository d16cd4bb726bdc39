// The cost of one CVT evaluation's diagram: samples part way through a CVT on one of CGAL's models
// (like those a remesh evaluates most of its diagrams on), then the LRVD and its cell integrals
// computed again and again on one thread. Prints the shape of the diagram (polygons per triangle,
// clippings, predicate calls) and the CPU time per diagram and per integration, minimum and mean.
// Ends with a digest of the last diagram and its integrals (every field, the doubles' bits): two
// builds that print the same digest computed the same diagram to the last bit.
// Usage: bench_diagram [MODEL] [N] [REPETITIONS] [CVT_ITERATIONS]   (default: elk 516 300 20)
// MODEL is one of CGAL's models by name (elk, armadillo, ...) or a mesh file's path; a mesh of
// kSpatialOrderMinTriangles or more is renumbered along a Morton curve first, as lrvd remesh does.
// Exit status 1 when the timed diagram fails verification, 2 on bad arguments or an unreadable mesh.
#include <algorithm>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>

#include <tbb/global_control.h>

#include "bench_util.h"
#include "common/error.h"
#include "io/mesh_io.h"
#include "predicates/predicates.h"
#include "remesh/cvt.h"
#include "remesh/remesh_pipeline.h"
#include "samples/samples.h"
#include "verification/diagram_check.h"
#include "voronoi/lrvd.h"

using namespace lrvd;

namespace {

// FNV-1a over the values given, one after another.
struct Digest {
  std::uint64_t h = 1469598103934665603ull;
  void add(std::uint64_t x) {
    for (int b = 0; b < 8; ++b) h = (h ^ ((x >> (8 * b)) & 0xff)) * 1099511628211ull;
  }
  void add(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    add(bits);
  }
  void add(int x) { add(static_cast<std::uint64_t>(static_cast<std::uint32_t>(x))); }
};

std::uint64_t digest(const Diagram& d, const CellIntegrals& cells) {
  Digest g;
  for (int o : d.triangle_offsets) g.add(o);
  for (const CellPolygon& p : d.polygons) g.add(p.triangle), g.add(p.cell), g.add(p.first_vertex), g.add(p.vertex_count);
  for (const SymbolicVertex& q : d.vertices) {
    g.add(static_cast<int>(q.type));
    for (int x : q.v) g.add(x);
    for (int x : q.label) g.add(x);
  }
  for (unsigned char a : d.polygon_along) g.add(static_cast<int>(a));
  for (size_t i = 0; i < cells.area.size(); ++i) {
    g.add(cells.area[i]);
    for (int c = 0; c < 3; ++c) g.add(cells.centroid[i][c]);
    g.add(cells.energy[i]);
  }
  g.add(cells.total_energy);
  return g.h;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string model = argc > 1 ? argv[1] : "elk";
  const int n = argc > 2 ? std::atoi(argv[2]) : 516;
  const int repetitions = argc > 3 ? std::atoi(argv[3]) : 300;
  const int cvt_iterations = argc > 4 ? std::atoi(argv[4]) : 20;
  if (model.empty() || model[0] == '-' || n < 1 || repetitions < 1 || cvt_iterations < 0) {
    std::fprintf(stderr, "usage: %s [MODEL] [N] [REPETITIONS] [CVT_ITERATIONS]\n", argv[0]);
    return 2;
  }
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const bool is_path = model.find('/') != std::string::npos || model.find('.') != std::string::npos;
  SurfaceMesh mesh;
  Samples start;
  try {
    mesh = read_mesh(is_path ? model : std::string(LRVD_CGAL_DATA_DIR) + "/" + model + ".off").mesh;
    start = sample_uniform(mesh, n, 1);
    order_for_remeshing(mesh, start);
  } catch (const InputError& e) {
    std::fprintf(stderr, "bench_diagram: %s\n", e.what());
    return 2;
  }
  CvtOptions options;
  options.iterations = cvt_iterations;
  const Samples samples = optimize_cvt(mesh, start, options).samples;

  Diagram diagram = compute_lrvd(mesh, samples);
  const DiagramVerification check = verify_diagram(mesh, samples, diagram);
  std::map<int, int> histogram;  // polygons in a triangle -> triangles
  for (int t = 0; t < mesh.triangle_count(); ++t)
    ++histogram[diagram.triangle_offsets[t + 1] - diagram.triangle_offsets[t]];
  std::printf("%s, %d samples after %d CVT iterations: %d triangles, %zu polygons, %zu polygon vertices, %s\n",
              model.c_str(), n, cvt_iterations, mesh.triangle_count(), diagram.polygons.size(),
              diagram.vertices.size(), check.passed ? "verified" : ("FAILED: " + check.summary()).c_str());
  std::printf("  %d triangle clippings (a triangle clipped again counts again), %d connectivity rounds\n",
              diagram.stats.clipped_triangles, diagram.stats.connectivity_rounds);
  for (const auto& [polygons, triangles] : histogram)
    std::printf("  triangles with %d polygon%s: %d\n", polygons, polygons == 1 ? "" : "s", triangles);

  reset_predicate_stats();
  double best_diagram = 1e30, best_integrals = 1e30, sum_diagram = 0, sum_integrals = 0, energy = 0;
  CellIntegrals cells;
  for (int r = 0; r < repetitions; ++r) {
    const double t0 = bench::cpu_seconds();
    diagram = compute_lrvd(mesh, samples);
    const double t1 = bench::cpu_seconds();
    cells = integrate_cells(diagram, mesh, samples);
    energy += cells.total_energy;
    const double t2 = bench::cpu_seconds();
    best_diagram = std::min(best_diagram, t1 - t0);
    best_integrals = std::min(best_integrals, t2 - t1);
    sum_diagram += t1 - t0;
    sum_integrals += t2 - t1;
  }
  const PredicateStats stats = predicate_stats();
  std::printf("diagram %.3f ms (mean %.3f), integrals %.3f ms (mean %.3f), %.0f predicate calls per diagram, "
              "energy %.6g\n",
              1e3 * best_diagram, 1e3 * sum_diagram / repetitions, 1e3 * best_integrals,
              1e3 * sum_integrals / repetitions, static_cast<double>(stats.total.calls) / repetitions,
              energy / repetitions);
  std::printf("digest %016llx\n", static_cast<unsigned long long>(digest(diagram, cells)));
  return check.passed ? 0 : 1;
}
