// CVT remeshing: the energy gradient, both optimisers, and the dual's validity and quality.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "mesh/mesh_io.h"
#include "mesh/stress.h"
#include "metrics/quality.h"
#include "metrics/self_intersections.h"
#include "remesh/remesh.h"
#include "test_meshes.h"
#include "verification/remesh_check.h"
#include "voronoi/lrvd.h"

using namespace lrvd;

namespace {

SurfaceMesh cgal_mesh(const std::string& name) { return read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/" + name).mesh; }

SurfaceMesh for_samples(const SurfaceMesh& mesh, int n) {
  const double length = suggested_refinement_length(mesh, n);
  return length > 0 && mesh.max_edge_length() > length ? refine_long_edges(mesh, length) : mesh;
}

struct Remeshed {
  RemeshResult result;
  RemeshVerification check;
  QualityMetrics quality;
};

Remeshed remesh(const SurfaceMesh& input, int n, int seed = 1) {
  const SurfaceMesh mesh = for_samples(input, n);
  Remeshed r;
  r.result = remesh_cvt(input, mesh, sample_uniform(mesh, n, seed));
  r.check = verify_remesh(input, r.result.dual.positions, r.result.dual.triangles, n);
  r.quality = quality_metrics(input, r.result.dual.positions, r.result.dual.triangles);
  return r;
}

// The first CVT of n uniform samples (`seed`) on `mesh` (the input itself or refined for n: no
// crossing components) and the defects of its dual, before any repair round.
struct FirstCvt {
  CvtResult cvt;
  DualDefects defects;
};

FirstCvt first_cvt(const SurfaceMesh& mesh, int n, int seed) {
  FirstCvt r;
  r.cvt = optimize_cvt(mesh, sample_uniform(mesh, n, seed), CvtOptions{});
  r.defects = find_dual_defects(compute_dual(r.cvt.diagram, mesh, r.cvt.samples), r.cvt.diagram, mesh, r.cvt.samples,
                                mesh.is_closed());
  return r;
}

// The remesh of n uniform samples (`seed`) on `mesh` with the vertices left at their samples: the
// CVT's dual, as the fitting and the relaxation get it.
RemeshResult unfitted(const SurfaceMesh& reference, const SurfaceMesh& mesh, int n, int seed) {
  RemeshOptions options;
  options.fit = false;
  return remesh_cvt(reference, mesh, sample_uniform(mesh, n, seed), options);
}
// Every triangle of `moved` (the same triangles as `before`) keeps its orientation.
void require_none_turned_over(const DualMesh& before, const DualMesh& moved) {
  REQUIRE(moved.triangles == before.triangles);
  auto normal = [](const DualMesh& m, const Triangle& f) {
    return cross(m.positions[f[1]] - m.positions[f[0]], m.positions[f[2]] - m.positions[f[0]]);
  };
  for (const Triangle& f : moved.triangles) REQUIRE(dot(normal(before, f), normal(moved, f)) > 0);
}

// A closed cone 10 high on a unit disk (12 sides): its apex's angles sum to about 35°.
SurfaceMesh closed_cone() {
  const int k = 12;
  std::vector<Vec3> positions = {{0, 0, 10}, {0, 0, 0}};
  std::vector<Triangle> triangles;
  for (int i = 0; i < k; ++i) positions.push_back({std::cos(2 * M_PI * i / k), std::sin(2 * M_PI * i / k), 0});
  for (int i = 0; i < k; ++i) {
    const int a = 2 + i, b = 2 + (i + 1) % k;
    triangles.push_back({0, a, b});
    triangles.push_back({1, b, a});
  }
  return SurfaceMesh(positions, triangles);
}

// The point of closed_cone's side at height z, `degrees` round the axis.
Vec3 on_cone(double z, double degrees) {
  const double r = (10 - z) / 10, a = degrees * M_PI / 180;
  return Vec3{r * std::cos(a), r * std::sin(a), z};
}

}  // namespace

TEST_CASE("The CVT gradient 2 m_i (x_i - c_i) matches finite differences", "[cvt]") {
  const SurfaceMesh mesh = test::icosphere(4);
  const Samples samples = sample_uniform(mesh, 60, 3);
  for (DiagramKind kind : {DiagramKind::Lrvd, DiagramKind::Rvd}) {
    const CvtEnergy e = cvt_energy(mesh, samples, kind);
    const double h = 1e-6;
    for (int i : {0, 17, 42})
      for (int c = 0; c < 3; ++c) {
        Samples plus = samples, minus = samples;
        plus.positions[i][c] += h;
        minus.positions[i][c] -= h;
        const double fd = (cvt_energy(mesh, plus, kind).energy - cvt_energy(mesh, minus, kind).energy) / (2 * h);
        INFO(to_string(kind) << " sample " << i << " axis " << c);
        REQUIRE(fd == Approx(e.gradient[i][c]).margin(1e-6 * norm(e.gradient[i]) + 1e-9).epsilon(1e-4));
      }
  }
}

TEST_CASE("Lloyd and L-BFGS both lower the CVT energy", "[cvt]") {
  const SurfaceMesh mesh = cgal_mesh("knot.off");
  const Samples initial = sample_uniform(mesh, 200, 2);
  for (CvtOptimizer optimizer : {CvtOptimizer::Lloyd, CvtOptimizer::Lbfgs}) {
    CvtOptions options;
    options.optimizer = optimizer;
    options.iterations = 40;
    const CvtResult r = optimize_cvt(mesh, initial, options);
    REQUIRE(r.energy_history.size() >= 2);
    REQUIRE(r.energy < 0.8 * r.energy_history.front());
    REQUIRE(r.iterations > 0);
    REQUIRE(r.iterations <= 40);
    // Samples stay on the surface.
    for (int i = 0; i < r.samples.size(); ++i) {
      const Triangle& t = mesh.triangle(r.samples.triangles[i]);
      const Vec3 w = r.samples.barycentric[i];
      REQUIRE(distance(w.x * mesh.position(t[0]) + w.y * mesh.position(t[1]) + w.z * mesh.position(t[2]),
                       r.samples.positions[i]) < 1e-9);
    }
    if (optimizer == CvtOptimizer::Lloyd)  // Lloyd lowers the energy at (almost) every step
      for (size_t k = 1; k < r.energy_history.size(); ++k)
        REQUIRE(r.energy_history[k] <= r.energy_history[k - 1] * (1 + 1e-3));
  }
}

TEST_CASE("The CVT stops on relative changes: a model 1024 times smaller is optimised as far", "[cvt]") {
  // LBFGSpp's energy-change test is |f_k - f_k+1| <= delta · max(|f_k|, |f_k+1|, 1): absolute
  // below 1. A small model's energy is far below it (2^-40 of the unit sphere's here), and the test
  // stopped its CVT after a few iterations with a much higher energy.
  const SurfaceMesh unit = test::icosphere(3);
  std::vector<Vec3> shrunk = unit.positions();
  for (Vec3& p : shrunk) p = std::ldexp(1.0, -10) * p;
  const SurfaceMesh small(shrunk, unit.triangles());
  const Samples start = sample_uniform(unit, 60, 3);
  Samples start_small = start;
  for (Vec3& p : start_small.positions) p = std::ldexp(1.0, -10) * p;
  CvtOptions options;
  options.iterations = 40;
  const CvtResult a = optimize_cvt(unit, start, options);
  const CvtResult b = optimize_cvt(small, start_small, options);
  REQUIRE(b.energy_history.front() < 1e-9);  // the case: an energy far below 1
  REQUIRE(a.iterations == 40);
  REQUIRE(b.iterations == a.iterations);
  const double drop_a = a.energy / a.energy_history.front(), drop_b = b.energy / b.energy_history.front();
  REQUIRE(drop_b == Approx(drop_a).epsilon(0.01));
}

TEST_CASE("A remesh is the same in any unit: the elk at 516 scaled by 2^-30 and 2^30", "[cvt][remesh]") {
  // L-BFGS's first step moves the sites one unit of its variables: in the model's own unit, the
  // elk 516 took 95 evaluations at 2^5 its size (Qmin 0.561) and failed its line searches at 2^-40.
  // Its variables are now in a power of two of the cell size, so a power-of-two scaling of the
  // model scales the whole run exactly: the same triangles, every vertex times the factor.
  const SurfaceMesh elk = cgal_mesh("elk.off");
  const Samples start = sample_uniform(elk, 516, 1);
  RemeshOptions options;
  std::vector<std::string> lines;
  options.on_progress = [&](const std::string& line) { lines.push_back(line); };
  const RemeshResult base = remesh_cvt(elk, elk, start, options);
  REQUIRE(base.repair_rounds > 0);  // the case goes through the repair rounds and the fitting
  REQUIRE(base.polished);  // and the Lloyd step on the state kept
  // The progress lines tell each step: the first CVT's defects, each round before and after, the
  // Lloyd step, the eased density, its Lloyd step and the choice, the fitting.
  REQUIRE(lines.size() == 6 + 2 * static_cast<size_t>(base.repair_rounds));
  CHECK_THAT(lines.front(), Catch::StartsWith("CVT: ") && Catch::Contains("topological defects"));
  for (int k = 1; k <= base.repair_rounds; ++k) {
    CHECK_THAT(lines[2 * k - 1], Catch::StartsWith(fmt::format("repair round {} of {}: density x{} around", k,
                                                               options.repair_rounds, options.repair_factor)));
    CHECK_THAT(lines[2 * k], Catch::StartsWith(fmt::format("repair round {}: ", k)) && Catch::Contains("the dual has"));
  }
  CHECK_THAT(lines[2 * base.repair_rounds], Catch::EndsWith("the dual has no defect"));
  CHECK(lines[2 * base.repair_rounds + 1] == "1 Lloyd step on the samples: the dual has no defect");
  CHECK(lines[2 * base.repair_rounds + 2] == "10 iterations with the density eased 25% of the way back: the dual has no defect");
  CHECK(lines[2 * base.repair_rounds + 3] == "1 Lloyd step on the samples: the dual has no defect");
  CHECK_THAT(lines[2 * base.repair_rounds + 4], Catch::StartsWith("the eased state: worst triangle "));
  CHECK(lines.back() == "fitting the vertices to the surface");
  for (int k : {-30, 30}) {
    const double s = std::ldexp(1.0, k);
    std::vector<Vec3> scaled = elk.positions();
    for (Vec3& p : scaled) p = s * p;
    const SurfaceMesh mesh(scaled, elk.triangles());
    Samples moved = start;
    for (Vec3& p : moved.positions) p = s * p;
    const RemeshResult r = remesh_cvt(mesh, mesh, moved);
    INFO("2^" << k);
    REQUIRE(r.diagram_evaluations == base.diagram_evaluations);
    REQUIRE(r.dual.triangles == base.dual.triangles);
    REQUIRE(r.dual.positions.size() == base.dual.positions.size());
    for (size_t v = 0; v < r.dual.positions.size(); ++v) REQUIRE(r.dual.positions[v] == s * base.dual.positions[v]);
  }
}

TEST_CASE("A remesh's kept state takes a Lloyd step when its dual has no defect, and keeps it only then", "[cvt][remesh]") {
  // L-BFGS ends with its sites in space, put on the surface afterwards; the Lloyd step moves each
  // sample to its cell's centroid, which lowers the energy of a state L-BFGS left.
  const SurfaceMesh ellipsoid = cgal_mesh("ellipsoid.off");
  RemeshOptions without;
  without.polish_steps = 0;
  const RemeshResult plain = remesh_to(ellipsoid, 300, 1, without);
  const RemeshResult polished = remesh_to(ellipsoid, 300, 1);
  REQUIRE(plain.repair_rounds == 0);
  REQUIRE_FALSE(plain.polished);
  REQUIRE(polished.polished);
  CHECK(polished.diagram_evaluations == plain.diagram_evaluations + 1);
  CHECK(polished.total_iterations == plain.total_iterations + 1);
  CHECK(polished.cvt.energy < plain.cvt.energy);
  // The kept CVT's history is the run's and then the step's.
  REQUIRE(polished.cvt.energy_history.size() == plain.cvt.energy_history.size() + 1);
  CHECK(polished.cvt.energy_history.back() == polished.cvt.energy);
  CHECK(verify_remesh(ellipsoid, polished.dual.positions, polished.dual.triangles, 300).passed);

  // A state with defects is left as the rounds left it: the elk at 516 without repair rounds.
  const SurfaceMesh elk = cgal_mesh("elk.off");
  RemeshOptions no_rounds;
  no_rounds.repair_rounds = 0;
  no_rounds.keep_to_sheets_retry = false;
  const RemeshResult defective = remesh_to(elk, 516, 1, no_rounds);
  REQUIRE_FALSE(defective.defects.empty());
  CHECK_FALSE(defective.polished);
  no_rounds.polish_steps = 0;
  CHECK(remesh_to(elk, 516, 1, no_rounds).diagram_evaluations == defective.diagram_evaluations);
}

TEST_CASE("The density raised by repair rounds is eased back when the triangles gain by it", "[cvt][remesh]") {
  // Elk 300 needs repair rounds; the state they leave has no defect, and 10 iterations with the
  // density eased a quarter of the way back, then its Lloyd step, give it a better worst triangle.
  const SurfaceMesh elk = cgal_mesh("elk.off");
  RemeshOptions without;
  without.ease_iterations = 0;
  std::vector<std::string> lines;
  RemeshOptions with;
  with.on_progress = [&](const std::string& line) { lines.push_back(line); };
  const RemeshResult plain = remesh_to(elk, 300, 1, without);
  const RemeshResult eased = remesh_to(elk, 300, 1, with);
  REQUIRE(plain.repair_rounds > 0);
  REQUIRE(eased.repair_rounds == plain.repair_rounds);  // the rounds are the same; what follows them differs
  REQUIRE_FALSE(plain.eased);
  REQUIRE(eased.eased);
  // The easing's iterations and its Lloyd step cost diagrams (a line search may take several an
  // iteration, but not ten on average).
  CHECK(eased.diagram_evaluations > plain.diagram_evaluations + with.ease_iterations);
  CHECK(eased.diagram_evaluations < plain.diagram_evaluations + 10 * with.ease_iterations);
  // The choice is told, with the worst triangle of each state (before the fitting).
  const auto line = std::find_if(lines.begin(), lines.end(),
                                 [](const std::string& l) { return l.rfind("the eased state: ", 0) == 0; });
  REQUIRE(line != lines.end());
  double before = 0, after = 0;
  REQUIRE(std::sscanf(line->c_str(), "the eased state: worst triangle %lf -> %lf, kept", &before, &after) == 2);
  CHECK(after > before);
  CHECK(verify_remesh(elk, eased.dual.positions, eased.dual.triangles, 300).passed);
  CHECK(verify_remesh(elk, plain.dual.positions, plain.dual.triangles, 300).passed);

  // A run without repair rounds is not eased: the ellipsoid at 300 is the same either way.
  const SurfaceMesh ellipsoid = cgal_mesh("ellipsoid.off");
  const RemeshResult clean = remesh_to(ellipsoid, 300, 1);
  const RemeshResult clean_without = remesh_to(ellipsoid, 300, 1, without);
  REQUIRE(clean.repair_rounds == 0);
  CHECK_FALSE(clean.eased);
  CHECK(clean.diagram_evaluations == clean_without.diagram_evaluations);
  CHECK(clean.dual.positions == clean_without.dual.positions);

  RemeshOptions bad;
  bad.ease_fraction = 1.5;
  CHECK_THROWS_AS(remesh_to(ellipsoid, 300, 1, bad), InputError);
  bad.ease_fraction = 0.25;
  bad.ease_iterations = -1;
  CHECK_THROWS_AS(remesh_to(ellipsoid, 300, 1, bad), InputError);
}

TEST_CASE("Remeshing and sampling refuse a model too large or too small for doubles, naming its size", "[cvt][remesh]") {
  const SurfaceMesh unit = test::icosphere(2);
  for (double s : {1e-200, 1e40, 1e200}) {
    std::vector<Vec3> scaled = unit.positions();
    for (Vec3& p : scaled) p = s * p;
    const SurfaceMesh mesh(scaled, unit.triangles());
    REQUIRE_THROWS_WITH(remesh_cvt(mesh, mesh, sample_uniform(mesh, 20, 1)),
                        Catch::Contains("across") && Catch::Contains("scale the model first"));
    REQUIRE_THROWS_AS(quality_metrics(mesh, mesh.positions(), mesh.triangles()), InputError);
  }
  // Inside the range the models work: 1e-25 and 1e25 across.
  for (double s : {1e-25, 1e25}) {
    std::vector<Vec3> scaled = unit.positions();
    for (Vec3& p : scaled) p = s * p;
    const SurfaceMesh mesh(scaled, unit.triangles());
    const RemeshResult r = remesh_cvt(mesh, mesh, sample_uniform(mesh, 40, 1));
    const RemeshVerification check = verify_remesh(mesh, r.dual.positions, r.dual.triangles, 40);
    INFO(s << "\n" << check.summary());
    REQUIRE(check.passed);
  }
}

TEST_CASE("The quality metrics refuse a remesh too large for doubles instead of giving inf and NaN", "[quality]") {
  const SurfaceMesh unit = test::icosphere(2);
  std::vector<Vec3> huge = unit.positions();
  for (Vec3& p : huge) p = 1e200 * p;
  REQUIRE_THROWS_WITH(quality_metrics(unit, huge, unit.triangles()),
                      Catch::Contains("the remesh is") && Catch::Contains("across"));
  // The same remesh at the reference's size is measured, also with a far vertex no triangle uses.
  std::vector<Vec3> with_unused = unit.positions();
  with_unused.push_back({1e200, 0, 0});
  const QualityMetrics m = quality_metrics(unit, with_unused, unit.triangles());
  REQUIRE(std::isfinite(m.q_avg));
  REQUIRE(m.hausdorff_pct < 1e-9);  // points drawn on a triangle are on it up to rounding
}

TEST_CASE("A CVT given the diagram of its start computes no diagram twice and ends where it would without it", "[cvt]") {
  const SurfaceMesh mesh = cgal_mesh("knot.off");
  CvtOptions options;
  options.iterations = 12;
  const CvtResult first = optimize_cvt(mesh, sample_uniform(mesh, 200, 2), options);
  options.lloyd_warmup = 1;
  options.triangle_density.assign(mesh.triangle_count(), 1.0);
  for (int t = 0; t < mesh.triangle_count(); t += 7) options.triangle_density[t] = 4.0;  // as a repair round
  const CvtResult fresh = optimize_cvt(mesh, first.samples, options);
  const CvtResult reused = optimize_cvt(mesh, first.samples, options, &first.diagram);
  REQUIRE(reused.diagram_evaluations == fresh.diagram_evaluations - 1);
  REQUIRE(reused.energy_history == fresh.energy_history);
  REQUIRE(reused.samples.positions == fresh.samples.positions);
}

TEST_CASE("A CVT that keeps samples to their sheets does not drain one side of a thin wall", "[cvt]") {
  // folded_sheet: a U of a 0.005-thick sheet whose walls face each other 0.02 apart. The cells of the
  // outer side wrap the bend; their centroids lie in the gap, closest to the inner side: projected
  // there, the outer side near the bend loses its samples (the dual's chords then cross).
  const SurfaceMesh input = make_stress_mesh("folded_sheet", 0.5);
  const SurfaceMesh mesh = for_samples(input, 300);
  const Samples initial = sample_uniform(mesh, 300, 1);
  auto near_bend = [](const Samples& s) {
    std::pair<int, int> outer_inner{0, 0};
    for (const Vec3& p : s.positions)
      if (p[0] > 0.4 && p[0] <= 0.5) ++(std::abs(p[1]) > 0.0125 ? outer_inner.first : outer_inner.second);
    return outer_inner;
  };
  CvtOptions options;
  const auto [outer, inner] = near_bend(optimize_cvt(mesh, initial, options).samples);
  options.keep_to_sheets = true;
  const auto [kept_outer, kept_inner] = near_bend(optimize_cvt(mesh, initial, options).samples);
  INFO("outer/inner near the bend: " << outer << "/" << inner << ", kept to sheets " << kept_outer << "/" << kept_inner);
  REQUIRE(2 * outer < inner);
  REQUIRE(3 * kept_outer >= 2 * kept_inner);
}

TEST_CASE("The dual of a CVT on the stress meshes is a manifold of the input's topology at low N", "[cvt][remesh]") {
  // The stress meshes where the remesh is valid today; comb (n = 100: too few samples for three
  // cells around every finger) fails: docs/results.md, "Seeds 1–3 on the hard rows".
  // folded_sheet 300 is valid through the second run that keeps samples on their own sheets
  // (RemeshOptions::keep_to_sheets_retry).
  const std::pair<const char*, int> cases[] = {{"thin_plate", 100},     {"thin_plate", 300}, {"open_cup", 100},
                                               {"open_cup", 300},       {"open_cup", 1000},
                                               {"flat_ellipsoid", 100}, {"flat_ellipsoid", 300}, {"knot_tube", 100},
                                               {"knot_tube", 300},      {"comb", 300},       {"thin_tube", 100},
                                               {"thin_tube", 300},      {"folded_sheet", 100}, {"folded_sheet", 300},
                                               {"interpenetrating_spheres", 100}, {"interpenetrating_spheres", 300}};
  for (const auto& [name, n] : cases) {
    const SurfaceMesh input = make_stress_mesh(name, 0.5);
    {
      const Remeshed r = remesh(input, n);
      INFO(name << " n=" << n << "\n" << r.check.summary());
      REQUIRE(r.result.dual.positions.size() == static_cast<size_t>(n));
      REQUIRE(r.check.vertex_count.passed);
      REQUIRE(r.check.manifold.passed);
      REQUIRE(r.check.closed.passed);
      REQUIRE(r.check.oriented.passed);
      REQUIRE(r.check.topology.passed);
      REQUIRE(r.check.non_degenerate.passed);
      // Without crossings too: the repair untangles crossing triangles (remesh/untangle.h).
      REQUIRE(r.check.passed);
      REQUIRE(r.check.self_intersecting_pairs == 0);
      const std::string mesh_name = name;
      // The spheres cross each other by construction (paper Fig. 11): their crossings are inherited.
      if (mesh_name == "interpenetrating_spheres") REQUIRE(r.check.inherited_intersecting_pairs > 0);
    }
  }
}

TEST_CASE("Only crossings between input components that cross each other are the input's own", "[cvt][remesh]") {
  // Two spheres that cross (as in paper Fig. 11) and a third 0.05 from the first, which the "remesh"
  // (the input's own vertices, the third sphere's swollen by a tenth) pushes into the first: its
  // crossings are the remesh's, the first two spheres' the input's.
  const SurfaceMesh spheres = test::merge(test::icosphere(2), test::icosphere(2), {1, 0, 0});
  const SurfaceMesh three = test::merge(spheres, test::icosphere(2), {0, 2.05, 0});
  Samples samples;  // at the vertices (some coincide where the first two spheres cross)
  samples.positions = three.positions();
  samples.triangles.resize(three.vertex_count());
  samples.barycentric.resize(three.vertex_count());
  for (int t = 0; t < three.triangle_count(); ++t)
    for (int c = 0; c < 3; ++c) {
      samples.triangles[three.triangle(t)[c]] = t;
      samples.barycentric[three.triangle(t)[c]] = Vec3{c == 0 ? 1.0 : 0.0, c == 1 ? 1.0 : 0.0, c == 2 ? 1.0 : 0.0};
    }
  DualMesh dual;
  dual.positions = three.positions();
  dual.triangles = three.triangles();
  const Vec3 centre{0, 2.05, 0};
  for (int v = spheres.vertex_count(); v < three.vertex_count(); ++v)
    dual.positions[v] = centre + 1.1 * (dual.positions[v] - centre);
  const std::vector<int>& component = three.triangle_components();
  int own = 0, inherited = 0;
  for (const auto& [s, t] : find_self_intersections(dual.positions, dual.triangles)) {
    const int a = std::min(component[s], component[t]), b = std::max(component[s], component[t]);
    REQUIRE(a != b);
    ++(b == component[dual.triangles.size() - 1] ? own : inherited);
  }
  REQUIRE(own > 0);
  REQUIRE(inherited > 0);
  const InputCrossings input(three);
  REQUIRE(input.any());
  UntangleOptions none;
  none.passes = 0;
  DualMesh copy = dual;
  REQUIRE(untangle_crossings(three, samples, copy, input, none).crossings_before == own);
  REQUIRE(untangle_crossings(three, samples, copy, InputCrossings(), none).crossings_before == own + inherited);
  REQUIRE_FALSE(InputCrossings(test::merge(test::icosphere(2), test::icosphere(2), {5, 0, 0})).any());

  // A whole remesh: the two spheres, and a torus round the first whose inner equator runs 0.02 from
  // it, which the remesh's chords cut into at 150 vertices. The repair once passed over those
  // crossings as the input's (its spheres cross) and ended with them (exit 3 from the command line).
  const SurfaceMesh ringed = test::merge(test::merge(test::icosphere(3), test::icosphere(3), {0, 0, 1}),
                                         test::torus(1.32, 0.3, 96, 24), {0, 0, 0});
  const RemeshResult r = remesh_to(ringed, 150);  // as `lrvd remesh -n 150` does it
  const RemeshVerification check = verify_remesh(ringed, r.dual.positions, r.dual.triangles, 150);
  INFO(check.summary());
  REQUIRE(check.passed);
  REQUIRE(check.self_intersecting_pairs == 0);
  REQUIRE(check.inherited_intersecting_pairs > 0);
}

TEST_CASE("The kept state is untangled again with each longer reach and the fewest crossings kept: a folded sheet at 300", "[cvt][remesh]") {
  // Without repair rounds (or the other runs) the folded sheet's first CVT at 300 is kept with its
  // defects, topological ones among them; at the end it is fitted and untangled with a reach of half
  // an edge, which leaves crossings (measured: 60 -> 8), and then untangled again from its fitted
  // vertices with each of final_max_moves. A reach of 0.5 repeats the first untangling (as many
  // crossings: not kept), 0.55 leaves fewer (measured: 5) and is kept, and the last 0.5 must not
  // replace it.
  const SurfaceMesh input = make_stress_mesh("folded_sheet", 0.5);
  const SurfaceMesh mesh = for_samples(input, 300);
  RemeshOptions options;
  options.repair_rounds = 0;
  options.keep_to_sheets_retry = false;
  options.tip_caps_retry = false;
  options.reallocation_retry = false;
  auto run = [&](const std::vector<double>& reaches) {
    options.final_max_moves = reaches;
    return remesh_cvt(input, mesh, sample_uniform(mesh, 300, 3), options);
  };
  const RemeshResult once = run({});
  INFO(once.defects.describe());
  REQUIRE(once.untangle.crossings_after > 0);
  const RemeshResult again = run({0.5, 0.55, 0.5});
  INFO("crossings " << once.untangle.crossings_before << " -> " << once.untangle.crossings_after << ", then "
                    << again.untangle.crossings_after);
  CHECK(again.untangle.crossings_before == once.untangle.crossings_before);
  CHECK(again.untangle.crossings_after < once.untangle.crossings_after);
  CHECK(again.untangle.remaining.size() == static_cast<size_t>(again.untangle.crossings_after));
  // The dual kept is the one those crossings were counted on.
  CHECK(find_self_intersections(again.dual.positions, again.dual.triangles,
                                proper_triangles(again.dual.positions, again.dual.triangles)) == again.untangle.remaining);
  CHECK(again.untangled_from.positions.empty());
}

TEST_CASE("A run whose line search backtracks counts L-BFGS iterations, within the caps, not evaluations", "[cvt][remesh]") {
  // Elk 300's repair rounds backtrack often (about 2.7 diagrams per iteration), and some end on a
  // failed line search; such a round was once reported with its evaluations as iterations (105 and
  // 124 against a cap of 30, 525 in all).
  const SurfaceMesh elk = cgal_mesh("elk.off");
  RemeshOptions options;
  std::vector<std::string> lines;
  options.on_progress = [&](const std::string& line) { lines.push_back(line); };
  const RemeshResult r = remesh_cvt(elk, elk, sample_uniform(elk, 300, 1), options);
  REQUIRE(r.repair_rounds > 0);
  REQUIRE(r.total_iterations <= options.cvt.iterations + r.repair_rounds * options.repair_iterations +
                                    options.ease_iterations + 2 * options.polish_steps);
  REQUIRE(2 * r.total_iterations < r.diagram_evaluations);
  int rounds_seen = 0;
  for (const std::string& line : lines) {
    int round = 0, iterations = 0;
    if (std::sscanf(line.c_str(), "repair round %d: %d iterations", &round, &iterations) != 2) continue;
    ++rounds_seen;
    INFO(line);
    REQUIRE(iterations >= 1);
    REQUIRE(iterations <= options.repair_iterations);
  }
  REQUIRE(rounds_seen == r.repair_rounds);
}

TEST_CASE("Remeshing CGAL's models gives valid meshes of the requested size and quality", "[cvt][remesh]") {
  struct Case {
    const char* model;
    int n;
    double q_min, theta_min, hausdorff_pct;  // floors: the paper's LRVD figures or better
  };
  for (const Case& c : {Case{"elk.off", 516, 0.41, 16.7, 3.0}, Case{"elk.off", 2000, 0.52, 22.2, 1.5},
                        Case{"knot.off", 300, 0.41, 16.7, 3.5}, Case{"knot.off", 516, 0.41, 16.7, 3.0}, Case{"knot.off", 2000, 0.53, 30.0, 0.87},
                        Case{"ellipsoid.off", 300, 0.5, 25.0, 3.0}}) {
    const Remeshed r = remesh(cgal_mesh(c.model), c.n);
    INFO(c.model << " n=" << c.n << "\n" << r.check.summary() << r.quality.to_json().dump());
    REQUIRE(r.check.passed);
    REQUIRE(r.check.vertex_count.passed);
    REQUIRE(r.check.topology.passed);
    REQUIRE(r.check.self_intersecting_pairs == 0);
    REQUIRE(r.quality.q_min >= c.q_min);
    REQUIRE(r.quality.theta_min >= c.theta_min);
    REQUIRE(r.quality.hausdorff_pct <= c.hausdorff_pct);
  }
}

TEST_CASE("The CVT keeps every sample on its connected component", "[cvt]") {
  // CGAL's bones: 26 closed components, some a few hundredths of the others' area. An L-BFGS site
  // may cross the gap between two bones; its closest point is then taken on its own bone, or a
  // small bone could lose its last sample (and the diagram its cells there).
  const SurfaceMesh mesh = cgal_mesh("bones.off");
  REQUIRE(mesh.component_count() == 26);
  const Samples start = sample_by_component(mesh, 200, 1, mesh.minimum_vertex_counts());
  auto per_component = [&](const Samples& s) {
    std::vector<int> count(mesh.component_count(), 0);
    for (int t : s.triangles) ++count[mesh.triangle_components()[t]];
    return count;
  };
  const std::vector<int> before = per_component(start);
  for (int c : before) REQUIRE(c >= 4);
  for (CvtOptimizer optimizer : {CvtOptimizer::Lbfgs, CvtOptimizer::Lloyd}) {
    CvtOptions options;
    options.optimizer = optimizer;
    options.iterations = 40;
    const CvtResult r = optimize_cvt(mesh, start, options);
    REQUIRE(per_component(r.samples) == before);
    REQUIRE(r.energy < r.energy_history.front());
  }
}

TEST_CASE("Open meshes with holes keep every hole at low N", "[cvt][remesh]") {
  // CGAL's holes (six holes in a curved sheet) and pig (seven boundary loops, two of them 3 and 4
  // edges long): a hole inside one cell, or two holes met by one cell, closes it in the dual. The
  // repair finds those cells from the boundary loops they meet (the dual alone has no defect
  // there), and pinched vertices, which open meshes may have with every edge used once or twice.
  for (const char* model : {"holes.off", "pig.off"}) {
    const SurfaceMesh input = cgal_mesh(model);
    REQUIRE_FALSE(input.is_closed());
    const Remeshed r = remesh(input, 200);
    INFO(model << "\n" << r.check.summary());
    REQUIRE(r.result.repair_rounds > 0);
    REQUIRE(r.check.passed);
    REQUIRE(r.check.boundary_loops == static_cast<int>(input.boundary_loops().size()));
  }
}

TEST_CASE("A sample cornered at a sharp boundary corner gets a larger cell, not company: CGAL's negative at 500", "[cvt][remesh]") {
  // A disk of six triangles with a 38-degree corner: the CVT leaves a small cell in the corner with
  // one neighbour, a sample in no triangle. Raising the density there (48 rounds) only made the
  // pattern smaller; lowering it on that cell's own triangles lets the cell grow to meet two others.
  const SurfaceMesh input = cgal_mesh("negative.off");
  REQUIRE_FALSE(input.is_closed());
  // The first CVT's dual, before any repair: the cornered sample is found as such.
  const DualDefects defects = first_cvt(for_samples(input, 500), 500, 1).defects;
  REQUIRE(defects.cornered.size() == 1);
  REQUIRE(defects.topological == defects.cornered);
  const Remeshed r = remesh(input, 500);
  INFO(r.check.summary());
  REQUIRE(r.check.passed);
  REQUIRE(r.result.repair_rounds <= 3);
  REQUIRE(r.result.dual.positions.size() == 500);
}

TEST_CASE("The second run moves samples into the defect cells: CGAL's triceratops at 300", "[cvt][remesh]") {
  // Horns and a frill thinner than the cells: the first run's 24 rounds of raised density end with
  // pinched and unused vertices; the second run, which also moves samples of light cells into the
  // defect cells, ends valid.
  const SurfaceMesh input = cgal_mesh("triceratops.off");
  const Remeshed r = remesh(input, 300);
  INFO(r.check.summary());
  REQUIRE(r.result.kept_to_sheets);
  REQUIRE(r.check.passed);
  REQUIRE(r.result.dual.positions.size() == 300);
}

TEST_CASE("A cap on a sharp tip gets a larger cell in a third run: CGAL's triceratops at 200", "[cvt][remesh]") {
  // At 200 vertices the horn tips end as caps inside one ring cell (samples in no triangle) after
  // both runs of raised density: fewer than three cells fit round a tip sharper than a half-plane,
  // at any density. The third run lowers the density on such caps and ends valid.
  const SurfaceMesh input = cgal_mesh("triceratops.off");
  RemeshOptions two_runs;
  two_runs.tip_caps_retry = false;
  const RemeshResult before = remesh_to(input, 200, 1, two_runs);
  REQUIRE_FALSE(verify_remesh(input, before.dual.positions, before.dual.triangles, 200).passed);
  const Remeshed r = remesh(input, 200);
  INFO(r.check.summary());
  REQUIRE(r.result.tip_caps_lowered);
  REQUIRE(r.check.passed);
  REQUIRE(r.result.dual.positions.size() == 200);
}

TEST_CASE("A cell at a sharp tip that meets two cells sharing two arcs round it is a tip cap", "[cvt][remesh]") {
  // A closed cone 10 high on a unit disk (12 sides): its apex's angles sum to about 35°. A sample
  // near the apex, two lower down on either side, three further down, three on the base: the apex
  // cell meets only the two side cells, which share two arcs round it, so the dual has the triangle
  // of the three twice (Horse at 20000 has this at a tip whose angles sum to 175°).
  const SurfaceMesh cone = closed_cone();
  REQUIRE(cone.is_closed());
  std::vector<Vec3> points = {on_cone(9.5, 0), on_cone(8.5, 90), on_cone(8.5, 265), on_cone(5, 10), on_cone(5, 130), on_cone(5, 250)};
  for (double d : {60.0, 180.0, 300.0}) points.push_back({0.5 * std::cos(d * M_PI / 180), 0.5 * std::sin(d * M_PI / 180), 0});
  const Samples samples = locate_points(cone, points);
  const Diagram diagram = compute_lrvd(cone, samples);
  const DualMesh dual = compute_dual(diagram, cone, samples);
  const DualDefects defects = find_dual_defects(dual, diagram, cone, samples, true);
  // The apex sample is used, twice in the same triangle.
  REQUIRE(std::count(dual.triangles.begin(), dual.triangles.end(), Triangle{0, 1, 2}) +
              std::count(dual.triangles.begin(), dual.triangles.end(), Triangle{0, 2, 1}) ==
          2);
  CHECK(defects.topological == std::vector<int>{0, 1, 2});
  CHECK(defects.tip_caps == std::vector<int>{0});
  CHECK(defects.cornered.empty());
}

TEST_CASE("A ring cell round the narrowing part below a tip cap is named with the cap", "[cvt][remesh]") {
  // The closed cone of the test above: a sample near the apex, one lower down whose cell wraps
  // round the cone below the apex's (the cap meets only that one, a ring), three further down and
  // three on the base. The third run lowers the density on both, so the cap can grow over the ring
  // (a sphere stretched 100 times at 2000 vertices ended with such a pair at each tip).
  const SurfaceMesh cone = closed_cone();
  std::vector<Vec3> points = {on_cone(9.5, 0), on_cone(8, 180), on_cone(5, 10), on_cone(5, 130), on_cone(5, 250)};
  for (double d : {60.0, 180.0, 300.0}) points.push_back({0.5 * std::cos(d * M_PI / 180), 0.5 * std::sin(d * M_PI / 180), 0});
  const Samples samples = locate_points(cone, points);
  const Diagram diagram = compute_lrvd(cone, samples);
  const DualMesh dual = compute_dual(diagram, cone, samples);
  const DualDefects defects = find_dual_defects(dual, diagram, cone, samples, true);
  CHECK(defects.topological == std::vector<int>{0});
  CHECK(defects.tip_caps == std::vector<int>{0});
  CHECK(defects.tip_cap_rings == std::vector<int>{1});
  CHECK(std::find(defects.cell_topology.begin(), defects.cell_topology.end(), 1) != defects.cell_topology.end());
  CHECK_FALSE(defects.euler_ok);
}

TEST_CASE("A repair round that would raise the density everywhere stops the run: a torus thinner than its cells", "[cvt][remesh]") {
  // A torus of radii 1 and 0.001 at 100 vertices: cells about 0.02 across, the tube 0.006 round, so
  // every cell wraps it. A density raised on every triangle leaves the CVT as it is: the runs stop
  // at their first round instead of going on for 24 rounds each, and say so.
  const int around = 100, across = 6;
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      const double u = 2 * M_PI * i / around, v = 2 * M_PI * j / across, r = 1 + 0.001 * std::cos(v);
      positions.push_back({r * std::cos(u), r * std::sin(u), 0.001 * std::sin(v)});
    }
  auto at = [&](int i, int j) { return (i % around) * across + (j % across); };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  const SurfaceMesh torus(positions, triangles);
  REQUIRE(torus.euler_characteristic() == 0);
  const SurfaceMesh mesh = for_samples(torus, 100);
  const RemeshResult r = remesh_cvt(torus, mesh, sample_uniform(mesh, 100, 1));
  REQUIRE_FALSE(verify_remesh(torus, r.dual.positions, r.dual.triangles, 100).passed);
  REQUIRE(r.repair_saturated);
  REQUIRE(r.repair_rounds == 0);
  REQUIRE(r.dual.positions.size() == 100);
}

TEST_CASE("On an open sheet the fitting takes the boundary vertices out to the boundary and hardly past it", "[cvt][remesh][fit]") {
  // The unit square: the dual's boundary runs through the boundary cells' samples, inside the
  // square; the boundary's planes in the cells' quadrics take it out to the square's sides. Before
  // them the Hausdorff distance was 2.75 %, and the balancing's sideways steps, blind to the
  // distance past the side, put a vertex 0.032 (2.2 % of the diagonal) beyond it.
  const SurfaceMesh square = test::grid(30, 30);
  const RemeshResult r = remesh_to(square, 100);
  const RemeshVerification check = verify_remesh(square, r.dual.positions, r.dual.triangles, 100);
  INFO(check.summary());
  REQUIRE(check.passed);
  const double diagonal = std::sqrt(2.0);
  for (const Vec3& p : r.dual.positions) {
    CHECK(std::min({p.x, 1 - p.x, p.y, 1 - p.y}) > -0.005 * diagonal);  // measured: 0.0036 at most
    CHECK(p.z == Approx(0).margin(1e-12));
  }
  const QualityMetrics quality = quality_metrics(square, r.dual.positions, r.dual.triangles);
  CHECK(quality.hausdorff_pct < 1.0);  // measured: 0.26 %
  CHECK(quality.theta_min >= 30.0);
}

TEST_CASE("Fitting the vertices to their cells' planes lowers the distance and keeps the CVT's shape", "[cvt][remesh][fit]") {
  const SurfaceMesh input = cgal_mesh("elk.off");
  const RemeshResult cvt = unfitted(input, input, 516, 1);
  DualMesh fitted = cvt.dual;
  const FitResult fit = fit_to_surface(cvt.cvt.diagram, input, fitted);
  const QualityMetrics before = quality_metrics(input, cvt.dual.positions, cvt.dual.triangles);
  const QualityMetrics after = quality_metrics(input, fitted.positions, fitted.triangles);
  INFO(before.to_json().dump() << "\n" << after.to_json().dump());
  CHECK(fit.moved > 0);
  CHECK(fitted.triangles == cvt.dual.triangles);
  CHECK(after.q_min >= before.q_min);
  CHECK(after.theta_min >= std::min(30.0, before.theta_min));
  CHECK(after.hausdorff_pct < 0.6 * before.hausdorff_pct);  // measured: 2.39 % -> 1.22 %
  CHECK(after.rms_pct < 0.6 * before.rms_pct);
  CHECK(after.q_avg >= 0.96 * before.q_avg);  // measured 0.903 -> 0.874; balancing keeps 0.95 of each Q
  require_none_turned_over(cvt.dual, fitted);
  const RemeshVerification check = verify_remesh(input, fitted.positions, fitted.triangles, 516);
  INFO(check.summary());
  REQUIRE(check.passed);
}

TEST_CASE("Relaxing the worst triangles raises the worst Q and keeps the vertices on the surface", "[cvt][remesh][fit]") {
  // CGAL's knot at 1000, the CVT's dual without the fitting: the vertices of the worst triangles
  // move towards their neighbours, onto the surface; nothing turns over or crosses.
  const SurfaceMesh input = cgal_mesh("knot.off");
  const SurfaceMesh mesh = for_samples(input, 1000);
  const RemeshResult cvt = unfitted(input, mesh, 1000, 1);
  DualMesh relaxed = cvt.dual;
  const ClosestPointIndex index(mesh);
  RelaxOptions relax;
  relax.rounds = 5;
  const RelaxResult r = relax_worst_triangles(mesh, index, cvt.cvt.samples, relaxed, relax);
  const QualityMetrics before = shape_metrics(cvt.dual.positions, cvt.dual.triangles);
  const QualityMetrics after = shape_metrics(relaxed.positions, relaxed.triangles);
  INFO(before.q_min << " -> " << after.q_min << ", " << r.moved << " moved");
  CHECK(after.q_min > before.q_min + 0.05);  // measured: 0.688 -> 0.83
  CHECK(r.moved > 0);
  CHECK(r.moved < 1000 / 2);  // the worst triangles' vertices, not the whole mesh
  CHECK(r.crossings.empty());
  require_none_turned_over(cvt.dual, relaxed);
  const double diagonal = input.bounding_box().diagonal();
  for (int v = 0; v < 1000; ++v)
    if (relaxed.positions[v] != cvt.dual.positions[v]) REQUIRE(index.query(relaxed.positions[v]).distance < 1e-9 * diagonal);
  REQUIRE(verify_remesh(input, relaxed.positions, relaxed.triangles, 1000).passed);

  // The whole remesh with the relaxation: the same CVT, a higher worst triangle after the fitting.
  RemeshOptions shape;
  shape.relax.rounds = 5;
  const RemeshResult plain = remesh_cvt(input, mesh, sample_uniform(mesh, 1000, 1));
  const RemeshResult shaped = remesh_cvt(input, mesh, sample_uniform(mesh, 1000, 1), shape);
  CHECK(shaped.diagram_evaluations == plain.diagram_evaluations);
  CHECK(shaped.relax.moved == r.moved);
  const double q_plain = shape_metrics(plain.dual.positions, plain.dual.triangles).q_min;
  const double q_shaped = shape_metrics(shaped.dual.positions, shaped.dual.triangles).q_min;
  CHECK(q_shaped > q_plain + 0.05);  // measured: 0.688 -> 0.821
  REQUIRE(verify_remesh(input, shaped.dual.positions, shaped.dual.triangles, 1000).passed);
}

TEST_CASE("Relaxing the worst triangles leaves the vertices on an open sheet's boundary where they are", "[cvt][remesh][fit]") {
  const SurfaceMesh plane = test::grid(12, 12);
  const RemeshResult cvt = unfitted(plane, plane, 40, 3);
  DualMesh relaxed = cvt.dual;
  RelaxOptions relax;
  relax.rounds = 5;
  relax.worst_triangles = 1000;  // every triangle
  const RelaxResult r = relax_worst_triangles(plane, ClosestPointIndex(plane), cvt.cvt.samples, relaxed, relax);
  CHECK(r.moved > 0);
  std::map<std::pair<int, int>, int> edges;
  for (const Triangle& f : relaxed.triangles)
    for (int e = 0; e < 3; ++e) ++edges[{std::min(f[e], f[(e + 1) % 3]), std::max(f[e], f[(e + 1) % 3])}];
  int on_boundary = 0;
  for (const auto& [edge, count] : edges)
    if (count == 1)
      for (int v : {edge.first, edge.second}) {
        REQUIRE(relaxed.positions[v] == cvt.dual.positions[v]);
        ++on_boundary;
      }
  CHECK(on_boundary > 0);
  for (const Vec3& p : relaxed.positions) REQUIRE(std::abs(p.z) < 1e-12);
  require_none_turned_over(cvt.dual, relaxed);
  CHECK(shape_metrics(relaxed.positions, relaxed.triangles).q_min > shape_metrics(cvt.dual.positions, cvt.dual.triangles).q_min);
}

TEST_CASE("Relaxing the worst triangles puts back the corners of triangles that cross and did not: a folded sheet at 100", "[cvt][remesh][fit]") {
  // The folded sheet's first CVT at 100: its chords across the bend cut through those of the facing
  // wall (32 pairs). Some moves towards the neighbours make crossings of their own; their corners go
  // back (measured: 19 vertices), and only crossings the dual had before are left.
  const SurfaceMesh input = make_stress_mesh("folded_sheet", 0.5);
  const SurfaceMesh mesh = for_samples(input, 100);
  const FirstCvt first = first_cvt(mesh, 100, 1);
  const DualMesh dual = compute_dual(first.cvt.diagram, mesh, first.cvt.samples);
  const std::set<std::pair<int, int>> before(first.defects.crossing_pairs.begin(), first.defects.crossing_pairs.end());
  REQUIRE_FALSE(before.empty());
  const ClosestPointIndex index(mesh);
  RelaxOptions relax;
  relax.rounds = 5;
  DualMesh relaxed = dual;
  const RelaxResult r = relax_worst_triangles(mesh, index, first.cvt.samples, relaxed, relax);
  INFO(r.moved << " moved, " << r.reverted << " put back, crossings " << before.size() << " -> " << r.crossings.size());
  CHECK(r.reverted > 0);
  CHECK(r.moved > 0);
  const auto after = find_self_intersections(relaxed.positions, relaxed.triangles,
                                             proper_triangles(relaxed.positions, relaxed.triangles));
  CHECK(after == r.crossings);
  for (const auto& pair : after) REQUIRE(before.count(pair) == 1);
  require_none_turned_over(dual, relaxed);
  // Given the crossings (as the remesh passes the repair's), the same moves and put-backs.
  DualMesh given = dual;
  const RelaxResult g = relax_worst_triangles(mesh, index, first.cvt.samples, given, relax, &first.defects.crossing_pairs);
  CHECK(given.positions == relaxed.positions);
  CHECK(g.reverted == r.reverted);
  CHECK(g.crossings == r.crossings);
}

TEST_CASE("Remeshing renumbers a large mesh along a Morton curve and leaves a small one and the samples as they are", "[cvt][remesh]") {
  // A sphere of 20480 triangles (above kSpatialOrderMinTriangles), its triangles shuffled.
  SurfaceMesh mesh = test::shuffled(test::icosphere(5), 5);
  REQUIRE(mesh.triangle_count() >= kSpatialOrderMinTriangles);
  const SurfaceMesh before = mesh;
  Samples samples = sample_uniform(mesh, 100, 1);
  const Samples drawn = samples;
  order_for_remeshing(mesh, samples);
  REQUIRE(samples.positions == drawn.positions);
  REQUIRE(samples.barycentric == drawn.barycentric);
  int moved = 0;
  for (int i = 0; i < samples.size(); ++i) {
    moved += samples.triangles[i] != drawn.triangles[i];
    // The sample's point, from its new triangle and its barycentric coordinates, is where it was.
    const Triangle& tri = mesh.triangle(samples.triangles[i]);
    const Vec3& b = samples.barycentric[i];
    const Vec3 p = b.x * mesh.position(tri[0]) + b.y * mesh.position(tri[1]) + b.z * mesh.position(tri[2]);
    REQUIRE(distance(p, samples.positions[i]) < 1e-12);
  }
  CHECK(moved > 90);
  CHECK(mesh.triangles() != before.triangles());
  // A remesh of it is valid (the reference is the mesh as read).
  const RemeshResult r = remesh_cvt(before, mesh, samples);
  REQUIRE(verify_remesh(before, r.dual.positions, r.dual.triangles, 100).passed);

  SurfaceMesh small = test::icosphere(3);
  Samples few = sample_uniform(small, 50, 1);
  const std::vector<Triangle> small_before = small.triangles();
  const Samples few_before = few;
  order_for_remeshing(small, few);
  CHECK(small.triangles() == small_before);
  CHECK(few.triangles == few_before.triangles);
}

TEST_CASE("Fitting keeps the vertices of a flat surface on it", "[cvt][remesh][fit]") {
  // On a plane an inner cell's quadric constrains the normal direction only, and the samples are
  // on the plane already: the quadric step leaves those vertices where they are. A cell on the
  // square's boundary adds the boundary's planes, which pull its vertex towards the side, in the
  // plane. Balancing may move vertices along the plane, never off it.
  const SurfaceMesh plane = test::grid(12, 12);
  const RemeshResult cvt = unfitted(plane, plane, 40, 3);
  DualMesh quadric_only = cvt.dual;
  FitOptions no_balance;
  no_balance.balance = false;
  fit_to_surface(cvt.cvt.diagram, plane, quadric_only, no_balance);
  auto to_side = [](const Vec3& p) { return std::min({p.x, 1 - p.x, p.y, 1 - p.y}); };
  int moved = 0;
  for (size_t v = 0; v < quadric_only.positions.size(); ++v) {
    const Vec3 &before = cvt.dual.positions[v], &after = quadric_only.positions[v];
    REQUIRE(std::abs(after.z) < 1e-12);
    if (distance(after, before) < 1e-12) continue;
    ++moved;
    REQUIRE(to_side(after) < to_side(before));
    REQUIRE(to_side(after) > -1e-12);
  }
  CHECK(moved > 0);
  DualMesh balanced = cvt.dual;
  fit_to_surface(cvt.cvt.diagram, plane, balanced);
  for (const Vec3& p : balanced.positions) REQUIRE(std::abs(p.z) < 1e-12);
  const QualityMetrics before = quality_metrics(plane, cvt.dual.positions, cvt.dual.triangles);
  const QualityMetrics after = quality_metrics(plane, balanced.positions, balanced.triangles);
  CHECK(after.hausdorff_pct <= before.hausdorff_pct);
  CHECK(after.q_min >= before.q_min);
}

TEST_CASE("Balancing the two-sided distance beats the quadric fit on a sphere and turns nothing over", "[cvt][remesh][fit]") {
  // With every vertex on the planes of its cell, the chords of a sphere stay inside it by about
  // 2/3 of their sagitta; the balanced offset leaves about half of it on each side.
  const SurfaceMesh sphere = test::icosphere(4);
  const RemeshResult cvt = unfitted(sphere, sphere, 200, 1);
  DualMesh quadric_only = cvt.dual, balanced = cvt.dual;
  FitOptions no_balance;
  no_balance.balance = false;
  fit_to_surface(cvt.cvt.diagram, sphere, quadric_only, no_balance);
  const FitResult fit = fit_to_surface(cvt.cvt.diagram, sphere, balanced);
  const QualityMetrics before = quality_metrics(sphere, quadric_only.positions, quadric_only.triangles);
  const QualityMetrics after = quality_metrics(sphere, balanced.positions, balanced.triangles);
  INFO(before.to_json().dump() << "\n" << after.to_json().dump());
  CHECK(fit.offsets.max_after < fit.offsets.max_before);
  CHECK(after.hausdorff_pct < 0.8 * before.hausdorff_pct);  // measured: 0.300 % -> 0.208 %
  CHECK(after.rms_pct < 0.8 * before.rms_pct);             // measured: 0.140 % -> 0.104 %
  CHECK(after.q_min >= before.q_min);
  CHECK(after.theta_min >= std::min(30.0, before.theta_min));
  CHECK(balanced.triangles == cvt.dual.triangles);
  require_none_turned_over(cvt.dual, balanced);
  const RemeshVerification check = verify_remesh(sphere, balanced.positions, balanced.triangles, 200);
  INFO(check.summary());
  REQUIRE(check.passed);
}

TEST_CASE("Balancing with the power 4 instead of 16 is valid and nearer the mean: a sphere at 200", "[cvt][remesh][fit]") {
  // Σ|d|^p with p = 4 (the loop for any p) and the default 16 (unrolled): both lower the sampled
  // two-sided maximum from the quadric fit's; the larger p is closer to the maximum, the smaller
  // closer to least squares (measured: maximum 0.0098 vs 0.0072, RMS 0.079 % vs 0.104 %).
  const SurfaceMesh sphere = test::icosphere(4);
  const RemeshResult cvt = unfitted(sphere, sphere, 200, 1);
  DualMesh fourth = cvt.dual, sixteenth = cvt.dual;
  FitOptions p4;
  p4.offsets.power = 4;
  const FitResult f4 = fit_to_surface(cvt.cvt.diagram, sphere, fourth, p4);
  const FitResult f16 = fit_to_surface(cvt.cvt.diagram, sphere, sixteenth);
  const QualityMetrics before = quality_metrics(sphere, cvt.dual.positions, cvt.dual.triangles);
  const QualityMetrics q4 = quality_metrics(sphere, fourth.positions, fourth.triangles);
  const QualityMetrics q16 = quality_metrics(sphere, sixteenth.positions, sixteenth.triangles);
  INFO("max " << f4.offsets.max_before << " -> " << f4.offsets.max_after << " (p 4), " << f16.offsets.max_after
              << " (p 16)\n" << q4.to_json().dump() << "\n" << q16.to_json().dump());
  CHECK(f4.offsets.max_before == f16.offsets.max_before);  // the same quadric step
  CHECK(f4.offsets.max_after < f4.offsets.max_before);
  // Well apart: an objective of p = 16 with the steepest descent of p = 4 lands at 0.0074.
  CHECK(f16.offsets.max_after < 0.85 * f4.offsets.max_after);
  CHECK(q4.rms_pct < q16.rms_pct);
  CHECK(fourth.positions != sixteenth.positions);
  for (const auto& [fitted, q] : {std::pair{&fourth, &q4}, std::pair{&sixteenth, &q16}}) {
    CHECK(q->q_min >= before.q_min);
    CHECK(q->theta_min >= std::min(30.0, before.theta_min));
    require_none_turned_over(cvt.dual, *fitted);
    const RemeshVerification check = verify_remesh(sphere, fitted->positions, fitted->triangles, 200);
    INFO(check.summary());
    REQUIRE(check.passed);
  }
}

TEST_CASE("Focus rounds move the vertices at the largest distance with their ring, above the worst triangle", "[cvt][remesh][fit]") {
  // Elk 1000: the worst points are antler tines whose nearest vertices cannot reach them while every
  // triangle keeps 95 % of its Q; the focus rounds let those few vertices spend Q down to the worst
  // triangle's (within a Qavg budget), and move them with their one-ring where a triangle at that
  // floor stops them alone.
  const SurfaceMesh input = cgal_mesh("elk.off");
  RemeshOptions options;
  options.fit = false;
  options.untangle = false;
  const RemeshResult cvt = remesh_cvt(input, input, sample_uniform(input, 1000, 1), options);
  auto fitted = [&](int focus_rounds, double ring_share) {
    DualMesh dual = cvt.dual;
    FitOptions fit;
    fit.offsets.focus_rounds = focus_rounds;
    fit.offsets.ring_share = ring_share;
    fit_to_surface(cvt.cvt.diagram, input, dual, fit);
    return dual;
  };
  const DualMesh uniform = fitted(0, 0), alone = fitted(4, 0), grouped = fitted(4, 1);
  const QualityMetrics u = quality_metrics(input, uniform.positions, uniform.triangles);
  const QualityMetrics a = quality_metrics(input, alone.positions, alone.triangles);
  const QualityMetrics g = quality_metrics(input, grouped.positions, grouped.triangles);
  INFO(u.to_json().dump() << "\n" << a.to_json().dump() << "\n" << g.to_json().dump());
  CHECK(a.hausdorff_pct < u.hausdorff_pct);         // measured: 0.913 % -> 0.861 %
  CHECK(g.hausdorff_pct < 0.95 * a.hausdorff_pct);  // measured: 0.861 % -> 0.791 %
  CHECK(g.q_min >= u.q_min);
  CHECK(g.theta_min >= std::min(30.0, u.theta_min));
  CHECK(g.q_avg >= u.q_avg - 0.008);  // the budget is 0.005 (measured 0.893 -> 0.890)
  CHECK(grouped.triangles == cvt.dual.triangles);
  require_none_turned_over(cvt.dual, grouped);
  const RemeshVerification check = verify_remesh(input, grouped.positions, grouped.triangles, 1000);
  INFO(check.summary());
  REQUIRE(check.passed);
}

TEST_CASE("Two cells that meet across a neck narrower than them are where to act: two squares joined by a neck", "[cvt][remesh]") {
  // Two unit squares joined by a neck 0.1 wide and 0.1 long, cells about 0.3 and 0.18 wide: a cell
  // from each side meets the other in the neck along an arc from boundary to boundary through no
  // triple point, so the dual has no edge there and falls apart in two, with every sample used.
  // Without these two cells to act on the rounds stopped at once, and the output had two
  // components at 20 to 80 vertices, seeds 1 to 3.
  const SurfaceMesh sheet = test::neck_sheet(40, 0.1, 0.1);
  for (int n : {20, 60}) {
    const FirstCvt first = first_cvt(for_samples(sheet, n), n, 1);
    const DualDefects& defects = first.defects;
    INFO("n = " << n << ": " << defects.describe());
    REQUIRE(defects.topological.empty());
    REQUIRE_FALSE(defects.euler_ok);
    REQUIRE(defects.cell_topology.size() == 2);
    const double x0 = first.cvt.samples.positions[defects.cell_topology[0]].x,
                 x1 = first.cvt.samples.positions[defects.cell_topology[1]].x;
    CHECK(std::min(x0, x1) < 1.05);  // one on each side of the neck's middle
    CHECK(std::max(x0, x1) > 1.05);
    const Remeshed r = remesh(sheet, n);
    INFO(r.check.summary());
    REQUIRE(r.result.repair_rounds > 0);
    REQUIRE(r.check.passed);
    REQUIRE(r.check.components == 1);
  }
}

TEST_CASE("Cells that meet across narrow strips are repaired on CGAL's ALSTOM_TEST4 and on pig.stl at 200", "[cvt][remesh]") {
  // ALSTOM_TEST4: six open parts of a CAD model with strips narrower than the cells; pig.stl: after
  // --repair, 17 components cut apart at non-manifold edges. Both ended with the wrong topology when
  // such strips were not acted on (pig.stl: 18 components, one of its parts in two).
  for (const auto& [model, repair] : {std::pair{"ALSTOM_TEST4.off", false}, std::pair{"pig.stl", true}}) {
    const SurfaceMesh input = read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/" + model, ReadOptions{repair}).mesh;
    REQUIRE_FALSE(input.is_closed());
    const RemeshResult r = remesh_to(input, 200);
    const RemeshVerification check = verify_remesh(input, r.dual.positions, r.dual.triangles, 200);
    INFO(model << "\n" << check.summary());
    REQUIRE(check.passed);
    REQUIRE(check.components == input.component_count());
  }
}

TEST_CASE("A cell with a handle inside it is where to act: a sheet with a small handle on top", "[cvt][remesh]") {
  // The unit square with a square tube 0.025 wide and about 0.1 long arching over it (genus 1):
  // at 40 and 60 vertices (seed 2) the first CVT has the whole handle inside one cell. That cell
  // has one boundary loop, so it looked like a disk, and the rounds stopped with nothing to act on
  // (the output lost the handle); its V - E + F is -1. At 40 to 80 vertices, seeds 1 to 3, 12
  // of the 15 remeshes are valid with this rule and 6 without it.
  const SurfaceMesh sheet = test::sheet_with_handle(40, 18, 20, 3);
  REQUIRE(sheet.euler_characteristic() == -1);
  for (int n : {40, 60}) {
    const FirstCvt first = first_cvt(for_samples(sheet, n), n, 2);
    const DualDefects& defects = first.defects;
    INFO("n = " << n << ": " << defects.describe());
    REQUIRE(defects.topological.empty());
    REQUIRE_FALSE(defects.euler_ok);
    REQUIRE(defects.cell_topology.size() == 1);
    const Vec3 site = first.cvt.samples.positions[defects.cell_topology[0]];
    CHECK(std::hypot(site.x - 0.5, site.y - 0.5) < 0.25);  // the handle spans x 0.45-0.55, y 0.5-0.525
    const Remeshed r = remesh(sheet, n, 2);
    INFO(r.check.summary());
    REQUIRE(r.check.passed);
    REQUIRE(r.check.genus == 1);
  }
}

TEST_CASE("Components left at the fewest samples their topology needs get two more when one fails: CGAL's bones at 200", "[cvt][remesh]") {
  // 26 bones, 16 of them at 4 or 5 samples by their area: four cells on an elongated bone form a
  // chain of rings whose dual is no tetrahedron, and the second run's moves do not mend all of
  // them. With two more samples on each such bone (32 moved from the largest ones) the runs end
  // valid.
  const SurfaceMesh bones = cgal_mesh("bones.off");
  const Samples start = sample_by_component(bones, 200, 1, bones.minimum_vertex_counts());
  RemeshOptions without;
  without.reallocation_retry = false;
  const RemeshResult failed = remesh_cvt(bones, bones, start, without);
  REQUIRE_FALSE(failed.defects.empty());
  REQUIRE(failed.samples_reallocated == 0);
  REQUIRE(failed.reallocation_tried == 0);
  REQUIRE(failed.runs >= 2);  // the first run and the one with samples kept to their sheets, at least
  const RemeshResult r = remesh_cvt(bones, bones, start);
  INFO(r.defects.describe());
  REQUIRE(r.samples_reallocated == 32);
  REQUIRE(r.reallocation_tried == 32);
  REQUIRE(r.runs > failed.runs);  // the runs again from the moved samples
  REQUIRE(r.defects.empty());
  const RemeshVerification check = verify_remesh(bones, r.dual.positions, r.dual.triangles, 200);
  INFO(check.summary());
  REQUIRE(check.passed);
}

TEST_CASE("The curvature density: 1 on a flat sheet, mean 1 by area, higher at a flat ellipsoid's rim, smooth over a cell", "[cvt]") {
  const SurfaceMesh flat = test::grid(10, 10);
  for (double rho : curvature_density(flat, 60)) REQUIRE(rho == Approx(1.0).epsilon(1e-14));

  const SurfaceMesh ellipsoid = make_stress_mesh("flat_ellipsoid", 1.0);  // semi-axes 1, 0.5, 0.05
  for (int n : {50, 200, 1000}) {
    const std::vector<double> rho = curvature_density(ellipsoid, n);
    double mass = 0, rim = 0, rim_area = 0, middle = 0, middle_area = 0;
    double steepest = 1;  // the largest ratio of the densities of two edge neighbours
    for (int t = 0; t < ellipsoid.triangle_count(); ++t) {
      const double a = ellipsoid.triangle_area(t);
      mass += rho[t] * a;
      Vec3 c{0, 0, 0};
      for (int v : ellipsoid.triangle(t)) c = c + ellipsoid.position(v) / 3.0;
      const double r = std::hypot(c.x, c.y / 0.5);  // 1 on the rim, 0 in the middle
      if (r > 0.97) rim += rho[t] * a, rim_area += a;
      if (r < 0.5) middle += rho[t] * a, middle_area += a;
      for (int e = 0; e < 3; ++e) steepest = std::max(steepest, rho[t] / rho[ellipsoid.neighbor(t, e)]);
    }
    INFO("n = " << n << ", triangles " << ellipsoid.triangle_count() << ", rim " << rim / rim_area << ", middle "
                << middle / middle_area << ", steepest " << steepest);
    CHECK(mass == Approx(ellipsoid.area()).epsilon(1e-12));
    CHECK(rim / rim_area > 3 * (middle / middle_area));
    // A single pass of averaging left neighbours 3.9-5.1 times apart here; passes as many as the
    // triangles per sample leave 1.2-2.0.
    CHECK(steepest < 2.5);
  }
}

TEST_CASE("A remesh with the curvature density is valid and puts more vertices at a flat ellipsoid's rim", "[cvt][remesh]") {
  const SurfaceMesh input = make_stress_mesh("flat_ellipsoid", 1.0);
  const int n = 200;
  auto near_rim = [](const DualMesh& dual) {
    int count = 0;
    for (const Vec3& p : dual.positions) count += std::hypot(p.x, p.y / 0.5) > 0.9;
    return count;
  };
  const SurfaceMesh mesh = for_samples(input, n);
  RemeshOptions curvature;
  curvature.cvt.density = CvtDensity::Curvature;
  const RemeshResult adaptive = remesh_cvt(input, mesh, sample_uniform(mesh, n, 1), curvature);
  const RemeshResult uniform = remesh_cvt(input, mesh, sample_uniform(mesh, n, 1));
  const RemeshVerification check = verify_remesh(input, adaptive.dual.positions, adaptive.dual.triangles, n);
  INFO(check.summary() << "\nnear the rim: " << near_rim(adaptive.dual) << " against " << near_rim(uniform.dual));
  REQUIRE(check.passed);
  // The band r > 0.9 holds 46 of the uniform remesh's 200 vertices and 65 of the adaptive one's.
  CHECK(near_rim(adaptive.dual) > 1.25 * near_rim(uniform.dual));
}
