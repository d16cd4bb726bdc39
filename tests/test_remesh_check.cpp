// Remesh verification: valid remeshes pass every property; each mutation of a valid mesh fails
// exactly the property it breaks; self-intersection counts agree with CGAL's PMP.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include "io/mesh_io.h"
#include "mesh/self_intersections.h"
#include "test_meshes.h"
#include "verification/remesh_check.h"

using namespace lrvd;

namespace {

std::map<std::string, const PropertyResult*> properties(const RemeshVerification& r) {
  return {{"vertex_count", &r.vertex_count}, {"manifold", &r.manifold},     {"closed", &r.closed},
          {"oriented", &r.oriented},         {"topology", &r.topology},     {"non_degenerate", &r.non_degenerate},
          {"no_self_intersection", &r.no_self_intersection}};
}

//! Every property passes but `failing`, which fails (none fails when `failing` is empty).
void require_only_failing(const RemeshVerification& r, const std::string& failing) {
  INFO(r.summary());
  for (const auto& [name, p] : properties(r)) {
    INFO(name);
    REQUIRE(p->passed == (name != failing));
    REQUIRE((p->violations == 0) == (name != failing));
    if (name == failing) REQUIRE_FALSE(p->first_offenders.empty());
  }
  REQUIRE(r.passed == failing.empty());
  REQUIRE((r.summary().find(failing + ":") != std::string::npos) == !failing.empty());
}

RemeshVerification verify_self(const SurfaceMesh& mesh) {
  return verify_remesh(mesh, mesh.positions(), mesh.triangles(), mesh.vertex_count());
}

//! Torus (genus 1, χ = 0) around the z axis: radii 2 and 0.7, nu × nv quads split in two.
SurfaceMesh torus(int nu, int nv) {
  const double two_pi = 2 * std::acos(-1.0);
  std::vector<Vec3> p;
  std::vector<Triangle> t;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = two_pi * i / nu, v = two_pi * j / nv;
      p.push_back({(2 + 0.7 * std::cos(v)) * std::cos(u), (2 + 0.7 * std::cos(v)) * std::sin(u), 0.7 * std::sin(v)});
    }
  auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      t.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return SurfaceMesh(p, t);
}

//! Self-intersecting face pairs by CGAL's Polygon_mesh_processing (the reference implementation).
int pmp_self_intersections(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v;
  for (const Vec3& q : positions) v.push_back(mesh.add_vertex(Kernel::Point_3(q.x, q.y, q.z)));
  for (const Triangle& f : triangles) REQUIRE(mesh.add_face(v[f[0]], v[f[1]], v[f[2]]) != Mesh::null_face());
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(pairs));
  return static_cast<int>(pairs.size());
}

}  // namespace

TEST_CASE("A valid icosphere passes every remesh property") {
  const SurfaceMesh sphere = test::icosphere(2);
  const RemeshVerification r = verify_remesh(test::icosphere(3), sphere.positions(), sphere.triangles(), 162);
  require_only_failing(r, "");
  REQUIRE(r.components == 1);
  REQUIRE(r.euler_characteristic == 2);
  REQUIRE(r.genus == 0);
  REQUIRE(r.boundary_loops == 0);
  REQUIRE(r.self_intersecting_pairs == 0);
  REQUIRE(r.manifold.checked > 0);
  REQUIRE(r.no_self_intersection.checked == sphere.triangle_count());
  const nlohmann::json j = r.to_json();
  for (const char* key : {"passed", "time_s", "components", "euler_characteristic", "genus", "self_intersecting_pairs"})
    REQUIRE(j.contains(key));
  for (const char* key : {"vertex_count", "manifold", "closed", "oriented", "topology", "non_degenerate",
                          "no_self_intersection"})
    REQUIRE(j["properties"][key]["passed"].get<bool>());
}

TEST_CASE("CGAL's knot (genus 1) passes against itself") {
  const SurfaceMesh knot = read_mesh(std::string(LRVD_CGAL_DATA_DIR) + "/knot.off").mesh;
  const RemeshVerification r = verify_self(knot);
  require_only_failing(r, "");
  REQUIRE(r.euler_characteristic == 0);
  REQUIRE(r.genus == 1);
  REQUIRE(r.components == 1);
  REQUIRE(r.self_intersecting_pairs == 0);
}

TEST_CASE("A flipped triangle fails orientation only") {
  const SurfaceMesh sphere = test::icosphere(2);
  std::vector<Triangle> t = sphere.triangles();
  std::swap(t[5][0], t[5][1]);
  const RemeshVerification r = verify_remesh(sphere, sphere.positions(), t, sphere.vertex_count());
  require_only_failing(r, "oriented");
  REQUIRE(r.oriented.violations == 3);
}

TEST_CASE("A removed triangle fails closedness only") {
  const SurfaceMesh sphere = test::icosphere(2);
  std::vector<Triangle> t = sphere.triangles();
  t.erase(t.begin() + 7);
  const RemeshVerification r = verify_remesh(sphere, sphere.positions(), t, sphere.vertex_count());
  require_only_failing(r, "closed");
  REQUIRE(r.closed.violations == 3);
  REQUIRE(r.boundary_loops == 1);
  REQUIRE(r.input_boundary_loops == 0);
  REQUIRE(r.euler_characteristic == 1);
  REQUIRE(r.genus == 0);
}

TEST_CASE("An extra triangle on an edge fails manifoldness only") {
  // A fin standing on the diagonal (0, 4) of an open grid: that edge gets three triangles, the
  // Euler characteristic is unchanged (one vertex, two edges, one triangle more).
  const SurfaceMesh grid = test::grid(2, 2);
  std::vector<Vec3> p = grid.positions();
  std::vector<Triangle> t = grid.triangles();
  p.push_back({0.25, 0.25, 0.5});
  t.push_back({0, 4, 9});
  const RemeshVerification r = verify_remesh(grid, p, t, 10);
  require_only_failing(r, "manifold");
  REQUIRE(r.manifold.violations == 1);
  REQUIRE(r.manifold.first_offenders[0] == "edge (0, 4) has 3 triangles");
}

TEST_CASE("Two octahedra glued at one vertex fail manifoldness only") {
  // The second octahedron's vertex (-1, 0, 0) + (2, 0, 0) is the first one's vertex 0.
  const SurfaceMesh two = test::merge(test::octahedron(), test::octahedron(), {2, 0, 0});
  std::vector<Vec3> p = two.positions();
  std::vector<Triangle> t = two.triangles();
  p.erase(p.begin() + 7);
  for (Triangle& f : t)
    for (int& v : f) v = v == 7 ? 0 : (v > 7 ? v - 1 : v);
  const RemeshVerification r = verify_remesh(two, p, t, 11);
  require_only_failing(r, "manifold");
  REQUIRE(r.manifold.first_offenders[0] == "vertex 0 has 2 separate triangle fans");
  REQUIRE(r.components == 2);
  REQUIRE(r.genus == -1);
}

TEST_CASE("An unused vertex or a wrong vertex count fails the vertex count only") {
  const SurfaceMesh sphere = test::icosphere(1);
  std::vector<Vec3> p = sphere.positions();
  p.push_back({5, 5, 5});
  const RemeshVerification unused = verify_remesh(sphere, p, sphere.triangles(), static_cast<int>(p.size()));
  require_only_failing(unused, "vertex_count");
  REQUIRE(unused.vertex_count.first_offenders[0] == "vertex 42 is used by no triangle");

  const RemeshVerification wrong = verify_remesh(sphere, sphere.positions(), sphere.triangles(), 41);
  require_only_failing(wrong, "vertex_count");
  REQUIRE(wrong.vertex_count.violations == 1);
  require_only_failing(verify_remesh(sphere, sphere.positions(), sphere.triangles(), -1), "");
}

TEST_CASE("A sphere checked against a torus fails topology only") {
  const SurfaceMesh ring = torus(24, 12);
  REQUIRE(ring.euler_characteristic() == 0);
  require_only_failing(verify_self(ring), "");
  const SurfaceMesh sphere = test::icosphere(2);
  const RemeshVerification r = verify_remesh(ring, sphere.positions(), sphere.triangles(), -1);
  require_only_failing(r, "topology");
  REQUIRE(r.genus == 0);
  // Two spheres against one: the component count differs as well.
  const SurfaceMesh spheres = test::merge(sphere, sphere, {3, 0, 0});
  const RemeshVerification two = verify_remesh(sphere, spheres.positions(), spheres.triangles(), -1);
  require_only_failing(two, "topology");
  REQUIRE(two.topology.violations == 2);
}

TEST_CASE("A collinear triangle fails non-degeneracy only") {
  // Along the bottom of a 2 × 1 grid, the cap (2, 1, 0) over vertices (0,0), (0.5,0), (1,0):
  // consistently oriented, the Euler characteristic is unchanged.
  const SurfaceMesh grid = test::grid(2, 1);
  std::vector<Triangle> t = grid.triangles();
  t.push_back({2, 1, 0});
  const RemeshVerification r = verify_remesh(grid, grid.positions(), t, grid.vertex_count());
  require_only_failing(r, "non_degenerate");
  REQUIRE(r.non_degenerate.first_offenders[0] == "triangle 4 (2, 1, 0) has collinear corners");
}

TEST_CASE("Two interpenetrating spheres fail self-intersection only") {
  // Checked against an input whose two spheres are apart: the crossings are the remesh's own.
  const SurfaceMesh apart = test::merge(test::icosphere(2), test::icosphere(2), {5, 0, 0});
  const SurfaceMesh spheres = test::merge(test::icosphere(2), test::icosphere(2), {1, 0, 0});
  const RemeshVerification r = verify_remesh(apart, spheres.positions(), spheres.triangles(), spheres.vertex_count());
  require_only_failing(r, "no_self_intersection");
  REQUIRE(r.self_intersecting_pairs > 0);
  REQUIRE(r.inherited_intersecting_pairs == 0);
  REQUIRE(r.self_intersecting_pairs == r.no_self_intersection.violations);
  REQUIRE(r.self_intersecting_pairs == pmp_self_intersections(spheres.positions(), spheres.triangles()));
}

TEST_CASE("Crossings between components that cross in the input too are inherited, not violations") {
  const SurfaceMesh spheres = test::merge(test::icosphere(2), test::icosphere(2), {1, 0, 0});
  const RemeshVerification r = verify_self(spheres);
  REQUIRE(r.passed);
  REQUIRE(r.self_intersecting_pairs == 0);
  REQUIRE(r.inherited_intersecting_pairs == pmp_self_intersections(spheres.positions(), spheres.triangles()));
  // Only the components that cross in the input pass on their crossings: a third sphere, apart in
  // the input (0.05 from the first), that the remesh swells by a tenth into the first counts, while
  // the first two spheres' crossings stay inherited. (An audit found them all passed: any crossing
  // in the input excused every crossing between two output components.)
  const SurfaceMesh sphere = test::icosphere(2);
  const SurfaceMesh three = test::merge(spheres, sphere, {0, 2.05, 0});
  std::vector<Vec3> swollen = three.positions();
  const Vec3 centre{0, 2.05, 0};
  for (int v = spheres.vertex_count(); v < three.vertex_count(); ++v) swollen[v] = centre + 1.1 * (swollen[v] - centre);
  const RemeshVerification third = verify_remesh(three, swollen, three.triangles(), three.vertex_count());
  INFO(third.summary());
  REQUIRE(verify_self(three).passed);
  REQUIRE_FALSE(third.no_self_intersection.passed);
  REQUIRE(third.self_intersecting_pairs > 0);
  REQUIRE(third.inherited_intersecting_pairs == r.inherited_intersecting_pairs);
  REQUIRE(third.self_intersecting_pairs + third.inherited_intersecting_pairs ==
          pmp_self_intersections(swollen, three.triangles()));
  // A crossing inside one component still counts: a vertex of the first sphere pushed through it.
  std::vector<Vec3> dented = spheres.positions();
  dented[0] = -1.5 * dented[0];
  const RemeshVerification d = verify_remesh(spheres, dented, spheres.triangles(), spheres.vertex_count());
  REQUIRE_FALSE(d.no_self_intersection.passed);
  REQUIRE(d.self_intersecting_pairs > 0);
}

TEST_CASE("Valid meshes have no self-intersecting pairs, as CGAL's PMP agrees") {
  for (const SurfaceMesh& mesh : {test::icosphere(3), torus(24, 12), test::grid(5, 5), test::octahedron()}) {
    const RemeshVerification r = verify_self(mesh);
    REQUIRE(r.self_intersecting_pairs == 0);
    REQUIRE(r.no_self_intersection.passed);
    REQUIRE(pmp_self_intersections(mesh.positions(), mesh.triangles()) == 0);
  }
}

TEST_CASE("Self-intersections through a shared edge or a shared vertex are found") {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.5, 0}, {0.2, 0.2, 1}, {0.2, 0.2, -1},
                               {-1, 0, 1}, {-1, -1, 1}};
  const SurfaceMesh input = test::grid(1, 1);
  SECTION("coplanar triangles folded over their shared edge") {
    const std::vector<Triangle> t = {{0, 1, 2}, {1, 0, 3}};
    REQUIRE(verify_remesh(input, p, t, -1).self_intersecting_pairs == 1);
  }
  SECTION("coplanar triangles on both sides of their shared edge") {
    std::vector<Vec3> q = p;
    q[3] = {0.2, -0.5, 0};
    REQUIRE(verify_remesh(input, q, {{0, 1, 2}, {1, 0, 3}}, -1).self_intersecting_pairs == 0);
  }
  SECTION("a triangle piercing another one through their shared vertex") {
    REQUIRE(verify_remesh(input, p, {{0, 1, 2}, {0, 4, 5}}, -1).self_intersecting_pairs == 1);
  }
  SECTION("triangles touching only at their shared vertex") {
    REQUIRE(verify_remesh(input, p, {{0, 1, 2}, {0, 6, 7}}, -1).self_intersecting_pairs == 0);
  }
  SECTION("a vertex of one triangle on the face of another, unshared") {
    std::vector<Vec3> q = p;
    q[6] = {0.25, 0.25, 0};  // lies inside triangle (0, 1, 2)
    REQUIRE(verify_remesh(input, q, {{0, 1, 2}, {6, 4, 7}}, -1).self_intersecting_pairs == 1);
  }
}

TEST_CASE("The crossing search round hubs finds what the search of every box pair finds") {
  // Fans round a few vertices, in space and folded flat in one plane (shared edges, coplanar
  // overlaps), and triangles without a hub among them: with every vertex of 2, 3, 4 or 8 tested
  // triangles a hub, the pairs are those of the search that meets every pair of boxes.
  // Every other round the points are in four clusters far apart, each triangle in one: few fans
  // meet, and the fans are searched two by two; otherwise most do, and the search goes by bits.
  std::mt19937 rng(7);
  for (int round = 0; round < 40; ++round) {
    const bool flat = round % 3 == 0, clusters = round % 2 == 1;
    std::uniform_int_distribution<int> coordinate(-6, 6);
    std::vector<Vec3> p;
    for (int i = 0; i < 40; ++i)
      p.push_back({double(coordinate(rng)) + (clusters ? 100.0 * (i % 4) : 0.0), double(coordinate(rng)),
                   flat ? 0.0 : double(coordinate(rng))});
    // A point of cluster c (all points when there are no clusters); points 0-7 are the hubs.
    std::uniform_int_distribution<int> cluster(0, 3), member(0, 9), hub(0, 1);
    auto any = [&](int c) { return clusters ? 4 * member(rng) + c : 4 * member(rng) + cluster(rng); };
    auto centre = [&](int c) { return clusters ? 4 * hub(rng) + c : 4 * hub(rng) + cluster(rng); };
    std::vector<Triangle> t;
    for (int i = 0; i < 160; ++i) {
      const int c = cluster(rng);
      Triangle f = {i % 2 ? centre(c) : any(c), any(c), any(c)};
      if (i % 5 == 0) f[1] = centre(c);  // now and then a triangle with two hubs
      t.push_back(f);
    }
    const std::vector<char> proper = proper_triangles(p, t);
    const auto every_pair = find_self_intersections(p, t, proper, std::numeric_limits<int>::max());
    REQUIRE_FALSE(every_pair.empty());
    for (int valence : {2, 3, 4, 8}) {
      INFO("round " << round << ", hubs of " << valence << " triangles");
      REQUIRE(find_self_intersections(p, t, proper, valence) == every_pair);
    }
  }
}

TEST_CASE("A fan of 4000 triangles is searched for crossings round its hub and not pair by pair") {
  // A disk of 4,000 wedges round its centre, then one more wedge laid over one and a half of them
  // (sharing an edge with the first): it crosses the two it lies on, and the search finds exactly
  // those.
  const int n = 4000;
  std::vector<Vec3> p = {{0, 0, 0}};
  for (int i = 0; i < n; ++i) p.push_back({std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0});
  std::vector<Triangle> t;
  for (int i = 0; i < n; ++i) t.push_back({0, 1 + i, 1 + (i + 1) % n});
  REQUIRE(find_self_intersections(p, t).empty());
  p.push_back({std::cos(2 * M_PI * 2.5 / n), std::sin(2 * M_PI * 2.5 / n), 0});  // over wedges 1-2
  t.push_back({0, 1 + 1, n + 1});
  const auto pairs = find_self_intersections(p, t);
  REQUIRE(pairs == find_self_intersections(p, t, {}, std::numeric_limits<int>::max()));
  REQUIRE(pairs == std::vector<std::pair<int, int>>{{1, n}, {2, n}});
}

TEST_CASE("Out-of-range indices and repeated vertices are reported, not thrown") {
  const SurfaceMesh sphere = test::icosphere(1);
  std::vector<Triangle> t = sphere.triangles();
  t[0][2] = 99;
  const RemeshVerification bad_index = verify_remesh(sphere, sphere.positions(), t, -1);
  REQUIRE_FALSE(bad_index.vertex_count.passed);
  REQUIRE_FALSE(bad_index.passed);
  t = sphere.triangles();
  t[0][2] = t[0][1];
  const RemeshVerification repeated = verify_remesh(sphere, sphere.positions(), t, -1);
  REQUIRE_FALSE(repeated.manifold.passed);
  REQUIRE(repeated.manifold.first_offenders[0].find("repeats a vertex") != std::string::npos);
}

TEST_CASE("A triangle repeated with the opposite orientation fails manifoldness") {
  const SurfaceMesh sphere = test::icosphere(1);
  std::vector<Triangle> t = sphere.triangles();
  t.push_back({t[3][2], t[3][1], t[3][0]});
  const RemeshVerification r = verify_remesh(sphere, sphere.positions(), t, -1);
  REQUIRE_FALSE(r.manifold.passed);
  REQUIRE(r.manifold.first_offenders[0].rfind("triangles 3 and 80 have the same vertices", 0) == 0);
  REQUIRE(r.oriented.passed);  // edges in three triangles are manifoldness' business
  REQUIRE(r.closed.passed);
  REQUIRE(r.no_self_intersection.passed);
}
