// Samples: reproducible uniform sampling by area, location of points by closest point, .xyz files.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "common/error.h"
#include "io/mesh_io.h"
#include "mesh/closest_point.h"
#include "mesh/refine.h"
#include "mesh/surface_mesh.h"
#include "samples/samples.h"
#include "test_meshes.h"

using namespace lrvd;

namespace {

std::string temp_path(const std::string& name) { return std::string(LRVD_BINARY_DIR) + "/test_" + name; }

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

bool positions_equal(const Samples& a, const Samples& b) { return a.positions == b.positions && a.triangles == b.triangles; }

}  // namespace

TEST_CASE("Uniform sampling is reproducible from its seed and lies on the surface") {
  const SurfaceMesh mesh = test::icosphere(2);
  const Samples a = sample_uniform(mesh, 500, 7), b = sample_uniform(mesh, 500, 7), c = sample_uniform(mesh, 500, 8);
  REQUIRE(a.size() == 500);
  REQUIRE(a.positions == b.positions);
  REQUIRE(a.triangles == b.triangles);
  REQUIRE(a.positions != c.positions);
  for (int i = 0; i < a.size(); ++i) {
    const Triangle& t = mesh.triangle(a.triangles[i]);
    const Vec3 w = a.barycentric[i];
    REQUIRE(w.x >= 0);
    REQUIRE(w.y >= 0);
    REQUIRE(w.z >= 0);
    REQUIRE(w.x + w.y + w.z == Approx(1.0));
    const Vec3 q = w.x * mesh.position(t[0]) + w.y * mesh.position(t[1]) + w.z * mesh.position(t[2]);
    REQUIRE(distance(q, a.positions[i]) < 1e-15);
  }
  // The first values of seed 1 are fixed on every machine: a changed generator changes them.
  const Samples fixed = sample_uniform(test::grid(1, 1), 2, 1);
  const Samples again = sample_uniform(test::grid(1, 1), 2, 1);
  REQUIRE(fixed.positions == again.positions);
  Random r(1);
  const uint64_t first = r.next();
  REQUIRE(first == Random(1).next());
  REQUIRE(first != Random(2).next());
}

TEST_CASE("Uniform sampling is uniform by area (chi-square with a fixed seed)") {
  // Unit square split in a 4x4 grid of cells; every cell has area 1/16.
  const SurfaceMesh mesh = test::grid(8, 8);
  const int n = 32000, bins = 16;
  const Samples s = sample_uniform(mesh, n, 12345);
  std::vector<int> count(bins, 0);
  for (const Vec3& p : s.positions) {
    const int i = std::min(3, int(p.x * 4)), j = std::min(3, int(p.y * 4));
    ++count[j * 4 + i];
  }
  double chi2 = 0;
  const double expected = double(n) / bins;
  for (int c : count) chi2 += (c - expected) * (c - expected) / expected;
  // 15 degrees of freedom: P(chi2 > 37.7) = 0.001.
  REQUIRE(chi2 < 37.7);
  // Triangles of unequal area: a thin and a fat triangle must receive samples by area.
  const SurfaceMesh two({{0, 0, 0}, {1, 0, 0}, {1, 0.1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
  const Samples t = sample_uniform(two, 20000, 3);
  int in_thin = 0;
  for (int tri : t.triangles) in_thin += tri == 0;
  const double share = two.triangle_area(0) / two.area();
  REQUIRE(std::abs(in_thin / 20000.0 - share) < 4 * std::sqrt(share * (1 - share) / 20000));
}

TEST_CASE("Every connected component receives a sample") {
  const SurfaceMesh mesh = test::merge(test::icosphere(2), test::merge(test::grid(1, 1), test::octahedron(), {0, 0, 3}),
                                       {5, 0, 0});
  REQUIRE(mesh.component_count() == 3);
  const Samples s = sample_uniform(mesh, 3, 99);
  std::vector<int> hit(3, 0);
  for (int t : s.triangles) ++hit[mesh.triangle_components()[t]];
  REQUIRE(hit == std::vector<int>{1, 1, 1});
  REQUIRE_THROWS_WITH(sample_uniform(mesh, 2, 1), Catch::Contains("3 connected components"));
  REQUIRE_THROWS_WITH(sample_uniform(mesh, 0, 1), Catch::Contains("at least 1"));
}

TEST_CASE("Sampling by component gives each its share by area, and at least its minimum") {
  // An icosphere (area about 12.1), a unit square (1) and an octahedron (3.46).
  const SurfaceMesh mesh = test::merge(test::icosphere(2), test::merge(test::grid(4, 4), test::octahedron(), {0, 0, 3}),
                                       {5, 0, 0});
  REQUIRE(mesh.component_count() == 3);
  auto counts = [&](const Samples& s) {
    std::vector<int> hit(3, 0);
    for (int t : s.triangles) ++hit[mesh.triangle_components()[t]];
    return hit;
  };
  std::vector<double> area(3, 0.0);
  for (int t = 0; t < mesh.triangle_count(); ++t) area[mesh.triangle_components()[t]] += mesh.triangle_area(t);
  const double total = area[0] + area[1] + area[2];
  const Samples s = sample_by_component(mesh, 100, 7, {4, 3, 4});
  REQUIRE(s.size() == 100);
  const std::vector<int> hit = counts(s);
  for (int c = 0; c < 3; ++c) {
    INFO("component " << c << ": " << hit[c] << " samples, share " << 100 * area[c] / total);
    REQUIRE(std::abs(hit[c] - 100 * area[c] / total) < 1.0);
  }
  for (int i = 0; i < s.size(); ++i) {
    const Triangle& tri = mesh.triangle(s.triangles[i]);
    const Vec3 p = s.barycentric[i].x * mesh.position(tri[0]) + s.barycentric[i].y * mesh.position(tri[1]) +
                   s.barycentric[i].z * mesh.position(tri[2]);
    REQUIRE(distance(p, s.positions[i]) < 1e-12);
  }
  // Minima above the shares are met first; the rest follow the areas.
  REQUIRE(counts(sample_by_component(mesh, 20, 7, {4, 7, 4})) [1] == 7);
  REQUIRE(counts(sample_by_component(mesh, 12, 7, {4, 4, 4})) == std::vector<int>{4, 4, 4});
  REQUIRE(positions_equal(sample_by_component(mesh, 50, 3, {4, 3, 4}), sample_by_component(mesh, 50, 3, {4, 3, 4})));
  REQUIRE_THROWS_WITH(sample_by_component(mesh, 11, 1, {4, 4, 4}), Catch::Contains("need 12"));
}

TEST_CASE("Closest point on a triangle covers vertex, edge and face regions") {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  auto check = [&](Vec3 p, Vec3 expected, double dist) {
    const ClosestPoint q = closest_point_on_triangle(p, a, b, c);
    REQUIRE(distance(q.point, expected) < 1e-15);
    REQUIRE(q.distance == Approx(dist));
    const Vec3 w = q.barycentric;
    REQUIRE(distance(w.x * a + w.y * b + w.z * c, expected) < 1e-15);
  };
  check({0.2, 0.2, 1}, {0.2, 0.2, 0}, 1);
  check({-1, -1, 0}, a, std::sqrt(2.0));
  check({2, -1, 0}, b, std::sqrt(2.0));
  check({-1, 3, 0}, c, std::sqrt(5.0));
  check({0.5, -2, 0}, {0.5, 0, 0}, 2);
  check({-3, 0.5, 0}, {0, 0.5, 0}, 3);
  check({1, 1, 0}, {0.5, 0.5, 0}, std::sqrt(0.5));
  // Degenerate triangles (coincident or collinear corners) give a finite answer on their edges.
  for (const auto& [u, v, w] : {std::array<Vec3, 3>{a, a, b}, std::array<Vec3, 3>{a, b, b}, std::array<Vec3, 3>{a, a, a},
                                std::array<Vec3, 3>{a, b, Vec3{2, 0, 0}}}) {
    const ClosestPoint q = closest_point_on_triangle({0.5, 1, 0}, u, v, w);
    REQUIRE(std::isfinite(q.distance));
    REQUIRE(q.distance >= 1.0);
    REQUIRE(q.distance <= distance(Vec3{0.5, 1, 0}, a));
  }
}

TEST_CASE("Points are located on the mesh by closest point") {
  const SurfaceMesh mesh = test::icosphere(3);
  const Samples truth = sample_uniform(mesh, 200, 4);
  std::vector<Vec3> pushed;
  for (const Vec3& p : truth.positions) pushed.push_back(p * (1 + 1e-4));  // slightly off the surface
  const Samples located = locate_points(mesh, pushed);
  REQUIRE(located.size() == 200);
  ClosestPointIndex index(mesh);
  for (int i = 0; i < 200; ++i) {
    REQUIRE(distance(located.positions[i], truth.positions[i]) < 2e-4);
    // Brute force agrees with the BVH on the distance.
    double best = INFINITY;
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      const Triangle& f = mesh.triangle(t);
      best = std::min(best, closest_point_on_triangle(pushed[i], mesh.position(f[0]), mesh.position(f[1]),
                                                      mesh.position(f[2])).distance);
    }
    REQUIRE(index.query(pushed[i]).distance == best);
  }
}

TEST_CASE("Points located on edges of a refined mesh get barycentric coordinates that are not negative") {
  // Centroids and edge midpoints of CGAL's ellipsoid on its refinement for 300 samples: many lie on
  // the new edges, where the closest point's 1 - v - w can round below zero, and the verification
  // would then put the sample outside its own triangle.
  const SurfaceMesh input = read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/ellipsoid.off").mesh;
  const SurfaceMesh mesh = refine_long_edges(input, suggested_refinement_length(input, 300));
  std::vector<Vec3> points;
  for (int t = 0; t < input.triangle_count(); ++t) {
    const Triangle& tri = input.triangle(t);
    const Vec3 &a = input.position(tri[0]), &b = input.position(tri[1]), &c = input.position(tri[2]);
    points.push_back((a + b + c) / 3.0);
    if (tri[0] < tri[1]) points.push_back(0.5 * (a + b));
  }
  const ClosestPointIndex index(mesh);
  int rounded_below = 0;
  for (const Vec3& p : points) {
    const Vec3 b = index.query(p).barycentric;
    rounded_below += b.x < 0 || b.y < 0 || b.z < 0;
  }
  CHECK(rounded_below > 0);  // the case is met
  const Samples samples = locate_points(mesh, points);
  for (int i = 0; i < samples.size(); ++i) {
    INFO("point " << i);
    const Vec3& b = samples.barycentric[i];
    REQUIRE((b.x >= 0 && b.y >= 0 && b.z >= 0));
    REQUIRE(b.x + b.y + b.z > 0.5);
  }
}

TEST_CASE("Closest-point queries answer alike at any scale of the mesh") {
  // The BVH is in floats: at 1e20 its squared distances overflowed (no triangle was found) and at
  // 1e-25 they vanished. It sees the mesh scaled by a power of two, so the triangle found is the
  // same and the point and distance scale with the mesh exactly.
  const SurfaceMesh mesh = test::icosphere(3);
  const ClosestPointIndex index(mesh);
  const Samples truth = sample_uniform(mesh, 100, 6);
  for (int k : {-90, -40, 40, 70}) {
    const double s = std::ldexp(1.0, k);
    std::vector<Vec3> scaled = mesh.positions();
    for (Vec3& p : scaled) p = s * p;
    const ClosestPointIndex big(SurfaceMesh(scaled, mesh.triangles()));
    for (int i = 0; i < truth.size(); ++i)
      for (double off : {1.0, 1.2, 0.9}) {
        const ClosestPoint a = index.query(off * truth.positions[i]);
        const ClosestPoint b = big.query(s * off * truth.positions[i]);
        INFO("2^" << k << " sample " << i);
        REQUIRE(b.triangle == a.triangle);
        REQUIRE(b.point == s * a.point);
        REQUIRE(b.distance == s * a.distance);
      }
  }
}

TEST_CASE("Closest-point queries on a model far from the origin find the nearest triangle") {
  // A sphere of radius 1 at 1e8: in floats its triangles' boxes would be a few values apart, so
  // the index sees it relative to its centre. Every answer is the brute-force nearest.
  const SurfaceMesh sphere = test::icosphere(3);
  std::vector<Vec3> far = sphere.positions();
  for (Vec3& p : far) p = p + Vec3{1e8, -1e8, 3e8};
  const SurfaceMesh mesh(far, sphere.triangles());
  const ClosestPointIndex index(mesh);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int k = 0; k < 500; ++k) {
    const int t = static_cast<int>(rng() % mesh.triangle_count());
    const Triangle& tri = mesh.triangle(t);
    const Vec3 on = (mesh.position(tri[0]) + mesh.position(tri[1]) + mesh.position(tri[2])) / 3.0;
    const Vec3 p = on + 0.2 * Vec3{unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5};
    // The brute force measures in a frame moved by the shift itself: the model's points and the
    // query are within a factor two of it, so the move is exact (Sterbenz), and the distances are
    // those of the input's doubles with the precision of the sphere's size, not of 3e8's.
    const Vec3 shift{1e8, -1e8, 3e8};
    double best = std::numeric_limits<double>::infinity();
    for (int u = 0; u < mesh.triangle_count(); ++u) {
      const Triangle& v = mesh.triangle(u);
      best = std::min(best, closest_point_on_triangle(p - shift, mesh.position(v[0]) - shift, mesh.position(v[1]) - shift,
                                                      mesh.position(v[2]) - shift).distance);
    }
    INFO("query " << k);
    const ClosestPoint answer = index.query(p);
    REQUIRE(answer.distance == Approx(best).margin(1e-12));
    REQUIRE(distance(answer.point, p) == Approx(best).margin(1e-7));  // the point is moved back: 3e8's rounding
  }
}

TEST_CASE("Closest-point queries on a tiny model far from the origin measure at the model's precision") {
  // A sphere 1e-6 across at 1000, where doubles step by 1.1e-13: a closest point computed at those
  // coordinates was a tenth of a percent of the model off, a query point on the surface could
  // miss every box, and a remesh stopped with "sample ... is not located on a triangle". The
  // index moves the model by an exact shift, so the answers are those of the sphere at the origin.
  const SurfaceMesh sphere = test::icosphere(2);
  std::vector<Vec3> small = sphere.positions(), far = sphere.positions();
  for (Vec3& p : small) p = 1e-6 * p;
  const Vec3 shift{1000, 1000, -1000};
  for (size_t i = 0; i < far.size(); ++i) far[i] = small[i] + shift;
  const SurfaceMesh near_mesh(small, sphere.triangles()), far_mesh(far, sphere.triangles());
  const ClosestPointIndex near_index(near_mesh), far_index(far_mesh);
  const Samples on_surface = sample_uniform(far_mesh, 200, 3);
  for (int i = 0; i < on_surface.size(); ++i) {
    const ClosestPoint answer = far_index.query(on_surface.positions[i], on_surface.triangles[i]);
    REQUIRE(answer.triangle >= 0);
    REQUIRE(answer.distance < 1e-12);  // on the surface up to the sample's own rounding at 1000
  }
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> offset(-1e-6, 1e-6);
  for (int k = 0; k < 200; ++k) {
    const Vec3 q{offset(rng), offset(rng), offset(rng)};
    // The far mesh's vertices are the small ones plus the shift, rounded to 1.1e-13: the same
    // sphere up to that, so the distances agree to a few of those units.
    REQUIRE(far_index.query(q + shift).distance == Approx(near_index.query(q).distance).margin(1e-12));
  }
}

TEST_CASE("A hinted closest-point query gives the unhinted answer") {
  // Points near and far from the surface, each with a hint nearby (its own triangle, a moved
  // point's old triangle) and one far away: the triangle and the point must not change, ties
  // between triangles at an edge or a vertex included.
  const SurfaceMesh mesh = test::icosphere(3);
  const ClosestPointIndex index(mesh);
  const Samples truth = sample_uniform(mesh, 300, 5);
  for (int i = 0; i < truth.size(); ++i)
    for (double scale : {1.0, 1.01, 0.97, 1.5}) {
      const Vec3 p = truth.positions[i] * scale;
      const Vec3 corner = mesh.position(mesh.triangle(truth.triangles[i])[0]) * scale;
      for (const Vec3& q : {p, corner}) {
        const ClosestPoint plain = index.query(q);
        for (int hint : {truth.triangles[i], truth.triangles[(i + 1) % truth.size()], mesh.triangle_count() - 1}) {
          const ClosestPoint hinted = index.query(q, hint);
          REQUIRE(hinted.triangle == plain.triangle);
          REQUIRE(hinted.point == plain.point);
        }
      }
    }
}

TEST_CASE("A closest-point query within one component answers from its triangles only") {
  // Two spheres 0.1 apart: points just outside the first one's surface, on the side facing the
  // second, and points inside the second. Within a component, the answer is the brute-force
  // closest triangle of that component, whichever the other's distance and the hint.
  const SurfaceMesh mesh = test::merge(test::icosphere(2), test::icosphere(2), {2.1, 0, 0});
  REQUIRE(mesh.component_count() == 2);
  const std::vector<int>& component = mesh.triangle_components();
  const ClosestPointIndex index(mesh);
  int other_closer = 0;
  for (double x : {1.02, 1.04, 1.06, 1.08, 1.5, 2.0, 2.5}) {
    for (double y : {-0.3, 0.0, 0.2}) {
      const Vec3 q{x, y, 0.1};
      const ClosestPoint any = index.query(q);
      for (int c : {0, 1}) {
        double best = std::numeric_limits<double>::infinity();
        for (int t = 0; t < mesh.triangle_count(); ++t)
          if (component[t] == c) {
            const Triangle& tri = mesh.triangle(t);
            best = std::min(best, closest_point_on_triangle(q, mesh.position(tri[0]), mesh.position(tri[1]),
                                                            mesh.position(tri[2])).distance);
          }
        const int first_of_other = c == 0 ? mesh.triangle_count() - 1 : 0;  // a hint in the other component
        for (int hint : {-1, first_of_other}) {
          const ClosestPoint within = index.query_within(q, component.data(), c, hint);
          REQUIRE(within.triangle >= 0);
          REQUIRE(component[within.triangle] == c);
          REQUIRE(within.distance == best);
        }
        if (component[any.triangle] != c && best > any.distance) ++other_closer;
      }
    }
  }
  REQUIRE(other_closer > 10);  // the filter mattered for many of the queries
}

TEST_CASE("Bad sample points are refused with a clear message") {
  const SurfaceMesh mesh = test::icosphere(2);
  REQUIRE_THROWS_WITH(locate_points(mesh, {{0, 0, 1.5}}), Catch::Contains("point 0") && Catch::Contains("1%"));
  REQUIRE_THROWS_WITH(locate_points(mesh, {{0, 0, 1}, {NAN, 0, 1}}), Catch::Contains("point 1 has a non-finite"));
  REQUIRE_THROWS_WITH(locate_points(mesh, {{0, 0, 1}, {1, 0, 0}, {0, 0, 1}}), Catch::Contains("points 0 and 2 coincide"));
  REQUIRE_THROWS_WITH(locate_points(mesh, {}), Catch::Contains("no sample points"));
  const SurfaceMesh two = test::merge(mesh, test::octahedron(), {4, 0, 0});
  REQUIRE_THROWS_WITH(locate_points(two, {{0, 0, 1}}), Catch::Contains("component 1") && Catch::Contains("no sample"));
}

TEST_CASE("Point files are read with optional weights and malformed lines are named") {
  const std::string good = temp_path("good.xyz"), weighted = temp_path("weighted.xyz"), bad = temp_path("bad.xyz"),
                    mixed = temp_path("mixed.xyz");
  write_text(good, "# comment\n0 0 1\n\n1 0 0\n");
  write_text(weighted, "0 0 1 0.5\n1 0 0 0.25\n");
  write_text(bad, "0 0 1\n1 zero 0\n");
  write_text(mixed, "0 0 1\n1 0 0 2\n");
  const PointFile g = read_xyz(good);
  REQUIRE(g.points.size() == 2);
  REQUIRE(g.weights.empty());
  const PointFile w = read_xyz(weighted);
  REQUIRE(w.weights == std::vector<double>{0.5, 0.25});
  REQUIRE_THROWS_WITH(read_xyz(bad), Catch::Contains(":2: 'zero' is not a number"));
  REQUIRE_THROWS_WITH(read_xyz(mixed), Catch::Contains(":2: every line must have the same number"));
  REQUIRE_THROWS_WITH(read_xyz(temp_path("missing.xyz")), Catch::Contains("cannot read"));
  const std::string out = temp_path("roundtrip.xyz");
  write_xyz(out, {{0.1, 1e-300, -3}}, {2.5});
  const PointFile r = read_xyz(out);
  REQUIRE(r.points[0] == Vec3{0.1, 1e-300, -3});
  REQUIRE(r.weights[0] == 2.5);
}
