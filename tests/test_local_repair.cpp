// Local repair rounds: the CVT's movable mask, the window's CVT on its sub-mesh, and remeshes whose
// repair rounds are local.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "common/error.h"
#include "io/mesh_io.h"
#include "mesh/refine.h"
#include "mesh/stress.h"
#include "remesh/local_repair.h"
#include "remesh/remesh.h"
#include "verification/remesh_check.h"
#include "voronoi/lrvd.h"

using namespace lrvd;

namespace {

SurfaceMesh cgal_mesh(const std::string& name) { return read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/" + name).mesh; }

// How many samples of `after` are not exactly where they are in `before` (position, triangle,
// barycentric coordinates), among those `select` picks.
template <class Select>
int moved_samples(const Samples& before, const Samples& after, Select select) {
  int moved = 0;
  for (int i = 0; i < before.size(); ++i)
    if (select(i) && !(before.positions[i] == after.positions[i] && before.triangles[i] == after.triangles[i] &&
                       before.barycentric[i] == after.barycentric[i]))
      ++moved;
  return moved;
}

}  // namespace

TEST_CASE("A CVT's movable mask leaves the frozen samples exactly where they are", "[cvt][local]") {
  const SurfaceMesh mesh = cgal_mesh("knot.off");
  const Samples start = sample_uniform(mesh, 200, 3);
  for (const CvtOptimizer optimizer : {CvtOptimizer::Lbfgs, CvtOptimizer::Lloyd}) {
    CvtOptions options;
    options.optimizer = optimizer;
    options.iterations = 15;
    options.movable.assign(start.size(), 0);
    for (int i = 0; i < start.size(); i += 3) options.movable[i] = 1;
    const CvtResult r = optimize_cvt(mesh, start, options);
    INFO((optimizer == CvtOptimizer::Lbfgs ? "L-BFGS" : "Lloyd"));
    REQUIRE(moved_samples(start, r.samples, [&](int i) { return !options.movable[i]; }) == 0);
    // The movable ones do move, and lower the energy.
    REQUIRE(moved_samples(start, r.samples, [&](int i) { return options.movable[i] != 0; }) > 50);
    REQUIRE(r.energy < r.energy_history.front());
  }
  CvtOptions wrong;
  wrong.movable.assign(start.size() - 1, 1);
  REQUIRE_THROWS_AS(optimize_cvt(mesh, start, wrong), InputError);
}

TEST_CASE("A window's CVT moves its own samples only, on its sub-mesh, and returns the diagram of all", "[cvt][local]") {
  const SurfaceMesh mesh = cgal_mesh("knot.off");
  CvtOptions first;
  first.iterations = 10;
  const CvtResult cvt = optimize_cvt(mesh, sample_uniform(mesh, 300, 1), first);
  // A window round two cells, as a repair round raises the density there.
  const std::vector<char> window = repair_window(cvt.diagram, {5, 77}, 2);
  const auto moving = std::count(window.begin(), window.end(), 1);
  const auto frozen = std::count(window.begin(), window.end(), 2);
  REQUIRE(moving >= 2 + 6);  // the two cells and at least their first ring
  REQUIRE(frozen > 0);
  REQUIRE(moving + frozen < 150);
  CvtOptions round;
  round.iterations = 30;
  round.lloyd_warmup = 1;
  round.triangle_density.assign(mesh.triangle_count(), 1.0);
  for (const CellPolygon& poly : cvt.diagram.polygons)
    if (poly.cell == 5 || poly.cell == 77) round.triangle_density[poly.triangle] = 2.0;
  const CvtResult r = optimize_cvt_in_window(mesh, cvt.samples, cvt.diagram, window, round);
  REQUIRE(moved_samples(cvt.samples, r.samples, [&](int i) { return window[i] != 1; }) == 0);
  REQUIRE(moved_samples(cvt.samples, r.samples, [&](int i) { return window[i] == 1; }) > moving / 2);
  // The diagram returned is the whole mesh's diagram of the new samples, and the raised density's
  // energy went down.
  const CvtEnergy whole = cvt_energy(mesh, r.samples, DiagramKind::Lrvd, &round.triangle_density);
  REQUIRE(r.diagram.polygons.size() == whole.diagram.polygons.size());
  REQUIRE(r.energy == whole.energy);
  REQUIRE(r.energy_history.size() == 2);
  REQUIRE(r.energy < r.energy_history.front());
  // Every sample stays on the surface: its triangle's point at its barycentric coordinates.
  for (int i = 0; i < r.samples.size(); ++i) {
    const Triangle& tri = mesh.triangle(r.samples.triangles[i]);
    const Vec3& b = r.samples.barycentric[i];
    const Vec3 p = b.x * mesh.position(tri[0]) + b.y * mesh.position(tri[1]) + b.z * mesh.position(tri[2]);
    REQUIRE(norm(p - r.samples.positions[i]) < 1e-9 * mesh.bounding_box().diagonal());
  }
}

TEST_CASE("Local repair rounds alone mend a folded sheet at 100 vertices, a row of many whole rounds", "[cvt][remesh][local]") {
  // The folded sheet (a slab 0.005 thick whose walls face each other 0.02 apart) at 100 vertices:
  // its first CVT's dual has defects, which every round here mends on a window of cells (never a
  // whole CVT); the remesh is valid with exactly 100 vertices.
  const SurfaceMesh input = make_stress_mesh("folded_sheet", 1.0);
  const double length = suggested_refinement_length(input, 100);
  const SurfaceMesh mesh = length > 0 && input.max_edge_length() > length ? refine_long_edges(input, length) : input;
  RemeshOptions options;
  options.repair = RepairScope::Local;
  options.local_repair.whole_first = 0;
  options.local_repair.whole_after = options.repair_rounds + 1;
  const RemeshResult r = remesh_cvt(input, mesh, sample_uniform(mesh, 100, 1), options);
  const RemeshVerification check = verify_remesh(input, r.dual.positions, r.dual.triangles, 100);
  INFO(check.summary());
  REQUIRE(r.repair_rounds > 0);
  REQUIRE(r.dual.positions.size() == 100);
  REQUIRE(check.passed);
}

TEST_CASE("A remesh mended within the whole rounds a local repair starts with is the whole repair's: elk at 516", "[cvt][remesh][local]") {
  // The elk at 516 needs two repair rounds: with LocalRepairOptions::whole_first 2 both are whole
  // CVTs, and the output is the one of RepairScope::Whole to the last bit.
  const SurfaceMesh input = cgal_mesh("elk.off");
  const double length = suggested_refinement_length(input, 516);
  const SurfaceMesh mesh = length > 0 && input.max_edge_length() > length ? refine_long_edges(input, length) : input;
  const Samples start = sample_uniform(mesh, 516, 1);
  RemeshOptions whole, local;
  whole.repair = RepairScope::Whole;
  local.repair = RepairScope::Local;
  local.local_repair.whole_first = 2;
  const RemeshResult a = remesh_cvt(input, mesh, start, whole);
  const RemeshResult b = remesh_cvt(input, mesh, start, local);
  REQUIRE(a.repair_rounds == 2);
  REQUIRE(b.repair_rounds == 2);
  REQUIRE(b.dual.positions == a.dual.positions);
  REQUIRE(b.dual.triangles == a.dual.triangles);
  // With no whole round first, the rounds are local: the remesh differs, and is valid.
  local.local_repair.whole_first = 0;
  const RemeshResult c = remesh_cvt(input, mesh, start, local);
  REQUIRE_FALSE(c.dual.positions == a.dual.positions);
  REQUIRE(verify_remesh(input, c.dual.positions, c.dual.triangles, 516).passed);
}
