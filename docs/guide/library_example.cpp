// lrvd as a library: the LRVD of random samples and its check, then a remesh to exactly N vertices
// and its check. Built as `lrvd_library_example` and run by the tests on CGAL's elk.
//
//   lrvd_library_example MESH N OUT.off
#include <cstdio>
#include <cstdlib>

#include "common/error.h"
#include "io/mesh_io.h"
#include "io/mesh_writers.h"
#include "remesh/remesh_pipeline.h"
#include "samples/samples.h"
#include "verification/diagram_check.h"
#include "verification/remesh_check.h"
#include "voronoi/lrvd.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s MESH N OUT.off\n", argv[0]);
    return 2;
  }
  try {
    // A manifold, consistently oriented triangle mesh; anything else throws InputError with the
    // reason (ReadOptions{true} repairs a soup first).
    const lrvd::SurfaceMesh input = lrvd::read_mesh(argv[1]).mesh;
    char* end = nullptr;
    const long n = std::strtol(argv[2], &end, 10);
    if (*end != '\0' || n < 1 || n > 10000000) throw lrvd::InputError("N must be a whole number from 1 to 10^7");

    // The diagram of n uniform random samples (seed 7), and the check of its six properties.
    const lrvd::Samples samples = lrvd::sample_uniform(input, n, 7);
    const lrvd::Diagram diagram = lrvd::compute_lrvd(input, samples);
    const lrvd::DiagramVerification diagram_check = lrvd::verify_diagram(input, samples, diagram);
    std::printf("LRVD: %zu polygons, %s\n", diagram.polygons.size(),
                diagram_check.passed ? "verified" : diagram_check.summary().c_str());

    // The remesh to exactly n vertices, as `lrvd remesh MESH -n N` makes it, and its check.
    const lrvd::RemeshResult remesh = lrvd::remesh_to(input, n);
    const lrvd::DualMesh& output = remesh.dual;
    lrvd::write_mesh(argv[3], output.positions, output.triangles);
    const lrvd::RemeshVerification remesh_check = lrvd::verify_remesh(input, output.positions, output.triangles, n);
    std::printf("remesh: %zu vertices, %zu triangles, %d repair rounds, %s\n", output.positions.size(),
                output.triangles.size(), remesh.repair_rounds,
                remesh_check.passed ? "verified" : remesh_check.summary().c_str());
    return diagram_check.passed && remesh_check.passed ? 0 : 3;
  } catch (const lrvd::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
