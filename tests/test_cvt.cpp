// The CVT (remesh/cvt.h): the energy gradient, both optimisers, their stopping rules, a start
// diagram reused, samples kept to their sheets and components, and the curvature density.
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
#include "io/mesh_io.h"
#include "mesh/self_intersections.h"
#include "mesh/stress.h"
#include "metrics/quality.h"
#include "remesh/remesh_pipeline.h"
#include "remesh_helpers.h"
#include "test_meshes.h"
#include "verification/remesh_check.h"
#include "voronoi/lrvd.h"

using namespace lrvd;
using test::cgal_mesh;
using test::for_samples;

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
