// LRVD, RVD and their power variants: every LRVD passes all six verified properties over the
// stress meshes and CGAL's models, the RVD shows the disconnected cells the LRVD removes, both
// agree where the sampling is dense, and degenerate and bad inputs behave as documented.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <tuple>

#include <fmt/format.h>

#include "common/error.h"
#include "diagram/clip.h"
#include "io/mesh_io.h"
#include "mesh/refine.h"
#include "mesh/stress.h"
#include "mps/mps.h"
#include "remesh/cvt.h"
#include "remesh/remesh_pipeline.h"
#include "report/mps_report.h"
#include "report/report.h"
#include "test_meshes.h"
#include "verification/diagram_check.h"
#include "verification/mps_check.h"
#include "voronoi/growth_entry.h"
#include "voronoi/lrvd.h"
#include "voronoi/rvd.h"

using namespace lrvd;

namespace {

SurfaceMesh cgal_mesh(const std::string& name) {
  return read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/" + name).mesh;
}

// The mesh the samples go on: refined when n would crowd its triangles (as `lrvd compute` does).
SurfaceMesh for_samples(const SurfaceMesh& mesh, int n) {
  const double length = suggested_refinement_length(mesh, n);
  return length > 0 && mesh.max_edge_length() > length ? refine_long_edges(mesh, length) : mesh;
}

std::string describe(const DiagramVerification& v) { return v.summary(); }

int disconnected_cells(const Diagram& d, const SurfaceMesh& mesh) {
  int count = 0;
  for (int c : cell_components(d, mesh).count) count += c > 1;
  return count;
}

void require_valid_lrvd(const SurfaceMesh& mesh, int n, int seed, const std::string& label) {
  const Samples samples = sample_uniform(mesh, n, seed);
  const Diagram d = compute_lrvd(mesh, samples);
  const DiagramVerification v = verify_diagram(mesh, samples, d);
  INFO(label << " n=" << n << " seed=" << seed << "\n" << describe(v));
  REQUIRE(v.passed);
  REQUIRE(v.connected.passed);
  REQUIRE(v.cells_with_multiple_components == 0);
}

}  // namespace

TEST_CASE("LRVD cells pass every property on the stress meshes", "[lrvd][property]") {
  for (const StressMeshInfo& info : stress_mesh_catalog()) {
    const SurfaceMesh base = make_stress_mesh(info.name, 0.5);
    for (int n : {10, 30, 100, 300, 1000}) {
      if (n < base.component_count()) continue;
      const SurfaceMesh mesh = for_samples(base, n);
      for (int seed = 1; seed <= 5; ++seed) require_valid_lrvd(mesh, n, seed, info.name);
    }
  }
}

TEST_CASE("LRVD cells pass every property on CGAL's elk, knot, ellipsoid and fold", "[lrvd][property]") {
  for (const char* name : {"elk.off", "knot.off", "ellipsoid.off", "fold.off"}) {
    const SurfaceMesh base = cgal_mesh(name);
    for (int n : {10, 30, 100, 300, 1000}) {
      const SurfaceMesh mesh = for_samples(base, n);
      for (int seed = 1; seed <= 5; ++seed) require_valid_lrvd(mesh, n, seed, name);
    }
  }
}

TEST_CASE("The RVD has disconnected cells on nearby sheets where the LRVD has none", "[rvd]") {
  for (const char* name : {"thin_plate", "folded_sheet", "open_cup"}) {
    const SurfaceMesh mesh = make_stress_mesh(name, 0.5);
    int rvd_disconnected = 0;
    for (int seed = 1; seed <= 5; ++seed) {
      const Samples samples = sample_uniform(mesh, 30, seed);
      const Diagram rvd = compute_rvd(mesh, samples);
      const Diagram lrvd = compute_lrvd(mesh, samples);
      rvd_disconnected += disconnected_cells(rvd, mesh);
      REQUIRE(disconnected_cells(lrvd, mesh) == 0);
      // The RVD passes everything it promises, and reports what it does not.
      const DiagramVerification v = verify_diagram(mesh, samples, rvd);
      INFO(name << " seed " << seed << "\n" << describe(v));
      REQUIRE(v.passed);
      REQUIRE(v.connected.promised == false);
      REQUIRE(v.cells_with_multiple_components == disconnected_cells(rvd, mesh));
    }
    INFO(name);
    REQUIRE(rvd_disconnected > 0);
  }
}

TEST_CASE("Without the connectivity restoration the fixpoint alone can leave a cell in pieces", "[lrvd]") {
  // DESIGN.md, "Where the paper is thin": find a case where the restoration had work to do, and
  // check that it was needed (pieces without it) and sufficient (verified with it).
  const SurfaceMesh mesh = cgal_mesh("elk.off");
  int cases = 0;
  for (int seed = 1; seed <= 10; ++seed) {
    const Samples samples = sample_uniform(mesh, 30, seed);
    const Diagram restored = compute_lrvd(mesh, samples);
    if (restored.stats.connectivity_rounds == 0) continue;
    ++cases;
    LrvdOptions plain;
    plain.restore_connectivity = false;
    const Diagram fixpoint = compute_lrvd(mesh, samples, plain);
    INFO("seed " << seed);
    REQUIRE(disconnected_cells(fixpoint, mesh) > 0);
    REQUIRE_FALSE(verify_diagram(mesh, samples, fixpoint).connected.passed);
    REQUIRE(verify_diagram(mesh, samples, restored).passed);
  }
  REQUIRE(cases > 0);
}

TEST_CASE("Cells with stray pieces in each other's regions are restored one round at a time", "[lrvd]") {
  // CGAL's diplodocus, 80,000 samples (seed 1) on the refined mesh. With every stray piece removed
  // in one round, two cells stayed in two pieces each, as the elk's did at 500,000 samples, where
  // two cells with stray pieces in each other's regions grew back onto their forbidden triangles
  // and were pinned there (docs/algorithms/lrvd.md, "Connectivity restoration"). Taken in separate rounds, they end connected.
  const SurfaceMesh mesh = for_samples(cgal_mesh("diplodocus.off"), 80000);
  const Samples samples = sample_uniform(mesh, 80000, 1);
  const Diagram d = compute_lrvd(mesh, samples);
  REQUIRE(d.stats.connectivity_rounds >= 2);  // the case this test is about
  REQUIRE(d.stats.pinned_labels > 0);
  REQUIRE(disconnected_cells(d, mesh) == 0);
  const DiagramVerification v = verify_diagram(mesh, samples, d);
  INFO(describe(v));
  REQUIRE(v.passed);
}

namespace {

// Where every restricted Voronoi cell is connected, the LRVD is the RVD: the same polygons in the
// same order, each the same cyclic sequence of symbolic vertices (clipping order may start it
// elsewhere). The RVD clips each cell on its own with full vertices; the LRVD's clipper packs its
// vertices and shares side tests between cells, so this checks that path vertex for vertex.
void require_same_polygons(const Diagram& rvd, const Diagram& lrvd) {
  REQUIRE(rvd.polygons.size() == lrvd.polygons.size());
  REQUIRE(rvd.triangle_offsets == lrvd.triangle_offsets);
  for (size_t p = 0; p < rvd.polygons.size(); ++p) {
    const CellPolygon &a = rvd.polygons[p], &b = lrvd.polygons[p];
    REQUIRE(a.triangle == b.triangle);
    REQUIRE(a.cell == b.cell);
    REQUIRE(a.vertex_count == b.vertex_count);
    // The same cyclic sequence of symbolic vertices (clipping order may start it elsewhere).
    const SymbolicVertex *va = rvd.polygon_vertices(a), *vb = lrvd.polygon_vertices(b);
    int shift = 0;
    while (shift < b.vertex_count && !(vb[shift] == va[0])) ++shift;
    REQUIRE(shift < b.vertex_count);
    for (int k = 0; k < a.vertex_count; ++k) REQUIRE(va[k] == vb[(k + shift) % b.vertex_count]);
  }
}

}  // namespace

TEST_CASE("RVD and LRVD are identical polygon for polygon on a sphere, densely and sparsely sampled", "[rvd][lrvd]") {
  const SurfaceMesh mesh = test::icosphere(5);  // 20480 triangles
  // At 60 samples most triangles lie inside one cell, and the LRVD keeps them as that cell alone
  // (voronoi/lrvd_workspace.h, TriangleStates).
  for (int n : {2000, 60}) {
    const Samples samples = sample_uniform(mesh, n, 11);
    const Diagram lrvd = compute_lrvd(mesh, samples);
    INFO(n << " samples");
    require_same_polygons(compute_rvd(mesh, samples), lrvd);
    REQUIRE(verify_diagram(mesh, samples, lrvd).passed);
  }
}

TEST_CASE("RVD and LRVD are identical on a coarse square: one, a few and many candidates a triangle",
          "[rvd][lrvd]") {
  // A plane square's Voronoi cells are convex, so connected. 8 triangles: 40 samples give most
  // triangles 3 to 16 candidates (the clipper's packed vertices), 300 samples more than 16 (its
  // per-cell path with full vertices); 1 sample, one candidate everywhere (no vertices stored).
  const SurfaceMesh mesh = test::grid(2, 2);
  for (int n : {1, 40, 300}) {
    INFO("n = " << n);
    const Samples samples = sample_uniform(mesh, n, 5);
    const Diagram lrvd = compute_lrvd(mesh, samples);
    size_t most = 0;
    for (int t = 0; t < mesh.triangle_count(); ++t)
      most = std::max<size_t>(most, lrvd.triangle_offsets[t + 1] - lrvd.triangle_offsets[t]);
    if (n == 1) REQUIRE(most == 1);
    if (n == 40) REQUIRE((most >= 3 && most <= 16));
    if (n == 300) REQUIRE(most > 16);
    require_same_polygons(compute_rvd(mesh, samples), lrvd);
    REQUIRE(verify_diagram(mesh, samples, lrvd).passed);
  }
}

TEST_CASE("The clipper's many-candidate path gives clip_triangle's polygons vertex for vertex, skipping far bisectors",
          "[lrvd][clip]") {
  // More than CellClipper::kMaxLabels candidates: each cell's polygon skips the bisectors that a
  // certified bound shows cannot cut it. The polygons must be the unpruned loop's, in the same
  // order from the same first vertex, for long and compact triangles, equal and unequal weights,
  // and for coordinates beyond the filters' range (no bound taken there).
  std::mt19937_64 rng(3);
  for (const double scale : {1.0, 0x1p110}) {
    for (const bool needle : {true, false}) {
      const SurfaceMesh mesh({Vec3{0, 0, 0} * scale, (needle ? Vec3{100, 0, 0} : Vec3{3, 0, 0}) * scale,
                              (needle ? Vec3{0, 0.5, 0.2} : Vec3{0, 3, 1}) * scale},
                             {Triangle{0, 1, 2}});
      for (const bool weighted : {false, true}) {
        const int m = 17 + int(rng() % 44);
        std::uniform_real_distribution<double> along(0, needle ? 100 : 3), across(-0.5, 1.5), weight(-0.2, 0.2);
        std::vector<Site> sites(m);
        for (int s = 0; s < m; ++s)
          sites[s] = Site{Vec3{along(rng), across(rng), across(rng)} * scale,
                          weighted ? weight(rng) * scale * scale : 0.0, s};
        sites[m - 1].p = sites[m - 2].p;  // one site twice
        const SymbolicContext ctx =
            checked_context(mesh.positions().data(), mesh.positions().size(), sites.data(), sites.size());
        REQUIRE(ctx.in_range == (scale == 1.0));
        std::vector<int> labels(m);
        for (int s = 0; s < m; ++s) labels[s] = s;
        CellClipper clipper;
        std::vector<TrianglePolygon> polygons;
        std::vector<PackedVertex> verts;
        std::vector<SymbolicVertex> wide;
        reset_predicate_stats();
        clipper.clip(mesh, 0, labels.data(), m, ctx, polygons, verts, wide);
        const std::uint64_t pruned_calls = predicate_stats().total.calls;
        REQUIRE(verts.empty());
        std::vector<SymbolicVertex> polygon, scratch;
        size_t next = 0, begin = 0;
        reset_predicate_stats();
        for (int k = 0; k < m; ++k) {
          clip_triangle(mesh, 0, k, labels.data(), m, ctx, polygon, scratch);
          if (polygon.empty()) continue;
          INFO("scale " << scale << " needle " << needle << " weighted " << weighted << " m " << m << " cell " << k);
          REQUIRE(next < polygons.size());
          REQUIRE(polygons[next].cell == k);
          const std::vector<SymbolicVertex> got(wide.begin() + begin, wide.begin() + polygons[next].end);
          REQUIRE(got == polygon);
          begin = polygons[next++].end;
        }
        const std::uint64_t plain_calls = predicate_stats().total.calls;
        CHECK(next == polygons.size());
        // Far bisectors are skipped where bounds can be taken; beyond the range every one is tested.
        if (scale == 1.0 && needle) CHECK(pruned_calls * 2 < plain_calls);
        if (scale != 1.0) CHECK(pruned_calls == plain_calls);
      }
    }
  }
}

TEST_CASE("Degenerate samples: on mesh vertices and edges, cospherical, shared triangles, n = 1 and n = V",
          "[lrvd][degenerate]") {
  const SurfaceMesh sphere = test::icosphere(2);  // 162 vertices, all on the unit sphere
  auto check = [&](const Samples& samples, const std::string& label) {
    for (DiagramKind kind : {DiagramKind::Lrvd, DiagramKind::Rvd}) {
      const Diagram d = compute_diagram(sphere, samples, kind);
      const DiagramVerification v = verify_diagram(sphere, samples, d);
      INFO(label << " " << to_string(kind) << "\n" << describe(v));
      REQUIRE(v.passed);
      if (kind == DiagramKind::Lrvd) REQUIRE(v.cells_with_multiple_components == 0);
    }
  };
  // Samples on every mesh vertex: cospherical, each mesh vertex equidistant from many samples.
  std::vector<Vec3> on_vertices = sphere.positions();
  check(locate_points(sphere, on_vertices), "all vertices (n = V, cospherical)");
  // Samples on a subset of vertices and on edge midpoints.
  std::vector<Vec3> mixed;
  for (int v = 0; v < sphere.vertex_count(); v += 7) mixed.push_back(sphere.position(v));
  for (int t = 0; t < sphere.triangle_count(); t += 23) {
    const Triangle& tri = sphere.triangle(t);
    mixed.push_back(0.5 * (sphere.position(tri[0]) + sphere.position(tri[1])));
  }
  check(locate_points(sphere, mixed), "vertices and edge midpoints");
  // Two and three samples in one triangle.
  const Triangle& tri = sphere.triangle(5);
  const Vec3 a = sphere.position(tri[0]), b = sphere.position(tri[1]), c = sphere.position(tri[2]);
  check(locate_points(sphere, {(a + b + c) / 3.0, 0.6 * a + 0.2 * b + 0.2 * c, 0.2 * a + 0.6 * b + 0.2 * c,
                               sphere.position(100)}),
        "three samples in one triangle");
  check(sample_uniform(sphere, 1, 3), "n = 1");
  // Samples symmetric about a mesh vertex (it is equidistant from both).
  const Vec3 left = Vec3{0.3, 0, 1} / norm(Vec3{0.3, 0, 1}), right = Vec3{-0.3, 0, 1} / norm(Vec3{-0.3, 0, 1});
  check(locate_points(sphere, {left, right, Vec3{0, 0, -1}}), "symmetric pair");
}

TEST_CASE("The power variants pass their promised properties", "[lrpd]") {
  const SurfaceMesh mesh = make_stress_mesh("folded_sheet", 0.5);
  for (int seed = 1; seed <= 3; ++seed) {
    Samples samples = sample_uniform(mesh, 100, seed);
    Random random(seed);
    for (int i = 0; i < samples.size(); ++i) samples.weights.push_back(1e-4 * random.uniform());
    for (DiagramKind kind : {DiagramKind::Lrpd, DiagramKind::Rpd}) {
      const Diagram d = compute_diagram(mesh, samples, kind);
      REQUIRE(d.kind == kind);
      const DiagramVerification v = verify_diagram(mesh, samples, d);
      INFO(to_string(kind) << " seed " << seed << "\n" << describe(v));
      REQUIRE(v.passed);
      if (kind == DiagramKind::Lrpd) REQUIRE(v.cells_with_multiple_components == 0);
    }
  }
  Samples unweighted = sample_uniform(mesh, 10, 1);
  REQUIRE_THROWS_WITH(compute_diagram(mesh, unweighted, DiagramKind::Lrpd), Catch::Contains("weight"));
}

TEST_CASE("LRPD cells with stray pieces in each other's own triangle stay conforming and connected", "[lrpd]") {
  // The maximal Poisson-disk samples of CGAL's ChineseDragon, on the unrefined mesh. Seed 10: cells
  // have stray pieces in (or next to) each other's own triangle. Forbidding both grows each home
  // polygon onto an edge across which its cell is forbidden; before those conflicts were settled
  // (the cell let back in and pinned there) 3 edges did not conform. Seed 37: a cell taken out of a
  // triangle kept a polygon reaching that triangle's edge from the neighbour, which nothing
  // re-examined; edge (2264, 2327) did not conform until removals re-checked the neighbours. Since
  // stray pieces near each other are removed in separate rounds, seed 37 needs no pin. Those cases
  // were found on the samples of the sampler's first gap round computed on an LRPD; on today's
  // samples seed 10 still pins 2 labels (of seeds 1-80 only 10, 19 and 56 pin any) and seed 37
  // forbids 33.
  const SurfaceMesh dragon = cgal_mesh("ChineseDragon-10kv.off");
  for (const auto& [seed, count] : {std::pair{10, 17306}, std::pair{37, 17373}}) {
    MpsOptions options;
    options.radius = 0.01;
    options.seed = seed;
    options.refinement = MpsRefinement::MinRadius;  // the splitting these samples were found with,
    options.refine_order = RefineOrder::Input;      // in that order,
    options.conflict = MpsConflict::CloseAcrossTurns;  // by that conflict rule,
    options.sample_features = false;                   // with darts alone
    const MpsResult r = maximal_poisson_disk_sampling(dragon, options);
    const Samples samples = locate_points(dragon, r.samples.positions, r.samples.weights);
    INFO("seed " << seed);
    REQUIRE(samples.size() == count);  // else the samples changed: find seeds that show both cases again
    LrvdOptions lrpd;
    lrpd.weighted = true;
    const Diagram d = compute_lrvd(dragon, samples, lrpd);
    const DiagramVerification v = verify_diagram(dragon, samples, d);
    INFO(describe(v));
    CHECK(d.stats.forbidden_labels > 0);  // the cases this test is about
    if (seed == 10) CHECK(d.stats.pinned_labels > 0);
    CHECK(v.conforming.passed);
    CHECK(v.connected.passed);
    CHECK(v.cells_with_multiple_components == 0);
    CHECK(v.passed);
  }
}

TEST_CASE("A shapeless mask leaves the cells as they are and drops only the masked triangles' vertices", "[lrpd]") {
  const SurfaceMesh mesh = make_stress_mesh("folded_sheet", 0.5);
  Samples samples = sample_uniform(mesh, 200, 4);
  Random random(4);
  for (int i = 0; i < samples.size(); ++i) samples.weights.push_back(1e-4 * random.uniform());
  LrvdOptions options;
  options.weighted = true;
  const Diagram full = compute_lrvd(mesh, samples, options);
  std::vector<char> mask(mesh.triangle_count());
  for (int t = 0; t < mesh.triangle_count(); ++t) mask[t] = t % 3 != 0;
  options.shapeless = &mask;
  const Diagram part = compute_lrvd(mesh, samples, options);
  REQUIRE(part.triangle_offsets == full.triangle_offsets);
  REQUIRE(part.polygons.size() == full.polygons.size());
  size_t expected_vertices = 0;
  for (size_t p = 0; p < full.polygons.size(); ++p) {
    const CellPolygon &a = full.polygons[p], &b = part.polygons[p];
    REQUIRE(b.triangle == a.triangle);
    REQUIRE(b.cell == a.cell);
    if (mask[a.triangle]) {
      REQUIRE(b.vertex_count == 0);
      continue;
    }
    expected_vertices += a.vertex_count;
    REQUIRE(b.vertex_count == a.vertex_count);
    for (int k = 0; k < a.vertex_count; ++k)
      REQUIRE(part.polygon_vertices(b)[k] == full.polygon_vertices(a)[k]);
  }
  REQUIRE(part.vertices.size() == expected_vertices);
  REQUIRE(expected_vertices < full.vertices.size());
  mask.pop_back();
  REQUIRE_THROWS_AS(compute_lrvd(mesh, samples, options), std::logic_error);
}

TEST_CASE("Cell integrals add up to the surface", "[lrvd]") {
  const SurfaceMesh mesh = cgal_mesh("knot.off");
  const Samples samples = sample_uniform(mesh, 200, 5);
  const Diagram d = compute_lrvd(mesh, samples);
  const CellIntegrals cells = integrate_cells(d, mesh, samples);
  double area = 0;
  for (double a : cells.area) area += a;
  REQUIRE(area == Approx(mesh.area()).epsilon(1e-10));
  for (int i = 0; i < samples.size(); ++i) {
    REQUIRE(cells.area[i] > 0);
    // The centroid lies within the cell's reach of its sample.
    REQUIRE(distance(cells.centroid[i], samples.positions[i]) < std::sqrt(cells.area[i]) * 3);
  }
  REQUIRE(cells.total_energy > 0);
}

TEST_CASE("The library refuses an empty mesh and samples whose parts disagree, instead of reading past them", "[lrvd][input]") {
  using Catch::Contains;
  const SurfaceMesh empty;
  REQUIRE_THROWS_AS(sample_uniform(empty, 5, 1), InputError);
  REQUIRE_THROWS_AS(sample_by_component(empty, 3, 1, {}), InputError);
  REQUIRE_THROWS_AS(locate_points(empty, {{0, 0, 0}}), InputError);
  REQUIRE_THROWS_WITH(remesh_to(empty, 10), Contains("the mesh is empty"));
  REQUIRE_THROWS_AS(empty.bounding_box(), InputError);

  const SurfaceMesh mesh = test::icosphere(2);
  const Samples good = sample_uniform(mesh, 30, 1);
  Samples short_triangles = good;
  short_triangles.triangles.resize(5);
  REQUIRE_THROWS_WITH(compute_lrvd(mesh, short_triangles), Contains("30 positions but 5 triangles"));
  REQUIRE_THROWS_WITH(compute_rvd(mesh, short_triangles), Contains("30 positions but 5 triangles"));
  Samples short_weights = good;
  short_weights.weights.assign(10, 0.01);
  REQUIRE_THROWS_WITH(compute_diagram(mesh, short_weights, DiagramKind::Lrpd), Contains("30 positions but 10 weights"));
  Samples nan_weight = good;
  nan_weight.weights.assign(30, 0.01);
  nan_weight.weights[2] = NAN;
  REQUIRE_THROWS_WITH(compute_diagram(mesh, nan_weight, DiagramKind::Lrpd), Contains("sample 2 has a non-finite weight"));
  // The maximality check's exact arithmetic once died on it (SIGFPE in GMP).
  REQUIRE_THROWS_WITH(verify_mps(mesh, nan_weight), Contains("sample 2 has a non-finite weight"));
  Samples nan_position = good;
  nan_position.positions[4].y = NAN;
  REQUIRE_THROWS_WITH(compute_lrvd(mesh, nan_position), Contains("sample 4 has a non-finite coordinate"));

  // A diagram, a mesh and samples that do not belong together.
  const Diagram diagram = compute_lrvd(mesh, good);
  Samples fewer = good;
  for (auto* v : {&fewer.positions, &fewer.barycentric}) v->resize(20);
  fewer.triangles.resize(20);
  REQUIRE_THROWS_WITH(integrate_cells(diagram, mesh, fewer), Contains("30 cells but 20 samples"));
  REQUIRE_THROWS_WITH(integrate_cells(diagram, test::icosphere(1), good), Contains("a mesh of 320 triangles"));
  const std::vector<double> short_density(7, 1.0);
  REQUIRE_THROWS_WITH(integrate_cells(diagram, mesh, good, &short_density), Contains("7 densities for 320 triangles"));
  REQUIRE_THROWS_WITH(optimize_cvt(mesh, fewer, {}, &diagram), Contains("not of these samples"));
}

TEST_CASE("Options out of range are refused naming the option, not clamped or passed to the solver", "[lrvd][input]") {
  using Catch::Contains;
  const SurfaceMesh mesh = test::icosphere(2);
  const Samples start = sample_uniform(mesh, 30, 1);
  CvtOptions cvt;
  cvt.triangle_density.assign(mesh.triangle_count(), 1.0);
  cvt.triangle_density[7] = -1;  // once "'epsilon' must be non-negative", from the L-BFGS solver
  REQUIRE_THROWS_WITH(optimize_cvt(mesh, start, cvt), Contains("density of triangle 7 is -1"));
  cvt.triangle_density[7] = NAN;  // once a CVT with energy nan and no error
  REQUIRE_THROWS_WITH(optimize_cvt(mesh, start, cvt), Contains("density of triangle 7 is nan"));
  cvt = {};
  cvt.iterations = -1;
  REQUIRE_THROWS_WITH(optimize_cvt(mesh, start, cvt), Contains("may not be negative"));

  RemeshOptions remesh;
  remesh.repair_rounds = -1;  // once taken as 0
  REQUIRE_THROWS_WITH(remesh_cvt(mesh, mesh, start, remesh), Contains("repair_rounds (-1)"));
  remesh = {};
  remesh.relax.rounds = -2;  // once taken as no relaxation
  REQUIRE_THROWS_WITH(remesh_cvt(mesh, mesh, start, remesh), Contains("rounds (-2)"));
  remesh = {};
  remesh.repair_factor = NAN;
  REQUIRE_THROWS_WITH(remesh_cvt(mesh, mesh, start, remesh), Contains("repair factor must be a number above 1"));
  // Samples too few for the surface, and a mesh that is no refinement of the reference.
  REQUIRE_THROWS_WITH(remesh_cvt(mesh, mesh, sample_uniform(mesh, 3, 1)), Contains("3 vertices are too few"));
  const SurfaceMesh two = test::merge(mesh, test::octahedron(), {4, 0, 0});
  REQUIRE_THROWS_WITH(remesh_cvt(two, mesh, start), Contains("is not a refinement of the reference"));

  MpsOptions mps;
  mps.radius = 0.1;
  mps.adaptive = true;
  mps.max_radius_ratio = NAN;  // once a uniform sampling at r_min without a word
  REQUIRE_THROWS_WITH(maximal_poisson_disk_sampling(mesh, mps), Contains("radius ratio"));
  mps = {};
  mps.radius = 1e-6;
  mps.max_expected_samples = NAN;  // once switched the memory guard off
  REQUIRE_THROWS_AS(maximal_poisson_disk_sampling(mesh, mps), InputError);

  ReadOptions read;
  read.weld = -1;  // once did nothing without a word
  REQUIRE_THROWS_WITH(read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/elk.off", read), Contains("weld (-1)"));
}

TEST_CASE("Bad diagram input is refused with a clear message", "[lrvd][input]") {
  const SurfaceMesh mesh = test::icosphere(2);
  REQUIRE_THROWS_WITH(compute_lrvd(mesh, Samples{}), Catch::Contains("no samples"));
  REQUIRE_THROWS_WITH(locate_points(mesh, {{0, 0, 1}, {0, 0, 1}}), Catch::Contains("coincide"));
  REQUIRE_THROWS_WITH(locate_points(mesh, {{0, 0, 1}, {0, NAN, 1}}), Catch::Contains("non-finite"));
  REQUIRE_THROWS_WITH(locate_points(mesh, {{0, 0, 3}}), Catch::Contains("from the surface"));
  // The first point that repeats an earlier one is named, with that one, and the lines when known.
  const std::vector<Vec3> repeated = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
  REQUIRE_THROWS_WITH(locate_points(mesh, repeated), Catch::StartsWith("points 1 and 3 coincide"));
  REQUIRE_THROWS_WITH(locate_points(mesh, repeated, {}, {2, 3, 5, 6, 7}),
                      Catch::StartsWith("points 1 (line 3) and 3 (line 6) coincide"));
  // The distance limit is named as such, beside the diagonal it is 1% of.
  REQUIRE_THROWS_WITH(locate_points(mesh, {{0, 0, 3}}),
                      Catch::Contains("farther than " + fmt::format("{:.3g}", 0.01 * mesh.bounding_box().diagonal()) +
                                      " (1% of the bounding-box diagonal, " +
                                      fmt::format("{:.4g}", mesh.bounding_box().diagonal()) + ")"));
  REQUIRE_THROWS_WITH(sample_uniform(mesh, 0, 1), Catch::Contains("at least 1"));
  // A component without a sample would have no cell (the CVT once handed such samples over and the
  // builder wrote out of bounds): refused, naming the component.
  const SurfaceMesh two = test::merge(mesh, test::octahedron(), {4, 0, 0});
  Samples one_side = sample_uniform(mesh, 10, 1);
  REQUIRE_NOTHROW(compute_lrvd(mesh, one_side));
  REQUIRE_THROWS_WITH(compute_lrvd(two, one_side), Catch::Contains("component 1") && Catch::Contains("holds no sample"));
  REQUIRE_NOTHROW(compute_lrvd(two, sample_uniform(two, 10, 1)));
  // More samples than triangles without refinement: several samples share triangles (§3.5); the
  // diagram is still valid.
  const SurfaceMesh coarse = test::octahedron();
  const Samples crowded = sample_uniform(coarse, 40, 2);
  const Diagram d = compute_lrvd(coarse, crowded);
  const DiagramVerification v = verify_diagram(coarse, crowded, d);
  INFO(describe(v));
  REQUIRE(v.passed);
}

TEST_CASE("the region growing's entries order as (power distance, sample, vertex)", "[lrvd]") {
  // The heap compares one 128-bit key; it must give the order of the three numbers, for negative
  // power distances (weighted diagrams) and for -0 and +0, which the doubles' order calls equal.
  using lrvd::detail::VertexEntry;
  std::mt19937_64 rng(7);
  const double specials[] = {0.0, -0.0, 1e-310, -1e-310, 1.0, -1.0, 1.5, -2.5, 1e300, -1e300,
                             std::numeric_limits<double>::min(), std::numeric_limits<double>::infinity()};
  std::uniform_real_distribution<double> value(-10.0, 10.0);
  std::uniform_int_distribution<int> small(0, 3), large(0, std::numeric_limits<int>::max());
  auto draw = [&] {
    const double d = rng() % 3 == 0 ? specials[rng() % std::size(specials)] : value(rng);
    const int sample = rng() % 2 ? small(rng) : large(rng), vertex = rng() % 2 ? small(rng) : large(rng);
    return std::make_tuple(d, sample, vertex);
  };
  for (int k = 0; k < 20000; ++k) {
    const auto [da, sa, va] = draw();
    const auto [db, sb, vb] = draw();
    const VertexEntry a(da, sa, va), b(db, sb, vb);
    CHECK(a.sample() == sa);
    CHECK(a.vertex() == va);
    const bool greater = da > db || (da == db && (sa > sb || (sa == sb && va > vb)));
    INFO(da << " " << sa << " " << va << " against " << db << " " << sb << " " << vb);
    CHECK((a > b) == greater);
  }
  CHECK_FALSE(VertexEntry(-0.0, 1, 2) > VertexEntry(0.0, 1, 2));
  CHECK_FALSE(VertexEntry(0.0, 1, 2) > VertexEntry(-0.0, 1, 2));
  CHECK(VertexEntry(0.0, 2, 0) > VertexEntry(-0.0, 1, 5));
  CHECK(VertexEntry(-1e-310, 0, 0) > VertexEntry(-1.0, 9, 9));
}

TEST_CASE("Cells left in pieces on coarse folded triangles are computed again on finer ones", "[lrvd]") {
  // A box whose faces are folded flat onto each other (six of its corners in the plane x = 0): on
  // the automatic refinement's 62 triangles, three cells compete for the overlapping sheets and
  // the connectivity restoration cycles between them (found by fuzz_compute).
  const std::vector<Vec3> positions = {{0, 10.25, 47}, {0, 0, -256}, {0, 257, 256},  {0, 192, 0},
                                       {192, 0, 0},    {0, 0, 257},  {256, 0, 5}, {0, 256, 1}};
  const std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}, {0, 3, 5}, {0, 5, 4},
                                           {3, 2, 6}, {3, 6, 5}, {2, 1, 7}, {2, 7, 6}, {1, 0, 4}, {1, 4, 7}};
  SampleRequest request;
  request.count = 16;
  request.seed = 7;
  auto prepared = [&](const std::string& refine) {
    Input input;
    input.loaded.mesh = SurfaceMesh(positions, triangles);
    request.refine = refine;
    prepare_samples(input, request);
    return input;
  };
  Input input = prepared("auto");
  const int coarse = input.mesh.triangle_count();
  const Diagram diagram = compute_input_diagram(input, DiagramKind::Lrvd);
  CHECK(input.connectivity_refinements >= 1);
  CHECK(input.mesh.triangle_count() > coarse);
  CHECK(input.samples.size() == 16);
  const DiagramVerification check = verify_diagram(input.mesh, input.samples, diagram);
  INFO(check.summary());
  CHECK(check.passed);

  // A refinement given by length is the user's: the diagram is computed once, on it.
  Input given = prepared(fmt::format("{:.17g}", input.loaded.mesh.max_edge_length()));
  compute_input_diagram(given, DiagramKind::Lrvd);
  CHECK(given.connectivity_refinements == 0);
}
