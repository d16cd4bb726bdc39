// SurfaceMesh adjacency, components, boundary loops, Euler characteristic and edge refinement.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "common/error.h"
#include "mesh/curvature.h"
#include "mesh/refine.h"
#include "mesh/spatial_order.h"
#include "mesh/stress.h"
#include "mesh/surface_mesh.h"
#include "test_meshes.h"

using namespace lrvd;

namespace {

// Neighbours' distance in the triangle array, on average over all edges.
double mean_gap(const SurfaceMesh& m) {
  double sum = 0;
  for (int t = 0; t < m.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) sum += std::abs(m.neighbor(t, e) - t);
  return sum / (3.0 * m.triangle_count());
}

}  // namespace

TEST_CASE("Octahedron adjacency is symmetric and closed") {
  const SurfaceMesh mesh = test::octahedron();
  REQUIRE(mesh.vertex_count() == 6);
  REQUIRE(mesh.triangle_count() == 8);
  REQUIRE(mesh.edge_count() == 12);
  REQUIRE(mesh.is_closed());
  REQUIRE(mesh.component_count() == 1);
  REQUIRE(mesh.euler_characteristic() == 2);
  for (int t = 0; t < mesh.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int n = mesh.neighbor(t, e);
      REQUIRE(n >= 0);
      const int f = mesh.neighbor_edge(t, e);
      REQUIRE(mesh.neighbor(n, f) == t);
      // The shared edge is traversed in opposite directions.
      REQUIRE(mesh.triangle(n)[f] == mesh.triangle(t)[(e + 1) % 3]);
      REQUIRE(mesh.triangle(n)[(f + 1) % 3] == mesh.triangle(t)[e]);
    }
  for (int v = 0; v < 6; ++v) {
    REQUIRE(mesh.vertex_triangle_count(v) == 4);
    REQUIRE(mesh.vertex_neighbors(v).size() == 4);
  }
  REQUIRE(mesh.area() == Approx(4 * std::sqrt(3.0)));
  REQUIRE(mesh.bounding_box().diagonal() == Approx(2 * std::sqrt(3.0)));
}

TEST_CASE("A grid sheet has one boundary loop in triangle order") {
  const SurfaceMesh mesh = test::grid(4, 3);
  REQUIRE_FALSE(mesh.is_closed());
  REQUIRE(mesh.boundary_loops().size() == 1);
  const auto& loop = mesh.boundary_loops()[0];
  REQUIRE(loop.size() == 2 * (4 + 3));
  REQUIRE(mesh.euler_characteristic() == 1);
  // Consecutive loop vertices form a boundary edge (u -> v) of some triangle.
  for (size_t k = 0; k < loop.size(); ++k) {
    const int u = loop[k], v = loop[(k + 1) % loop.size()];
    bool found = false;
    for (const int* t = mesh.vertex_triangles_begin(u); t != mesh.vertex_triangles_end(u); ++t)
      for (int e = 0; e < 3; ++e)
        if (mesh.triangle(*t)[e] == u && mesh.triangle(*t)[(e + 1) % 3] == v && mesh.neighbor(*t, e) < 0)
          found = true;
    REQUIRE(found);
  }
}

TEST_CASE("Components and their Euler characteristics are counted per component") {
  const SurfaceMesh mesh = test::merge(test::octahedron(), test::grid(2, 2), {5, 0, 0});
  REQUIRE(mesh.component_count() == 2);
  const auto chi = mesh.component_euler_characteristics();
  REQUIRE(chi.size() == 2);
  REQUIRE(chi[0] == 2);
  REQUIRE(chi[1] == 1);
  REQUIRE(mesh.euler_characteristic() == 3);
  REQUIRE(mesh.boundary_loops().size() == 1);
}

TEST_CASE("The constructor refuses what the algorithms cannot handle") {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0}};
  REQUIRE_THROWS_WITH(SurfaceMesh({}, {}), Catch::Contains("empty"));
  REQUIRE_THROWS_WITH(SurfaceMesh(p, {{0, 1, 7}}), Catch::Contains("index 7 out of range"));
  REQUIRE_THROWS_WITH(SurfaceMesh({{0, 0, 0}, {1, 0, 0}, {NAN, 1, 0}}, {{0, 1, 2}}),
                      Catch::Contains("vertex 2 has a non-finite"));
  REQUIRE_THROWS_WITH(SurfaceMesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}}),
                      Catch::Contains("triangle 0 (0, 1, 2) has zero area"));
  REQUIRE_THROWS_WITH(SurfaceMesh({p[0], p[1], p[2]}, {{0, 1, 2}, {1, 2, 0}}), Catch::Contains("duplicates"));
  REQUIRE_THROWS_WITH(SurfaceMesh({p[0], p[1], p[2], p[3], {0, -1, 0.5}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}),
                      Catch::Contains("edge (0, 1) has 3 or more"));
  REQUIRE_THROWS_WITH(SurfaceMesh({p[0], p[1], p[2], p[3]}, {{0, 1, 2}, {0, 1, 3}}),
                      Catch::Contains("inconsistent orientation") && !Catch::Contains("Möbius"));
  {
    // A Möbius strip of 12 quads: no orientation of it agrees on every edge, which the message says.
    std::vector<Vec3> strip;
    std::vector<Triangle> t;
    const int n = 12;
    for (int i = 0; i < n; ++i)
      for (const double w : {0.3, -0.3}) {
        const double u = 2 * M_PI * i / n, r = 1 + w * std::cos(u / 2);
        strip.push_back({r * std::cos(u), r * std::sin(u), w * std::sin(u / 2)});
      }
    for (int i = 0; i < n; ++i) {
      // Quad (top i, bottom i, bottom i + 1, top i + 1); past the last one the rails swap.
      const int a = 2 * i, b = 2 * i + 1, c = i + 1 < n ? 2 * i + 3 : 0, d = i + 1 < n ? 2 * i + 2 : 1;
      t.push_back({a, b, c});
      t.push_back({a, c, d});
    }
    REQUIRE_THROWS_WITH(SurfaceMesh(strip, t), Catch::Contains("inconsistent orientation") &&
                                                   Catch::Contains("one-sided, like a Möbius strip"));
  }
  REQUIRE_THROWS_WITH(SurfaceMesh(p, {{0, 1, 2}}), Catch::Contains("not used by any triangle"));
  // Two triangles touching at vertex 0 only.
  const std::vector<Vec3> bow = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  REQUIRE_THROWS_WITH(SurfaceMesh(bow, {{0, 1, 2}, {0, 3, 4}}), Catch::Contains("vertex 0 joins 2 separate fans"));
}

TEST_CASE("Angle deficits: 2π/3 at each corner of an octahedron and 2π times the Euler characteristic in all") {
  const SurfaceMesh octa = test::octahedron();
  const std::vector<double> d = angle_deficits(octa);
  for (double x : d) CHECK(x == Approx(2 * M_PI - 4 * M_PI / 3));  // four equilateral triangles
  // Gauss-Bonnet, closed and open: the boundary's turns count on the open sheet and sphere cap.
  auto total = [](const SurfaceMesh& m) {
    double sum = 0;
    for (double x : angle_deficits(m)) sum += x;
    return sum;
  };
  CHECK(total(test::icosphere(2)) == Approx(2 * M_PI * 2));
  const SurfaceMesh sheet = test::grid(4, 3);
  CHECK(total(sheet) == Approx(2 * M_PI * sheet.euler_characteristic()));
  const std::vector<double> g = angle_deficits(sheet);
  CHECK(g[0] == Approx(M_PI / 2));           // a corner turns by a right angle
  CHECK(g[1] == Approx(0).margin(1e-12));    // along a side it goes straight
  CHECK(g[6] == Approx(0).margin(1e-12));    // inside, the sheet is flat
}

TEST_CASE("The suggested refinement gives about four triangles a sample") {
  // docs/guide/command-line.md promises it for --refine auto: a mesh with fewer than two triangles
  // a sample is split to about four (splitting to length L leaves triangles of about L^2 / 6.5, not
  // equilateral ones).
  const std::pair<SurfaceMesh, int> cases[] = {{test::octahedron(), 100},
                                               {test::icosphere(1), 500},
                                               {test::grid(4, 3), 1000},
                                               {make_stress_mesh("thin_tube", 1.0), 20000}};
  for (const auto& [mesh, n] : cases) {
    INFO(mesh.triangle_count() << " triangles, " << n << " samples");
    const double length = suggested_refinement_length(mesh, n);
    REQUIRE(length > 0);
    const SurfaceMesh fine = refine_long_edges(mesh, length);
    // The estimate the CLI's size limit reads: with its margin, never below the count.
    const double expected = expected_refined_triangle_count(mesh, length);
    CHECK(kRefinedTriangleMargin * expected >= fine.triangle_count());
    CHECK(expected <= 1.5 * fine.triangle_count());
    REQUIRE(fine.triangle_count() >= 3 * n);
    REQUIRE(fine.triangle_count() <= 6 * n);
    REQUIRE(suggested_refinement_length(fine, n) == 0);  // two or more a sample: left alone
  }
}

TEST_CASE("Refinement stops at its triangle limit on a needle instead of splitting without end") {
  // A tetrahedron one long and 1e-6 wide: its long sides split into pieces as thin as the needle,
  // so the count grows with the length over the width, which the area-based estimate cannot see.
  const SurfaceMesh needle({{0, 0, 0}, {1e-6, 0, 0}, {0, 1e-6, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}});
  const double length = suggested_refinement_length(needle, 4);
  REQUIRE(length > 0);
  CHECK(expected_refined_triangle_count(needle, length) < 100);
  try {
    (void)refine_long_edges(needle, length, nullptr, RefineOrder::Input, 20000);
    FAIL("the refinement passed its limit");
  } catch (const RefinementLimitError& e) {
    CHECK_THAT(e.what(), Catch::Contains("more than 20000 triangles") && Catch::Contains("far longer than they are wide"));
  }
  // Within its limit the same call refines: the limit is the count, not a guess.
  const SurfaceMesh fine = refine_long_edges(needle, 0.01, nullptr, RefineOrder::Input, 20000);
  CHECK(fine.max_edge_length() <= 0.01);
  CHECK(fine.triangle_count() <= 20000);
  CHECK_THROWS_AS(refine_long_edges(needle, 0.01, nullptr, RefineOrder::Input, 3), std::invalid_argument);
}

TEST_CASE("Refinement bounds every edge and keeps the surface") {
  const SurfaceMesh mesh = test::octahedron();
  for (double length : {1.0, 0.3, 0.11}) {
    const SurfaceMesh fine = refine_long_edges(mesh, length);
    REQUIRE(fine.max_edge_length() <= length);
    REQUIRE(fine.area() == Approx(mesh.area()).epsilon(1e-12));
    REQUIRE(fine.is_closed());
    REQUIRE(fine.euler_characteristic() == 2);
    REQUIRE(fine.triangle_count() > mesh.triangle_count());
    // Every new vertex lies on the original surface: on one of the octahedron's faces |x|+|y|+|z| = 1.
    for (const Vec3& q : fine.positions())
      REQUIRE(std::abs(q.x) + std::abs(q.y) + std::abs(q.z) == Approx(1.0).epsilon(1e-14));
  }
  // The refinement hands its adjacency to the mesh instead of having it rebuilt and re-checked:
  // the same as the checking constructor finds, closed and open.
  for (const SurfaceMesh& fine : {refine_long_edges(mesh, 0.11), refine_long_edges(test::grid(3, 2), 0.1)}) {
    const SurfaceMesh checked(fine.positions(), fine.triangles());
    REQUIRE(fine.edge_count() == checked.edge_count());
    REQUIRE(fine.boundary_loops() == checked.boundary_loops());
    REQUIRE(fine.component_count() == checked.component_count());
    REQUIRE(fine.triangle_components() == checked.triangle_components());
    for (int t = 0; t < fine.triangle_count(); ++t)
      for (int e = 0; e < 3; ++e) REQUIRE(fine.neighbor(t, e) == checked.neighbor(t, e));
    for (int v = 0; v < fine.vertex_count(); ++v) REQUIRE(fine.vertex_neighbors(v) == checked.vertex_neighbors(v));
    // The vertex-to-vertex lists: exactly the ends of the edges at v, in increasing order.
    std::vector<std::vector<int>> expected(fine.vertex_count());
    for (const Triangle& tri : fine.triangles())
      for (int e = 0; e < 3; ++e) {
        expected[tri[e]].push_back(tri[(e + 1) % 3]);
        expected[tri[(e + 1) % 3]].push_back(tri[e]);
      }
    for (int v = 0; v < fine.vertex_count(); ++v) {
      std::sort(expected[v].begin(), expected[v].end());
      expected[v].erase(std::unique(expected[v].begin(), expected[v].end()), expected[v].end());
      REQUIRE(fine.vertex_neighbors(v) == expected[v]);
    }
  }
  // Each input triangle's pieces are consecutive, in the input's order (the octahedron's faces are
  // its octants), and the input's vertices keep their indices.
  {
    const SurfaceMesh fine = refine_long_edges(mesh, 0.11);
    auto octant = [](const Vec3& c) { return (c.x > 0 ? 4 : 0) + (c.y > 0 ? 2 : 0) + (c.z > 0 ? 1 : 0); };
    auto centroid = [](const SurfaceMesh& m, int t) {
      return (m.position(m.triangle(t)[0]) + m.position(m.triangle(t)[1]) + m.position(m.triangle(t)[2])) / 3.0;
    };
    std::vector<int> face_of_octant(8, -1);
    for (int t = 0; t < mesh.triangle_count(); ++t) face_of_octant[octant(centroid(mesh, t))] = t;
    int previous = 0;
    for (int t = 0; t < fine.triangle_count(); ++t) {
      const int face = face_of_octant[octant(centroid(fine, t))];
      REQUIRE(face >= previous);
      previous = face;
    }
    for (int v = 0; v < mesh.vertex_count(); ++v) REQUIRE(fine.position(v) == mesh.position(v));
  }
  // An open sheet keeps its boundary length and single loop.
  const SurfaceMesh sheet = refine_long_edges(test::grid(2, 2), 0.2);
  REQUIRE(sheet.max_edge_length() <= 0.2);
  REQUIRE(sheet.boundary_loops().size() == 1);
  REQUIRE(sheet.area() == Approx(1.0).epsilon(1e-12));
  REQUIRE(sheet.euler_characteristic() == 1);
  REQUIRE_THROWS_AS(refine_long_edges(mesh, 0.0), InputError);
}

TEST_CASE("A refinement whose rounded midpoints make a zero-area triangle says so, not just which triangle") {
  // At 3e14 a double steps by 1/16: a sphere of radius 20 there is fine as given, but edges split
  // down to 0.3 are a few steps long and some rounded midpoints fall on a line through two corners.
  const SurfaceMesh sphere = test::icosphere(3);
  std::vector<Vec3> far = sphere.positions();
  for (Vec3& p : far) p = p * 20.0 + Vec3{3e14, 3e14, 3e14};
  const SurfaceMesh mesh(far, sphere.triangles());
  REQUIRE_THROWS_WITH(refine_long_edges(mesh, 0.3),
                      Catch::Contains("splitting edges longer than 0.3 made a zero-area triangle (refined mesh:") &&
                          Catch::Contains("move the model nearer the origin"));
  std::vector<double> lengths(mesh.vertex_count(), 0.3);
  REQUIRE_THROWS_WITH(refine_to_length_field(mesh, lengths),
                      Catch::Contains("edges longer than the length field (down to 0.3) made a zero-area triangle"));
  // The same sphere at the origin refines without complaint.
  std::vector<Vec3> near = sphere.positions();
  for (Vec3& p : near) p = p * 20.0;
  REQUIRE(refine_long_edges(SurfaceMesh(near, sphere.triangles()), 0.3).max_edge_length() <= 0.3);
}

TEST_CASE("Refinement carries a field that is linear over each input triangle to the new vertices") {
  // f = a·x + b is linear everywhere, so the mean at each split must equal f at the new vertex.
  const SurfaceMesh mesh = test::octahedron();
  const Vec3 a{0.3, -1.7, 2.2};
  auto f = [&](const Vec3& p) { return dot(a, p) + 0.5; };
  std::vector<double> values;
  for (const Vec3& p : mesh.positions()) values.push_back(f(p));
  const SurfaceMesh fine = refine_long_edges(mesh, 0.11, &values);
  REQUIRE(values.size() == static_cast<size_t>(fine.vertex_count()));
  REQUIRE(fine.vertex_count() > 10 * mesh.vertex_count());
  for (int v = 0; v < fine.vertex_count(); ++v) REQUIRE(values[v] == Approx(f(fine.position(v))).margin(1e-12));
  std::vector<double> wrong(mesh.vertex_count() - 1, 0.0);
  REQUIRE_THROWS(refine_long_edges(mesh, 0.11, &wrong));
}

TEST_CASE("Refinement to a length field splits each edge to the smaller length at its ends") {
  // A positive field linear over the octahedron, from 0.05 to about 0.25: the field is carried to
  // the new vertices, every edge ends up no longer than the field at either end, and the coarse
  // parts keep fewer triangles than splitting everywhere to the smallest length.
  const SurfaceMesh mesh = test::octahedron();
  auto f = [](const Vec3& p) { return 0.15 + 0.1 * p.x; };
  std::vector<double> lengths;
  for (const Vec3& p : mesh.positions()) lengths.push_back(f(p));
  const SurfaceMesh fine = refine_to_length_field(mesh, lengths);
  REQUIRE(lengths.size() == static_cast<size_t>(fine.vertex_count()));
  for (int v = 0; v < fine.vertex_count(); ++v) REQUIRE(lengths[v] == Approx(f(fine.position(v))).margin(1e-12));
  double longest = 0;
  for (int t = 0; t < fine.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = fine.triangle(t)[e], b = fine.triangle(t)[(e + 1) % 3];
      const double length = distance(fine.position(a), fine.position(b));
      REQUIRE(length <= std::min(lengths[a], lengths[b]));
      longest = std::max(longest, length);
    }
  CHECK(longest > 0.15);  // coarser where the field is long
  CHECK(fine.triangle_count() < refine_long_edges(mesh, 0.05).triangle_count() / 2);
  CHECK(fine.area() == Approx(mesh.area()).epsilon(1e-12));
  std::vector<double> bad(mesh.vertex_count(), 0.1);
  bad[2] = 0;
  REQUIRE_THROWS_AS(refine_to_length_field(mesh, bad), InputError);
  bad[2] = std::nan("");
  REQUIRE_THROWS_AS(refine_to_length_field(mesh, bad), InputError);
  std::vector<double> wrong(mesh.vertex_count() - 1, 0.1);
  REQUIRE_THROWS(refine_to_length_field(mesh, wrong));
}

TEST_CASE("A spatially ordered refinement is the same surface with neighbours close in memory") {
  // Two icospheres side by side, their triangles shuffled: the input order says nothing of where a
  // triangle is. Both orders give the same triangles and carry a field alike; the spatial one
  // numbers vertices and components by first use and keeps neighbours close in the arrays.
  const SurfaceMesh mesh = test::shuffled(test::merge(test::icosphere(3), test::icosphere(2), {3, 0, 0}), 7);
  auto f = [](const Vec3& p) { return 0.06 + 0.01 * p.x - 0.02 * p.z; };
  std::vector<double> by_input, by_space;
  for (const Vec3& p : mesh.positions()) by_input.push_back(f(p));
  by_space = by_input;
  const SurfaceMesh input = refine_to_length_field(mesh, by_input);
  const SurfaceMesh spatial = refine_to_length_field(mesh, by_space, RefineOrder::Spatial);
  REQUIRE(spatial.vertex_count() == input.vertex_count());
  REQUIRE(spatial.triangle_count() == input.triangle_count());
  REQUIRE(spatial.triangle_count() > 4 * mesh.triangle_count());
  // The same triangles, as corner positions from the lowest corner on (orientation kept).
  auto corners = [](const SurfaceMesh& m) {
    std::vector<std::array<std::array<double, 3>, 3>> out;
    for (const Triangle& tri : m.triangles()) {
      std::array<std::array<double, 3>, 3> c;
      for (int k = 0; k < 3; ++k) c[k] = {m.position(tri[k]).x, m.position(tri[k]).y, m.position(tri[k]).z};
      std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
      out.push_back(c);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  REQUIRE(corners(spatial) == corners(input));
  for (int v = 0; v < spatial.vertex_count(); ++v) REQUIRE(by_space[v] == Approx(f(spatial.position(v))).margin(1e-12));
  // Adjacency and components as the checking constructor finds them (components by first triangle).
  const SurfaceMesh checked(spatial.positions(), spatial.triangles());
  REQUIRE(spatial.component_count() == 2);
  REQUIRE(spatial.triangle_components() == checked.triangle_components());
  for (int t = 0; t < spatial.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) REQUIRE(spatial.neighbor(t, e) == checked.neighbor(t, e));
  // Vertices in order of first use: each triangle's corners are at most one past those before it.
  int next = 0;
  for (const Triangle& tri : spatial.triangles())
    for (int v : tri) {
      REQUIRE(v <= next);
      if (v == next) ++next;
    }
  // Neighbours' distance in the triangle array, on average over all edges: the pieces of one input
  // triangle are consecutive in either order, but across input triangles the shuffled order jumps.
  INFO("mean neighbour gap: spatial " << mean_gap(spatial) << ", input " << mean_gap(input));
  CHECK(mean_gap(spatial) * 10 < mean_gap(input));
  // A mesh with no long edge is copied in either order, unsplit.
  std::vector<double> long_lengths(mesh.vertex_count(), 10.0);
  const SurfaceMesh same = refine_to_length_field(mesh, long_lengths, RefineOrder::Spatial);
  REQUIRE(corners(same) == corners(mesh));
}

TEST_CASE("A spatially ordered copy is the same surface, each triangle where the map says, corners in order") {
  const SurfaceMesh mesh = test::shuffled(test::merge(test::icosphere(3), test::icosphere(2), {3, 0, 0}), 11);
  std::vector<int> new_triangle;
  const SurfaceMesh ordered = spatially_ordered(mesh, &new_triangle);
  REQUIRE(ordered.triangle_count() == mesh.triangle_count());
  REQUIRE(ordered.vertex_count() == mesh.vertex_count());
  REQUIRE(new_triangle.size() == static_cast<size_t>(mesh.triangle_count()));
  // A permutation, and triangle t's corners, in their order, are those of new_triangle[t].
  std::vector<int> seen(mesh.triangle_count(), 0);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    REQUIRE(++seen[new_triangle[t]] == 1);
    for (int k = 0; k < 3; ++k)
      REQUIRE(ordered.position(ordered.triangle(new_triangle[t])[k]) == mesh.position(mesh.triangle(t)[k]));
  }
  // Adjacency as the checking constructor finds it, and the same topology.
  const SurfaceMesh checked(ordered.positions(), ordered.triangles());
  for (int t = 0; t < ordered.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) REQUIRE(ordered.neighbor(t, e) == checked.neighbor(t, e));
  REQUIRE(ordered.triangle_components() == checked.triangle_components());
  REQUIRE(ordered.component_count() == 2);
  REQUIRE(ordered.euler_characteristic() == mesh.euler_characteristic());
  INFO("mean neighbour gap: ordered " << mean_gap(ordered) << ", shuffled " << mean_gap(mesh));
  CHECK(mean_gap(ordered) * 10 < mean_gap(mesh));
}

TEST_CASE("A fan of 200k triangles round one vertex is built without quadratic work at its hub") {
  // Edge and duplicate look-ups go through the corner with the fewest triangles, and the
  // one-ring check searches the hub's sorted list: a hub costs O(d log d), not O(d²) (which would
  // be 4·10¹⁰ steps here).
  const int n = 200000;
  std::vector<Vec3> p = {{0, 0, 0}};
  for (int i = 0; i < n; ++i) p.push_back({std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0});
  std::vector<Triangle> t;
  for (int i = 0; i < n; ++i) t.push_back({0, 1 + i, 1 + (i + 1) % n});
  const SurfaceMesh fan(p, t);
  REQUIRE(fan.vertex_triangle_count(0) == n);
  REQUIRE(fan.euler_characteristic() == 1);
  REQUIRE(fan.boundary_loops().size() == 1);
  REQUIRE(fan.neighbor(0, 0) == n - 1);  // triangle 0's edge (0, 1) is the last triangle's (1, 0)
  REQUIRE(fan.neighbor(0, 2) == 1);      // and its edge (2, 0) triangle 1's (0, 2)
  // The same fan with a triangle repeated is refused, naming both.
  t.push_back(t[n / 2]);
  REQUIRE_THROWS_WITH(SurfaceMesh(p, t), Catch::Contains(std::to_string(n / 2)) && Catch::Contains("duplicates"));
}

TEST_CASE("The fewest vertices a mesh of the same topology can have") {
  REQUIRE(test::octahedron().minimum_vertex_count() == 4);  // a sphere: the tetrahedron
  REQUIRE(test::grid(3, 3).minimum_vertex_count() == 3);    // a disk: one triangle
  REQUIRE(test::merge(test::octahedron(), test::grid(2, 2), Vec3{5, 0, 0}).minimum_vertex_count() == 7);
  REQUIRE(make_stress_mesh("knot_tube").minimum_vertex_count() == 7);  // a torus
  // An annulus (the 3 x 3 grid without its middle square): three vertices on each loop.
  const SurfaceMesh grid = test::grid(3, 3);
  std::vector<Vec3> positions;
  for (int v = 0; v < grid.vertex_count(); ++v) positions.push_back(grid.position(v));
  std::vector<Triangle> ring;
  for (int t = 0; t < grid.triangle_count(); ++t)
    if (t != 8 && t != 9) ring.push_back(grid.triangle(t));  // the middle square's two triangles
  const SurfaceMesh annulus(positions, ring);
  REQUIRE(annulus.boundary_loops().size() == 2);
  REQUIRE(annulus.euler_characteristic() == 0);
  REQUIRE(annulus.minimum_vertex_count() == 6);
}

TEST_CASE("A Morton order visits each octant of the bounding cube in one run with x fastest") {
  // Eight clusters of points at the corners of a cube, each a few points in random order.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(0.0, 0.1);
  std::vector<Vec3> points;
  std::vector<int> octant;
  for (int k = 0; k < 80; ++k) {
    const int o = static_cast<int>(random() % 8);
    points.push_back({(o & 1) + jitter(random), (o >> 1 & 1) + jitter(random), (o >> 2 & 1) + jitter(random)});
    octant.push_back(o);
  }
  // A duplicate of point 0 after it: equal codes keep the index order.
  points.push_back(points[0]);
  octant.push_back(octant[0]);
  const std::vector<int> order = morton_order(points);
  REQUIRE(order.size() == points.size());
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < sorted.size(); ++i) REQUIRE(sorted[i] == static_cast<int>(i));
  // The octant number x + 2y + 4z never decreases along the order.
  for (size_t k = 1; k < order.size(); ++k) REQUIRE(octant[order[k - 1]] <= octant[order[k]]);
  const auto first = std::find(order.begin(), order.end(), 0);
  REQUIRE(first != order.end());
  REQUIRE(first + 1 != order.end());
  REQUIRE(*(first + 1) == static_cast<int>(points.size()) - 1);
  REQUIRE(morton_order({}).empty());
  REQUIRE(morton_order({{1, 2, 3}}) == std::vector<int>{0});
  // Enough points for the radix sort's own passes (small inputs go to a comparison sort): each of
  // 10000 points twice, the copy 10000 places later, and every copy right after its original.
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> many(20000);
  for (int i = 0; i < 10000; ++i) many[i] = many[i + 10000] = {unit(random), unit(random), unit(random)};
  const std::vector<int> big = morton_order(many);
  REQUIRE(big.size() == many.size());
  for (size_t k = 0; k + 1 < big.size(); ++k)
    if (big[k] < 10000) REQUIRE(big[k + 1] == big[k] + 10000);
}
