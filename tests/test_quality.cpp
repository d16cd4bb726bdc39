// Remesh quality metrics (paper §5): Q(t), angles, share of angles below 30°, two-sided Hausdorff
// and RMS distance as % of the reference's bounding-box diagonal.
#include <catch2/catch.hpp>

#include <cmath>

#include <tbb/task_arena.h>

#include "common/error.h"
#include "metrics/quality.h"
#include "test_meshes.h"

using namespace lrvd;

namespace {

const double kSqrt3 = std::sqrt(3.0);
const double kDegrees = 180 / std::acos(-1.0);

QualityMetrics one_triangle(const Vec3& a, const Vec3& b, const Vec3& c) { return shape_metrics({a, b, c}, {{0, 1, 2}}); }

std::vector<Vec3> shifted(const std::vector<Vec3>& positions, const Vec3& offset) {
  std::vector<Vec3> out;
  for (const Vec3& p : positions) out.push_back(p + offset);
  return out;
}

DistanceOptions few_samples(int n) {
  DistanceOptions options;
  options.samples_per_surface = n;
  return options;
}

}  // namespace

TEST_CASE("An equilateral triangle has Q = 1 and three 60 degree angles") {
  const QualityMetrics m = one_triangle({0, 0, 0}, {2, 0, 0}, {1, kSqrt3, 0});
  REQUIRE(m.q_min == Approx(1.0).epsilon(1e-12));
  REQUIRE(m.q_avg == Approx(1.0).epsilon(1e-12));
  REQUIRE(m.theta_min == Approx(60.0).epsilon(1e-12));
  REQUIRE(m.theta_max == Approx(60.0).epsilon(1e-12));
  REQUIRE(m.pct_triangles_below_30 == 0);
  REQUIRE(m.pct_angles_below_30 == 0);
  REQUIRE(m.triangles == 1);
  REQUIRE(m.vertices == 3);
}

TEST_CASE("A right isoceles triangle has the Q computed by hand") {
  // Legs 1: |t| = 1/2, p = (2 + √2)/2, h = √2, so Q = 6/√3 · (1/2) / ((2 + √2)/2 · √2) = √3 (√2 - 1).
  const QualityMetrics m = one_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  REQUIRE(m.q_min == Approx(kSqrt3 * (std::sqrt(2.0) - 1)).epsilon(1e-12));
  REQUIRE(m.q_min == Approx(0.717438935).epsilon(1e-8));
  REQUIRE(m.theta_min == Approx(45.0).epsilon(1e-12));
  REQUIRE(m.theta_max == Approx(90.0).epsilon(1e-12));
  REQUIRE(m.pct_angles_below_30 == 0);
}

TEST_CASE("A sliver triangle has two angles below 30 degrees and a small Q") {
  // Base 1, apex 0.1 above its midpoint: base angles atan(0.2) = 11.31°, apex 157.38°.
  const QualityMetrics m = one_triangle({0, 0, 0}, {1, 0, 0}, {0.5, 0.1, 0});
  const double base = std::atan(0.2) * kDegrees;
  REQUIRE(m.theta_min == Approx(base).epsilon(1e-12));
  REQUIRE(m.theta_max == Approx(180 - 2 * base).epsilon(1e-12));
  REQUIRE(m.pct_triangles_below_30 == 100);
  REQUIRE(m.pct_angles_below_30 == Approx(200.0 / 3));
  // |t| = 0.05, p = (1 + 2·√0.26)/2, h = 1.
  REQUIRE(m.q_min == Approx(6 / kSqrt3 * 0.05 / ((1 + 2 * std::sqrt(0.26)) / 2)).epsilon(1e-12));
  REQUIRE(m.q_min < 0.2);
}

TEST_CASE("Shares below 30 degrees on a hand-made two-triangle mesh") {
  // An equilateral triangle and a sliver below its base: 1 of 2 triangles, 2 of 6 angles.
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0.5, kSqrt3 / 2, 0}, {0.5, -0.1, 0}};
  const QualityMetrics m = shape_metrics(p, {{0, 1, 2}, {1, 0, 3}});
  REQUIRE(m.triangles == 2);
  REQUIRE(m.vertices == 4);
  REQUIRE(m.pct_triangles_below_30 == Approx(50.0));
  REQUIRE(m.pct_angles_below_30 == Approx(100.0 / 3));
  const double sliver_q = 6 / kSqrt3 * 0.05 / ((1 + 2 * std::sqrt(0.26)) / 2);
  REQUIRE(m.q_min == Approx(sliver_q).epsilon(1e-12));
  REQUIRE(m.q_avg == Approx((1 + sliver_q) / 2).epsilon(1e-12));
  REQUIRE(m.theta_min == Approx(std::atan(0.2) * kDegrees).epsilon(1e-12));
  const nlohmann::json j = m.to_json();
  for (const char* key : {"Qmin", "Qavg", "theta_min", "theta_max", "pct_triangles_below_30", "pct_angles_below_30",
                          "hausdorff_pct", "rms_pct", "triangles", "vertices"})
    REQUIRE(j.contains(key));
  REQUIRE(j["pct_triangles_below_30"].get<double>() == Approx(50.0));
}

TEST_CASE("A triangle naming a missing vertex is an input error") {
  REQUIRE_THROWS_AS(shape_metrics({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 3}}), InputError);
  REQUIRE_THROWS_AS(quality_metrics(test::octahedron(), test::octahedron().positions(), {}), InputError);
}

TEST_CASE("Zero-area triangles in a remesh leave the distances finite") {
  // Vertex 25 duplicates vertex 12 (the centre of the square): triangle (12, 25, 0) has two
  // coincident corners and (0, 12, 24) three collinear ones; neither adds surface.
  const SurfaceMesh square = test::grid(4, 4);
  std::vector<Vec3> p = square.positions();
  std::vector<Triangle> t = square.triangles();
  p.push_back(p[12]);
  t.push_back({12, 25, 0});
  t.push_back({0, 12, 24});
  const QualityMetrics m = quality_metrics(square, p, t, few_samples(20000));
  REQUIRE(m.hausdorff_pct < 1e-12);
  REQUIRE(m.rms_pct < 1e-12);
  REQUIRE(m.q_min == 0);
  REQUIRE(m.theta_max == Approx(180));
  REQUIRE_THROWS_AS(quality_metrics(square, p, {{12, 25, 0}}), InputError);
}

TEST_CASE("The distance of a mesh to itself is zero") {
  const SurfaceMesh mesh = test::icosphere(2);
  const QualityMetrics m = quality_metrics(mesh, mesh.positions(), mesh.triangles(), few_samples(20000));
  REQUIRE(m.hausdorff_pct < 1e-12);
  REQUIRE(m.rms_pct < 1e-12);
  REQUIRE(m.triangles == mesh.triangle_count());
}

TEST_CASE("A flat square shifted by d along its normal is at Hausdorff and RMS distance d") {
  const SurfaceMesh square = test::grid(4, 4);
  const double d = 0.01;
  const QualityMetrics m =
      quality_metrics(square, shifted(square.positions(), {0, 0, d}), square.triangles(), few_samples(20000));
  const double expected = 100 * d / std::sqrt(2.0);  // the unit square's diagonal is √2
  REQUIRE(m.hausdorff_pct == Approx(expected).epsilon(1e-9));
  REQUIRE(m.rms_pct == Approx(expected).epsilon(1e-9));
}

TEST_CASE("The Hausdorff distance is two-sided") {
  // The left half of the square is at distance 0 from the square, but the square's right edge is
  // 0.5 from the half: only the reference-to-remesh side sees it.
  const SurfaceMesh square = test::grid(4, 4);
  std::vector<Vec3> half = square.positions();
  for (Vec3& p : half) p.x *= 0.5;
  const QualityMetrics m = quality_metrics(square, half, square.triangles(), few_samples(20000));
  REQUIRE(m.hausdorff_pct == Approx(100 * 0.5 / std::sqrt(2.0)).epsilon(1e-9));
  REQUIRE(m.rms_pct > 0);
  REQUIRE(m.rms_pct < m.hausdorff_pct);
}

TEST_CASE("A coarse icosphere is at a small positive Hausdorff distance from a finer one") {
  const SurfaceMesh fine = test::icosphere(4);
  const SurfaceMesh coarse = test::icosphere(1), medium = test::icosphere(2);
  const QualityMetrics m1 = quality_metrics(fine, coarse.positions(), coarse.triangles(), few_samples(50000));
  const QualityMetrics m2 = quality_metrics(fine, medium.positions(), medium.triangles(), few_samples(50000));
  // Level 1 has edges of about 0.62 rad: its faces sag about 1 - cos(0.36) ≈ 0.064 below the
  // sphere, about 2% of the diagonal 2√3; level 2 about a quarter of that.
  REQUIRE(m1.hausdorff_pct > 0.5);
  REQUIRE(m1.hausdorff_pct < 3);
  REQUIRE(m2.hausdorff_pct > 0);
  REQUIRE(m2.hausdorff_pct < m1.hausdorff_pct / 2);
  REQUIRE(m2.rms_pct > 0);
  REQUIRE(m2.rms_pct < m2.hausdorff_pct);
  REQUIRE(m1.q_min > 0.8);  // icosphere triangles are nearly equilateral
}

TEST_CASE("Quality metrics are the same on every run and thread count") {
  const SurfaceMesh fine = test::icosphere(4), coarse = test::icosphere(2);
  auto run = [&] { return quality_metrics(fine, coarse.positions(), coarse.triangles(), few_samples(30000)); };
  const QualityMetrics a = run(), b = run();
  QualityMetrics c;
  tbb::task_arena single(1);
  single.execute([&] { c = run(); });
  for (const QualityMetrics* m : {&b, static_cast<const QualityMetrics*>(&c)}) {
    REQUIRE(m->hausdorff_pct == a.hausdorff_pct);
    REQUIRE(m->rms_pct == a.rms_pct);
    REQUIRE(m->q_min == a.q_min);
    REQUIRE(m->q_avg == a.q_avg);
  }
  // A different seed draws other points: the RMS moves a little.
  DistanceOptions other = few_samples(30000);
  other.seed += 1;
  REQUIRE(quality_metrics(fine, coarse.positions(), coarse.triangles(), other).rms_pct != a.rms_pct);
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
