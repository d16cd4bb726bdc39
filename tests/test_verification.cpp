// The diagram verification: valid LRVDs and RVDs pass every property they promise, and each
// property fails, naming the offender, when a valid diagram is broken in exactly its way.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "common/error.h"
#include "diagram/cells_output.h"
#include "diagram/dual.h"
#include "mesh/refine.h"
#include "test_meshes.h"
#include "verification/diagram_check.h"
#include "verification/diagram_geometry.h"
#include "verification/triangle_enclosures.h"
#include "voronoi/lrvd.h"
#include "voronoi/rvd.h"

using namespace lrvd;

namespace {

bool names(const PropertyResult& p, const std::string& part) {
  for (const std::string& s : p.first_offenders)
    if (s.find(part) != std::string::npos) return true;
  return false;
}

std::string offenders(const PropertyResult& p) {
  std::string out;
  for (const std::string& s : p.first_offenders) out += "  " + s + "\n";
  return out;
}

// Polygon indices of triangle t.
std::vector<int> polygons_of(const Diagram& d, int t) {
  std::vector<int> out;
  for (int p = d.triangle_offsets[t]; p < d.triangle_offsets[t + 1]; ++p) out.push_back(p);
  return out;
}

bool cell_in_triangle(const Diagram& d, int t, int cell) {
  for (int p : polygons_of(d, t))
    if (d.polygons[p].cell == cell) return true;
  return false;
}

// First triangle with at least `count` polygons, or -1.
int triangle_with_polygons(const Diagram& d, int count) {
  for (int t = 0; t + 1 < static_cast<int>(d.triangle_offsets.size()); ++t)
    if (d.triangle_offsets[t + 1] - d.triangle_offsets[t] >= count) return t;
  return -1;
}

void insert_polygon(Diagram& d, int at, const CellPolygon& poly) {
  d.polygons.insert(d.polygons.begin() + at, poly);
  for (size_t t = poly.triangle + 1; t < d.triangle_offsets.size(); ++t) ++d.triangle_offsets[t];
}

void erase_polygon(Diagram& d, int at) {
  const int triangle = d.polygons[at].triangle;
  d.polygons.erase(d.polygons.begin() + at);
  for (size_t t = triangle + 1; t < d.triangle_offsets.size(); ++t) --d.triangle_offsets[t];
}

struct Case {
  SurfaceMesh mesh;
  Samples samples;
  Diagram diagram;
};

// A valid LRVD with enough cells and boundaries to break: icosphere(2), 30 samples.
Case valid_lrvd() {
  Case c{test::icosphere(2), {}, {}};
  c.samples = sample_uniform(c.mesh, 30, 7);
  c.diagram = compute_lrvd(c.mesh, c.samples);
  const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
  INFO(v.summary());
  REQUIRE(v.passed);
  return c;
}

void require_only_broken(const DiagramVerification& v, const PropertyResult& broken, const std::string& offender) {
  INFO(v.summary() << "offenders of the broken property:\n" << offenders(broken));
  REQUIRE_FALSE(v.passed);
  REQUIRE_FALSE(broken.passed);
  REQUIRE(broken.violations >= 1);
  REQUIRE(names(broken, offender));
}

}  // namespace

TEST_CASE("Valid LRVDs pass all six properties on a sphere and a sheet", "[verification]") {
  const std::vector<std::pair<std::string, SurfaceMesh>> meshes = {{"icosphere(2)", test::icosphere(2)},
                                                                   {"grid(8, 8)", test::grid(8, 8)}};
  for (const auto& [name, mesh] : meshes)
    for (int n : {1, 2, 10, 50})
      for (std::uint64_t seed : {1u, 2u, 3u}) {
        const Samples samples = sample_uniform(mesh, n, seed);
        const Diagram d = compute_lrvd(mesh, samples);
        const DiagramVerification v = verify_diagram(mesh, samples, d);
        INFO(name << " n=" << n << " seed=" << seed << "\n" << v.summary());
        CHECK(v.passed);
        for (const PropertyResult* p : {&v.sample_in_cell, &v.connected, &v.equidistant, &v.disjoint, &v.coverage,
                                        &v.conforming}) {
          CHECK(p->passed);
          CHECK(p->promised);
          CHECK(p->checked > 0);
        }
        CHECK(v.cells_with_multiple_components == 0);
        CHECK(v.sample_in_cell.checked == n);
        CHECK(v.coverage.checked == mesh.triangle_count());
      }
}

TEST_CASE("Valid RVDs pass every property but connectedness, which they do not promise", "[verification]") {
  const std::vector<std::pair<std::string, SurfaceMesh>> meshes = {{"icosphere(2)", test::icosphere(2)},
                                                                   {"grid(8, 8)", test::grid(8, 8)}};
  for (const auto& [name, mesh] : meshes)
    for (int n : {1, 2, 10, 50})
      for (std::uint64_t seed : {1u, 2u, 3u}) {
        const Samples samples = sample_uniform(mesh, n, seed);
        const Diagram d = compute_rvd(mesh, samples);
        const DiagramVerification v = verify_diagram(mesh, samples, d);
        INFO(name << " n=" << n << " seed=" << seed << "\n" << v.summary());
        CHECK(v.passed);
        CHECK_FALSE(v.connected.promised);
        for (const PropertyResult* p : {&v.sample_in_cell, &v.equidistant, &v.disjoint, &v.coverage, &v.conforming})
          CHECK(p->passed);
      }
}

TEST_CASE("On nearby sheets the RVD's split cells are reported, not promised; the LRVD's are whole", "[verification]") {
  const SurfaceMesh mesh = test::merge(test::grid(6, 6), test::grid(6, 6), {0, 0, 0.05});
  int rvd_split = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const Samples samples = sample_uniform(mesh, 6, seed);
    const Diagram rvd = compute_rvd(mesh, samples);
    const DiagramVerification v = verify_diagram(mesh, samples, rvd);
    INFO("seed " << seed << "\n" << v.summary());
    CHECK(v.passed);  // connectedness is not promised by the RVD
    CHECK(v.connected.passed == (v.cells_with_multiple_components == 0));
    if (!v.connected.passed) {
      ++rvd_split;
      CHECK(names(v.connected, "pieces, stray piece in triangle"));
    }
    const Diagram lrvd = compute_lrvd(mesh, samples);
    const DiagramVerification w = verify_diagram(mesh, samples, lrvd);
    INFO(w.summary());
    CHECK(w.passed);
    CHECK(w.connected.passed);
  }
  CHECK(rvd_split > 0);
}

TEST_CASE("Degenerate inputs pass: bisectors along mesh edges and through mesh vertices, zero-area slivers",
          "[verification][degenerate]") {
  // At such inputs the perturbed diagram has slivers that collapse to points or segments in the
  // exact (unperturbed) geometry; they are no pieces of a cell and no overlap.
  const SurfaceMesh grid = test::grid(4, 4);
  const SurfaceMesh sphere = test::icosphere(2);
  std::vector<Vec3> mixed;  // samples on sphere vertices and edge midpoints
  for (int v = 0; v < sphere.vertex_count(); v += 7) mixed.push_back(sphere.position(v));
  for (int t = 0; t < sphere.triangle_count(); t += 23) {
    const Triangle& tri = sphere.triangle(t);
    mixed.push_back(0.5 * (sphere.position(tri[0]) + sphere.position(tri[1])));
  }
  const std::vector<std::tuple<std::string, const SurfaceMesh*, Samples>> cases = {
      {"four quadrants of a grid", &grid, locate_points(grid, {{0.25, 0.25, 0}, {0.75, 0.25, 0}, {0.25, 0.75, 0}, {0.75, 0.75, 0}})},
      {"samples on grid vertices", &grid, locate_points(grid, grid.positions())},
      {"sphere vertices and edge midpoints", &sphere, locate_points(sphere, mixed)},
      {"all sphere vertices (cospherical)", &sphere, locate_points(sphere, sphere.positions())}};
  for (const auto& [name, mesh, samples] : cases)
    for (DiagramKind kind : {DiagramKind::Lrvd, DiagramKind::Rvd}) {
      const Diagram d = compute_diagram(*mesh, samples, kind);
      const DiagramVerification v = verify_diagram(*mesh, samples, d);
      INFO(name << " " << to_string(kind) << "\n" << v.summary());
      CHECK(v.passed);
      CHECK(v.connected.passed);
      // Exact ties: some signs are zero, which only the rationals can tell.
      CHECK(v.rational_points > 0);
      CHECK(v.rational_points <= v.distinct_vertices + samples.size());
    }
}

TEST_CASE("A vertex the intervals cannot place is placed by the rationals", "[verification]") {
  // Sites one ulp apart in x: their bisector is all but parallel to the edge y = 0, and the
  // denominator of its parameter (2e-16) is below the rounding of its two terms.
  const std::vector<Vec3> corners = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<Site> sites = {{{0.3, 0.1, 0}, 0, 0}, {{std::nextafter(0.3, 1.0), 0.7, 0}, 0, 1}};
  const SymbolicContext ctx{corners.data(), sites.data()};
  const SymbolicVertex q = SymbolicVertex::on_edge(0, 1, 0, 1);
  REQUIRE_FALSE(enclose_position(q, ctx).has_value());
  const verify_detail::ExactVertex x = verify_detail::ExactVertex::of(q, ctx);
  REQUIRE(x.valid);
  const ExactPoint e = exact_position(q, ctx);
  for (int c = 0; c < 3; ++c) {
    const CGAL::Gmpq& v = verify_detail::coordinate(e, c);
    CHECK((CGAL::Gmpq(x.box[c].inf()) <= v && v <= CGAL::Gmpq(x.box[c].sup())));
  }
  CHECK(x.edge_parameter() == exact_edge_parameter(q, ctx));
  CHECK(x.p().x == e.x);
  CHECK_FALSE(verify_detail::within_edge(x));  // far beyond the edge's end
}

TEST_CASE("The verification's enclosures, made triangle by triangle, are enclose_position's bit for bit",
          "[verification]") {
  // Random triangles at scales from 1e-3 to 1e3, some far from the origin, and six sites: every type
  // B vertex of each edge, every type C of the triangle (in its corners' order, and in another order,
  // which takes enclose_position's own path), the corners; sites 4 and 5 mirror each other across
  // the first edge, so that their bisector is parallel to it (no enclosure: nullopt from both).
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(-1, 1);
  int compared = 0, none = 0;
  for (int round = 0; round < 300; ++round) {
    const double scale = std::pow(10.0, -3 + round % 7), shift = round % 3 == 0 ? 100 * scale : 0;
    std::vector<Vec3> points;
    for (int k = 0; k < 3; ++k) points.push_back({shift + scale * unit(rng), scale * unit(rng), scale * unit(rng)});
    points[1].y = points[0].y;  // the first edge along x: a mirror across it is exact in doubles
    points[1].z = points[0].z;
    std::vector<Site> sites;
    for (int k = 0; k < 4; ++k) {
      const Vec3 p{shift + scale * unit(rng), scale * unit(rng), scale * unit(rng)};
      sites.push_back({p, round % 2 ? 0.0 : scale * scale * std::abs(unit(rng)), k});
    }
    const double off = scale * (0.5 + std::abs(unit(rng)));
    sites.push_back({{shift, points[0].y + off, points[0].z}, 0.0, 4});
    sites.push_back({{shift, points[0].y - off, points[0].z}, 0.0, 5});
    const SymbolicContext ctx{points.data(), sites.data()};
    std::vector<SymbolicVertex> vertices;
    for (int c = 0; c < 3; ++c) vertices.push_back(SymbolicVertex::mesh_vertex(c));
    for (int a = 0; a < 6; ++a)
      for (int b = a + 1; b < 6; ++b) {
        for (int e = 0; e < 3; ++e) vertices.push_back(SymbolicVertex::on_edge(e, (e + 1) % 3, a, b));
        for (int c = b + 1; c < 4; ++c) {
          vertices.push_back(SymbolicVertex::in_triangle({0, 1, 2}, a, b, c));
          vertices.push_back(SymbolicVertex::in_triangle({1, 2, 0}, a, b, c));
        }
      }
    verify_detail::TriangleEnclosures enclosures;
    enclosures.reset({0, 1, 2}, ctx);
    for (const SymbolicVertex& q : vertices) {
      std::array<CGAL::Interval_nt<false>, 3> box;
      CGAL::Interval_nt<false> parameter;
      bool made;
      {
        CGAL::Protect_FPU_rounding<true> upward;
        made = enclosures.enclose(q, box, parameter);
      }
      const std::optional<PositionEnclosure> e = enclose_position(q, ctx);
      REQUIRE(made == e.has_value());
      ++compared;
      if (!made) {
        ++none;
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        CHECK(box[c].inf() == e->box[c].inf());
        CHECK(box[c].sup() == e->box[c].sup());
      }
      CHECK(parameter.inf() == e->parameter.inf());
      CHECK(parameter.sup() == e->parameter.sup());
    }
  }
  CHECK(compared == 300 * (3 + 15 * 3 + 2 * 4));
  CHECK(none >= 300);  // the mirrored pair on the first edge, at least
}

TEST_CASE("The report of a diagram broken in many places is the same with one thread and with four",
          "[verification]") {
  // Offenders in many of the parallel passes' chunks (512 triangles): their first ten, in triangle
  // order, are those of one pass.
  const SurfaceMesh mesh = test::icosphere(5);  // 20,480 triangles
  const Samples samples = sample_uniform(mesh, 2000, 3);
  Diagram d = compute_lrvd(mesh, samples);
  std::vector<int> broken;
  for (int t = mesh.triangle_count() - 1; t >= 0; t -= 97)
    if (d.triangle_offsets[t + 1] - d.triangle_offsets[t] >= 2) {
      erase_polygon(d, d.triangle_offsets[t] + 1);
      broken.push_back(t);
    }
  REQUIRE(broken.size() > 20);
  std::sort(broken.begin(), broken.end());
  auto verify_with = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return verify_diagram(mesh, samples, d).to_json();
  };
  nlohmann::json one = verify_with(1), four = verify_with(4);
  one.erase("time_s");
  four.erase("time_s");
  CHECK(one == four);
  const nlohmann::json& coverage = one.at("properties").at("coverage");
  CHECK(coverage.at("violations").get<std::size_t>() == broken.size());
  REQUIRE(coverage.at("first_offenders").size() == 10);
  for (int k = 0; k < 10; ++k)
    CHECK(coverage.at("first_offenders")[k].get<std::string>().rfind(fmt::format("triangle {}:", broken[k]), 0) == 0);
}

TEST_CASE("Samples on the corners of a right-angled tetrahedron: a connected LRVD in every order",
          "[verification][degenerate][lrvd]") {
  // The region of the sample at the right-angled corner reaches the opposite face in a triangle
  // that touches the rest of the region only at three edge midpoints, where three samples tie.
  // The perturbation gives the sample of the lower id a side of zero length there. The LRVD must
  // not grow across such a side (the piece beyond would be stray), and the side is no part of the
  // split that conformity compares. Before that, 12 of the 24 orders failed `connected`.
  const std::vector<Vec3> corners = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const SurfaceMesh tetrahedron(corners, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
  const SurfaceMesh refined = refine_long_edges(tetrahedron, 0.3);  // the midpoints become mesh vertices
  std::array<int, 4> order{0, 1, 2, 3};
  int orders = 0;
  reset_predicate_stats();
  do {
    std::vector<Vec3> points;
    for (int c : order) points.push_back(corners[c]);
    for (const SurfaceMesh* mesh : {&tetrahedron, &refined}) {
      const Samples samples = locate_points(*mesh, points);
      for (DiagramKind kind : {DiagramKind::Lrvd, DiagramKind::Rvd}) {
        const Diagram d = compute_diagram(*mesh, samples, kind);
        const DiagramVerification v = verify_diagram(*mesh, samples, d);
        INFO("order " << fmt::format("{}", fmt::join(order, " ")) << ", " << mesh->triangle_count() << " triangles, "
                      << to_string(kind) << "\n" << v.summary());
        CHECK(v.passed);
        CHECK(v.conforming.passed);
        // The diagram's own count of cells in pieces agrees with the verification's.
        int split = 0;
        for (int c : cell_components(d, *mesh).count) split += c > 1;
        CHECK(split == v.cells_with_multiple_components);
        if (kind == DiagramKind::Lrvd) CHECK(v.connected.passed);
      }
    }
    ++orders;
  } while (std::next_permutation(order.begin(), order.end()));
  CHECK(orders == 24);
  CHECK(predicate_stats().total.perturbations > 0);  // the ties were met
}

TEST_CASE("Samples on a cube's lattice: the RVD's neighbours include every two on one empty sphere",
          "[verification][degenerate][rvd]") {
  // The surface of the cube [0, 2]^3 in unit squares, each split in two, the diagonals alternating.
  std::map<std::array<int, 3>, int> index;
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  auto vertex = [&](std::array<int, 3> p) {
    auto [it, added] = index.emplace(p, static_cast<int>(positions.size()));
    if (added) positions.push_back({double(p[0]), double(p[1]), double(p[2])});
    return it->second;
  };
  const int n = 2;
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {0, n})
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto at = [&](int u, int v) {
            std::array<int, 3> p{};
            p[axis] = side, p[(axis + 1) % 3] = u, p[(axis + 2) % 3] = v;
            return vertex(p);
          };
          const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
          const bool even = (i + j) % 2 == 0;
          if (side == 0) {
            if (even) triangles.insert(triangles.end(), {{a, c, b}, {a, d, c}});
            else triangles.insert(triangles.end(), {{a, d, b}, {b, d, c}});
          } else {
            if (even) triangles.insert(triangles.end(), {{a, b, c}, {a, c, d}});
            else triangles.insert(triangles.end(), {{a, b, d}, {b, c, d}});
          }
        }
  const SurfaceMesh cube(positions, triangles);
  // Every lattice point, and the midpoints of every third edge: 8 samples at the corners of each
  // unit cube are on one empty sphere, and CGAL's triangulation of them need not join the pairs
  // the diagram's perturbation makes neighbours.
  std::vector<Vec3> points = positions;
  std::set<std::pair<int, int>> edges;
  for (const Triangle& t : triangles)
    for (int e = 0; e < 3; ++e) edges.insert(std::minmax(t[e], t[(e + 1) % 3]));
  int k = 0;
  for (const auto& [a, b] : edges)
    if (k++ % 3 == 0) points.push_back(0.5 * (positions[a] + positions[b]));
  const double length = suggested_refinement_length(cube, static_cast<int>(points.size()));
  const SurfaceMesh mesh = refine_long_edges(cube, length);
  const Samples samples = locate_points(mesh, points);
  for (DiagramKind kind : {DiagramKind::Rvd, DiagramKind::Lrvd}) {
    const Diagram d = compute_diagram(mesh, samples, kind);
    const DiagramVerification v = verify_diagram(mesh, samples, d);
    INFO(to_string(kind) << "\n" << v.summary());
    CHECK(v.passed);
    CHECK(v.equidistant.passed);
  }
}

TEST_CASE("Samples all in one plane on a circle round a mesh vertex: every order gives a valid RVD and RPD",
          "[verification][degenerate][rvd]") {
  // Four samples on the circle round the centre of a square of 2 x 2 quads, a mesh vertex. CGAL's
  // triangulation of coplanar samples has dimension 2 and joins one diagonal pair, while the
  // perturbation may make the other pair neighbours: before their circle grouped the triangles,
  // 9 of the 24 orders lost the cell of a whole triangle (an audit).
  const SurfaceMesh square = test::grid(2, 2);
  const std::array<Vec3, 4> corners = {Vec3{0.25, 0.25, 0}, {0.75, 0.25, 0}, {0.75, 0.75, 0}, {0.25, 0.75, 0}};
  std::array<int, 4> order{0, 1, 2, 3};
  int orders = 0;
  do {
    std::vector<Vec3> points;
    for (int c : order) points.push_back(corners[c]);
    Samples samples = locate_points(square, points);
    for (DiagramKind kind : {DiagramKind::Rvd, DiagramKind::Rpd}) {
      samples.weights = kind == DiagramKind::Rpd ? std::vector<double>(4, 0.01) : std::vector<double>();
      const Diagram d = compute_diagram(square, samples, kind);
      const DiagramVerification v = verify_diagram(square, samples, d);
      INFO("order " << fmt::format("{}", fmt::join(order, " ")) << ", " << to_string(kind) << "\n" << v.summary());
      CHECK(v.passed);
    }
    ++orders;
  } while (std::next_permutation(order.begin(), order.end()));
  CHECK(orders == 24);
}

TEST_CASE("Power diagrams do not promise that a sample lies in its cell", "[verification]") {
  const SurfaceMesh mesh = test::icosphere(1);
  Samples samples = sample_uniform(mesh, 10, 5);
  samples.weights.assign(10, 0.0);
  samples.weights[3] = 2.0;  // cell 3 swallows its neighbours' samples
  const Diagram d = compute_diagram(mesh, samples, DiagramKind::Rpd);
  const DiagramVerification v = verify_diagram(mesh, samples, d);
  INFO(v.summary());
  CHECK_FALSE(v.sample_in_cell.promised);
  CHECK_FALSE(v.sample_in_cell.passed);
  CHECK(v.passed);
}

namespace {

// Breaks c: in the triangle of the first sample whose triangle holds another cell's polygon too,
// the two polygons swap cells. Returns that sample, or -1 if there is none.
int swap_cells_in_a_sample_triangle(Case& c) {
  for (int i = 0; i < c.samples.size(); ++i) {
    int own = -1, other = -1;
    for (int p : polygons_of(c.diagram, c.samples.triangles[i]))
      (c.diagram.polygons[p].cell == i ? own : other) = p;
    if (own < 0 || other < 0) continue;
    std::swap(c.diagram.polygons[own].cell, c.diagram.polygons[other].cell);
    return i;
  }
  return -1;
}

// Breaks c: the one polygon of a triangle goes to a cell absent from that triangle and from its
// three neighbours. Returns {triangle, cell}, or {-1, -1} if there is none.
std::pair<int, int> relabel_a_far_polygon(Case& c) {
  const Diagram& d = c.diagram;
  for (int t = 0; t < c.mesh.triangle_count(); ++t) {
    if (polygons_of(d, t).size() != 1) continue;
    for (int k = 0; k < d.sample_count; ++k) {
      bool absent = !cell_in_triangle(d, t, k);
      for (int e = 0; e < 3; ++e) absent = absent && !cell_in_triangle(d, c.mesh.neighbor(t, e), k);
      if (!absent) continue;
      c.diagram.polygons[d.triangle_offsets[t]].cell = k;
      return {t, k};
    }
  }
  return {-1, -1};
}

}  // namespace

TEST_CASE("Mutation: swapped cells in a sample's triangle break sample_in_cell", "[verification][mutation]") {
  Case c = valid_lrvd();
  const int sample = swap_cells_in_a_sample_triangle(c);
  REQUIRE(sample >= 0);
  const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
  require_only_broken(v, v.sample_in_cell, fmt::format("sample {}: outside its cell's polygon", sample));
  CHECK(v.disjoint.passed);  // the same pieces, differently named: geometry is untouched
  CHECK(v.coverage.passed);
}

TEST_CASE("Mutation: a far-away polygon relabelled to a cell breaks connectedness", "[verification][mutation]") {
  Case c = valid_lrvd();
  const auto [target, cell] = relabel_a_far_polygon(c);
  REQUIRE(target >= 0);
  const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
  require_only_broken(v, v.connected, fmt::format("cell {}: 2 pieces, stray piece in triangle {}", cell, target));
  CHECK(v.cells_with_multiple_components >= 1);
  CHECK(v.disjoint.passed);
  CHECK(v.coverage.passed);
}

TEST_CASE("Mutation: a type B vertex with a wrong bisector breaks equidistance", "[verification][mutation]") {
  Case c = valid_lrvd();
  Diagram& d = c.diagram;
  int index = -1, triangle = -1;
  SymbolicVertex wrong;
  for (const CellPolygon& poly : d.polygons) {
    for (int k = 0; k < poly.vertex_count && index < 0; ++k) {
      const SymbolicVertex& q = d.vertices[poly.first_vertex + k];
      if (q.type != SymbolicVertex::Type::B) continue;
      for (int third = 0; third < d.sample_count; ++third)  // a sample with no polygon in the triangle
        if (!cell_in_triangle(d, poly.triangle, third)) {
          wrong = SymbolicVertex::on_edge(q.v[0], q.v[1], poly.cell, third);
          index = poly.first_vertex + k;
          triangle = poly.triangle;
          break;
        }
    }
    if (index >= 0) break;
  }
  REQUIRE(index >= 0);
  d.vertices[index] = wrong;
  const DiagramVerification v = verify_diagram(c.mesh, c.samples, d);
  const std::string name = fmt::format("B(edge {}-{}, cells {}|{})", wrong.v[0], wrong.v[1], wrong.label[0], wrong.label[1]);
  require_only_broken(v, v.equidistant, fmt::format("triangle {}: vertex {}", triangle, name));
}

TEST_CASE("Mutation: a duplicated polygon breaks disjointness and coverage", "[verification][mutation]") {
  Case c = valid_lrvd();
  const int t = triangle_with_polygons(c.diagram, 2);
  REQUIRE(t >= 0);
  const CellPolygon copy = c.diagram.polygons[c.diagram.triangle_offsets[t]];
  insert_polygon(c.diagram, c.diagram.triangle_offsets[t] + 1, copy);
  const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
  require_only_broken(v, v.disjoint, fmt::format("triangle {}: polygons of cells {} and {} overlap", t, copy.cell, copy.cell));
  CHECK(names(v.coverage, fmt::format("triangle {}: polygon areas sum to", t)));
  CHECK(v.equidistant.passed);  // the same cells meet at the same points
}

TEST_CASE("Mutation: a deleted polygon breaks coverage", "[verification][mutation]") {
  Case c = valid_lrvd();
  const int t = triangle_with_polygons(c.diagram, 2);
  REQUIRE(t >= 0);
  erase_polygon(c.diagram, c.diagram.triangle_offsets[t] + 1);
  const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
  require_only_broken(v, v.coverage, fmt::format("triangle {}: polygon areas sum to", t));
  CHECK(v.disjoint.passed);
}

TEST_CASE("Mutation: a polygon relabelled on one side of a mesh edge breaks conformity", "[verification][mutation]") {
  Case c = valid_lrvd();
  Diagram& d = c.diagram;
  // A whole-triangle polygon of cell j beside a triangle also holding j: relabel it to a neighbour
  // cell k, so the edge reads j from one side and k from the other.
  int target = -1, old_cell = -1, new_cell = -1;
  for (int t = 0; t < c.mesh.triangle_count() && target < 0; ++t) {
    if (polygons_of(d, t).size() != 1) continue;
    const int j = d.polygons[d.triangle_offsets[t]].cell;
    for (int e = 0; e < 3 && target < 0; ++e)
      for (int p : polygons_of(d, c.mesh.neighbor(t, e)))
        if (d.polygons[p].cell != j && cell_in_triangle(d, c.mesh.neighbor(t, e), j)) {
          target = t;
          old_cell = j;
          new_cell = d.polygons[p].cell;
          break;
        }
  }
  REQUIRE(target >= 0);
  d.polygons[d.triangle_offsets[target]].cell = new_cell;
  const DiagramVerification v = verify_diagram(c.mesh, c.samples, d);
  require_only_broken(v, v.conforming, fmt::format("triangle {} sees", target));
  CHECK(old_cell != new_cell);
  CHECK(v.disjoint.passed);
  CHECK(v.coverage.passed);
}

TEST_CASE("Pieces of a cell that touch at a single point of a mesh edge are not connected", "[verification]") {
  // Unit square, triangles t0 = (0, 1, 3) below the diagonal and t1 = (0, 3, 2) above it; the
  // diagonal is split at its midpoint M by bisector(0, 1). Cell 0 owns [0, M] seen from t0 and
  // [M, 3] seen from t1: its two polygons meet at M only.
  const SurfaceMesh mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 3}, {0, 3, 2}});
  const Samples samples = locate_points(mesh, {{0.3, 0.1, 0}, {0.7, 0.9, 0}});
  Diagram d;
  d.kind = DiagramKind::Lrvd;
  d.sample_count = 2;
  d.sites = make_sites(samples, false);
  const SymbolicVertex m = SymbolicVertex::on_edge(0, 3, 0, 1);
  auto a = [](int v) { return SymbolicVertex::mesh_vertex(v); };
  auto add = [&](int t, int cell, std::vector<SymbolicVertex> verts) {
    d.polygons.push_back({t, cell, static_cast<int>(d.vertices.size()), static_cast<int>(verts.size())});
    d.vertices.insert(d.vertices.end(), verts.begin(), verts.end());
  };
  add(0, 0, {a(0), a(1), m});
  add(0, 1, {a(1), a(3), m});
  add(1, 0, {m, a(3), a(2)});
  add(1, 1, {a(0), m, a(2)});
  d.triangle_offsets = {0, 2, 4};
  const DiagramVerification v = verify_diagram(mesh, samples, d);
  INFO(v.summary() << offenders(v.connected));
  CHECK(names(v.connected, "cell 0: 2 pieces"));
  CHECK(names(v.connected, "cell 1: 2 pieces"));
  CHECK(v.cells_with_multiple_components == 2);
  CHECK(v.disjoint.passed);   // each triangle is still cut into two convex pieces
  CHECK(v.coverage.passed);
  CHECK_FALSE(v.conforming.passed);
}

TEST_CASE("With many cells in one triangle the checks compare fewer pairs and still see every fault",
          "[verification]") {
  // 120 samples on a square of two triangles, not refined: about 60 polygons a triangle, where
  // the overlap and equidistance checks compare only the pairs their certified bounds keep, and
  // each sample is looked for in its own polygons first.
  const SurfaceMesh mesh = test::grid(1, 1);
  std::vector<Vec3> points;
  for (int k = 0; k < 120; ++k)
    points.push_back({std::fmod(0.618034 * k + 0.05, 1.0) * 0.98 + 0.01, (k + 0.5) / 120.0, 0});
  const Samples samples = locate_points(mesh, points);
  for (DiagramKind kind : {DiagramKind::Rvd, DiagramKind::Lrvd}) {
    INFO(to_string(kind));
    const Diagram valid = compute_diagram(mesh, samples, kind);
    REQUIRE(valid.triangle_offsets[1] > 40);
    REQUIRE(verify_diagram(mesh, samples, valid).passed);
    {
      // Polygon 3 of triangle 0 laid over polygon 30's place: the two overlap.
      Diagram d = valid;
      d.polygons[30].first_vertex = d.polygons[3].first_vertex;
      d.polygons[30].vertex_count = d.polygons[3].vertex_count;
      const DiagramVerification v = verify_diagram(mesh, samples, d);
      INFO(v.summary());
      CHECK(names(v.disjoint, fmt::format("polygons of cells {} and {} overlap", d.polygons[3].cell, d.polygons[30].cell)));
    }
    {
      // The cells of polygons 3 and 30 swapped: each polygon's vertices are closer to the other
      // cell's site, far from the cell it names.
      Diagram d = valid;
      std::swap(d.polygons[3].cell, d.polygons[30].cell);
      const DiagramVerification v = verify_diagram(mesh, samples, d);
      INFO(v.summary());
      CHECK(names(v.equidistant, fmt::format("of cell {} is closer to x_{} than to x_{}", d.polygons[3].cell,
                                             d.polygons[30].cell, d.polygons[3].cell)));
      CHECK_FALSE(v.sample_in_cell.passed);
    }
  }
}

TEST_CASE("The report has the documented JSON keys", "[verification]") {
  const SurfaceMesh mesh = test::octahedron();
  const Samples samples = sample_uniform(mesh, 4, 1);
  const DiagramVerification v = verify_diagram(mesh, samples, compute_lrvd(mesh, samples));
  const nlohmann::json j = v.to_json();
  REQUIRE(j.at("passed").get<bool>());
  REQUIRE(j.at("time_s").get<double>() >= 0);
  for (const char* name : {"sample_in_cell", "connected", "equidistant", "disjoint", "coverage", "conforming"}) {
    const nlohmann::json& p = j.at("properties").at(name);
    CHECK(p.at("passed").get<bool>());
    CHECK(p.at("violations").get<int>() == 0);
    CHECK(p.contains("checked"));
    CHECK(p.contains("promised"));
    CHECK(p.at("first_offenders").is_array());
  }
  CHECK(v.summary().empty());
  CHECK(j.at("distinct_vertices").get<std::int64_t>() >= mesh.vertex_count());
  CHECK(j.at("distinct_vertices").get<std::int64_t>() == v.distinct_vertices);
  CHECK(j.at("rational_points").get<std::int64_t>() == v.rational_points);
}

TEST_CASE("The functions that read a diagram refuse one that does not fit the mesh, naming why", "[verification]") {
  // A library audit crashed integrate_cells, compute_dual, cell_components and the cells output
  // with such diagrams (a cell, a vertex range or a mesh vertex out of range).
  const Case valid = valid_lrvd();
  const std::vector<std::pair<std::string, std::function<void(Diagram&)>>> breaks = {
      {"cell", [](Diagram& d) { d.polygons[0].cell = 999; }},
      {"out of range", [](Diagram& d) { d.polygons[0].first_vertex = static_cast<int>(d.vertices.size()); }},
      {"names mesh vertex", [](Diagram& d) { d.vertices[0] = SymbolicVertex::mesh_vertex(100000); }},
      {"offsets", [](Diagram& d) { d.triangle_offsets.back() += 1; }}};
  for (const auto& [what, corrupt] : breaks) {
    INFO(what);
    Diagram d = valid.diagram;
    corrupt(d);
    CHECK_FALSE(diagram_layout_error(d, valid.mesh).empty());
    CHECK_THROWS_AS(integrate_cells(d, valid.mesh, valid.samples), InputError);
    CHECK_THROWS_AS(compute_dual(d, valid.mesh, valid.samples), InputError);
    CHECK_THROWS_AS(cell_components(d, valid.mesh), InputError);
    CHECK_THROWS_AS(diagram_polygon_mesh(d, valid.mesh), InputError);
  }
  CHECK(diagram_layout_error(valid.diagram, valid.mesh).empty());
}

TEST_CASE("Malformed diagrams are reported, not crashed on", "[verification]") {
  SECTION("a cell that is no sample") {
    Case c = valid_lrvd();
    c.diagram.polygons[0].cell = 999;
    const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
    require_only_broken(v, v.disjoint, "names cell 999, which is no sample");
  }
  SECTION("a vertex index out of range") {
    Case c = valid_lrvd();
    c.diagram.vertices[0] = SymbolicVertex::mesh_vertex(100000);
    const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
    require_only_broken(v, v.disjoint, "A(100000), which is malformed");
  }
  SECTION("a vertex range whose end overflows an int") {
    Case c = valid_lrvd();
    c.diagram.polygons[0].first_vertex = std::numeric_limits<int>::max();
    const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
    require_only_broken(v, v.coverage, "vertex range out of bounds");
  }
  SECTION("sites that are not the samples: moved, or not finite (an audit: a NaN reached GMP, SIGFPE)") {
    for (const double x : {7.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
      Case c = valid_lrvd();
      c.diagram.sites[1].p.x = x;
      const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
      require_only_broken(v, v.coverage, "site 1 is not sample 1");
    }
  }
  SECTION("triangle offsets that do not match the mesh") {
    Case c = valid_lrvd();
    c.diagram.triangle_offsets.pop_back();
    const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
    require_only_broken(v, v.coverage, "diagram is malformed");
  }
  SECTION("a type B vertex whose edge is parallel to its bisector") {
    // Samples above each other: bisector(0, 1) is the line y = 0.5, parallel to edge (0, 1).
    const SurfaceMesh mesh = test::grid(1, 1);
    const Samples samples = locate_points(mesh, {{0.25, 0.25, 0}, {0.25, 0.75, 0}});
    Diagram d = compute_lrvd(mesh, samples);
    REQUIRE(verify_diagram(mesh, samples, d).passed);
    d.vertices[d.polygons[0].first_vertex] = SymbolicVertex::on_edge(0, 1, 0, 1);
    const DiagramVerification v = verify_diagram(mesh, samples, d);
    require_only_broken(v, v.equidistant, "B(edge 0-1, cells 0|1) of cell");
    CHECK(names(v.disjoint, "names no point"));
  }
}

TEST_CASE("Without exact geometry a valid LRVD passes and a sample outside its cell or a stray piece still fails",
          "[verification][mutation]") {
  // VerifyOptions::exact_geometry = false runs (1), (2) and (6) only; the triangle pass still
  // decides which polygons are flat, which (1) and (2) read.
  VerifyOptions fast;
  fast.exact_geometry = false;
  {
    const Case c = valid_lrvd();
    const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram, fast);
    INFO(v.summary());
    CHECK(v.passed);
    for (const PropertyResult* p : {&v.sample_in_cell, &v.connected, &v.equidistant, &v.disjoint, &v.coverage,
                                    &v.conforming})
      CHECK(p->passed);
    CHECK(v.sample_in_cell.checked == c.samples.size());
    CHECK(v.connected.checked == c.samples.size());
    CHECK(v.conforming.checked == c.mesh.triangle_count() * 3 / 2);  // a closed mesh: every edge is shared
    CHECK(v.equidistant.checked == 0);  // (3) does not run
    CHECK(v.cells_with_multiple_components == 0);
    CHECK(verify_diagram(c.mesh, c.samples, c.diagram).equidistant.checked > 0);  // it does by default
  }
  {
    Case c = valid_lrvd();
    const int sample = swap_cells_in_a_sample_triangle(c);
    REQUIRE(sample >= 0);
    const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram, fast);
    require_only_broken(v, v.sample_in_cell, fmt::format("sample {}: outside its cell's polygon", sample));
  }
  {
    Case c = valid_lrvd();
    const auto [target, cell] = relabel_a_far_polygon(c);
    REQUIRE(target >= 0);
    const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram, fast);
    require_only_broken(v, v.connected, fmt::format("cell {}: 2 pieces, stray piece in triangle {}", cell, target));
    CHECK(v.cells_with_multiple_components == 1);
  }
}

TEST_CASE("A sample on a mesh edge whose power bisector runs along that edge lies in its zero-area polygon",
          "[verification][degenerate]") {
  // Unit square, t0 = (0, 1, 3) below the diagonal y = x and t1 = (0, 3, 2) above it. Sample a on
  // the diagonal at (1/2, 1/2) with weight 0; sample b at (3/4, 1/4) or (1/4, 3/4) with weight 1/8:
  // their power bisector is the diagonal itself, through x_a, and b's side holds a whole triangle.
  // There the perturbation leaves cell a a sliver of zero area along the diagonal (when a is
  // sample 0), or nothing.
  const SurfaceMesh mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 3}, {0, 3, 2}});
  int flat_cases = 0;
  for (const Vec3 b : {Vec3{0.75, 0.25, 0}, Vec3{0.25, 0.75, 0}})
    for (const bool a_first : {true, false})
      for (const DiagramKind kind : {DiagramKind::Rpd, DiagramKind::Lrpd}) {
        const int a = a_first ? 0 : 1;
        const std::vector<Vec3> points = a_first ? std::vector<Vec3>{{0.5, 0.5, 0}, b} : std::vector<Vec3>{b, {0.5, 0.5, 0}};
        std::vector<double> weights(2, 0.125);
        weights[a] = 0;
        Samples samples = locate_points(mesh, points, weights);
        const Diagram d = compute_diagram(mesh, samples, kind);
        const int far = b.x > b.y ? 0 : 1;  // the triangle on b's side
        INFO(to_string(kind) << " b = (" << b.x << ", " << b.y << "), a = sample " << a);
        REQUIRE(verify_diagram(mesh, samples, d).passed);
        int flat = -1;
        for (int p : polygons_of(d, far)) {
          if (d.polygons[p].cell != a) continue;
          // b's side: cell a has no area there, its vertices all on the diagonal in the exact geometry
          // (the perturbed sliver's B vertices on edges 0-1 and 1-3, or 2-3 and 0-2, are at corners 0 and 3).
          for (int k = 0; k < d.polygons[p].vertex_count; ++k) {
            const ExactPoint e = exact_position(d.polygon_vertices(d.polygons[p])[k], d.context(mesh));
            CHECK(verify_detail::coordinate(e, 0) == verify_detail::coordinate(e, 1));
          }
          flat = p;
        }
        // The sample, at (1/2, 1/2) on the diagonal, located in that triangle instead.
        samples.triangles[a] = far;
        Vec3 at{0, 0, 0};  // halfway between mesh vertices 0 and 3
        for (int k = 0; k < 3; ++k)
          if (mesh.triangle(far)[k] == 0 || mesh.triangle(far)[k] == 3) at[k] = 0.5;
        samples.barycentric[a] = at;
        const DiagramVerification v = verify_diagram(mesh, samples, d);
        INFO(v.summary() << offenders(v.sample_in_cell));
        if (flat < 0) {
          CHECK(names(v.sample_in_cell, fmt::format("sample {}: cell {} has no polygon in the sample's triangle {}", a, a, far)));
          continue;
        }
        ++flat_cases;
        CHECK(v.sample_in_cell.passed);
        CHECK(v.passed);
        // Shrunk to corner 0 (its two vertices there, the first repeated: a segment of zero length),
        // the sliver is still on the sample's line but no longer reaches the sample.
        Diagram shrunk = d;
        std::vector<SymbolicVertex> at_corner;
        for (int k = 0; k < d.polygons[flat].vertex_count; ++k) {
          const SymbolicVertex& q = d.polygon_vertices(d.polygons[flat])[k];
          const ExactPoint e = exact_position(q, d.context(mesh));
          if (CGAL::is_zero(verify_detail::coordinate(e, 0)) && CGAL::is_zero(verify_detail::coordinate(e, 1)))
            at_corner.push_back(q);
        }
        REQUIRE(at_corner.size() == 2);
        at_corner.push_back(at_corner[0]);
        shrunk.polygons[flat].first_vertex = static_cast<int>(shrunk.vertices.size());
        shrunk.polygons[flat].vertex_count = 3;
        shrunk.vertices.insert(shrunk.vertices.end(), at_corner.begin(), at_corner.end());
        const DiagramVerification u = verify_diagram(mesh, samples, shrunk);
        INFO(u.summary() << offenders(u.sample_in_cell));
        CHECK(names(u.sample_in_cell, fmt::format("sample {}: outside its cell's polygon in triangle {} (it lies in cell {}'s)",
                                                  a, far, 1 - a)));
        // Relabelled to b, the sliver no longer makes the sample's cell hold it.
        Diagram broken = d;
        broken.polygons[flat].cell = 1 - a;
        const DiagramVerification w = verify_diagram(mesh, samples, broken);
        INFO(w.summary() << offenders(w.sample_in_cell));
        CHECK(names(w.sample_in_cell, fmt::format("sample {}: cell {} has no polygon in the sample's triangle {}", a, a, far)));
      }
  CHECK(flat_cases > 0);
}

TEST_CASE("Mutation: a triangle left without polygons breaks coverage naming it", "[verification][mutation]") {
  Case c = valid_lrvd();
  const int t = triangle_with_polygons(c.diagram, 1);
  REQUIRE(t >= 0);
  while (c.diagram.triangle_offsets[t + 1] > c.diagram.triangle_offsets[t])
    erase_polygon(c.diagram, c.diagram.triangle_offsets[t]);
  const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
  require_only_broken(v, v.coverage, fmt::format("triangle {}: no polygon", t));
  CHECK(v.disjoint.passed);  // the other triangles' polygons are untouched
}

TEST_CASE("Mutation: two vertices of a polygon swapped make it non-convex and break disjointness",
          "[verification][mutation]") {
  Case c = valid_lrvd();
  Diagram& d = c.diagram;
  // A polygon of four or more vertices: a, b, c, d read as a, c, b, d is a bow tie, b right of a -> c.
  int target = -1;
  for (int p = 0; p < static_cast<int>(d.polygons.size()) && target < 0; ++p)
    if (d.polygons[p].vertex_count >= 4) target = p;
  REQUIRE(target >= 0);
  const CellPolygon poly = d.polygons[target];
  std::swap(d.vertices[poly.first_vertex + 1], d.vertices[poly.first_vertex + 2]);
  const DiagramVerification v = verify_diagram(c.mesh, c.samples, d);
  require_only_broken(v, v.disjoint,
                      fmt::format("triangle {}: polygon of cell {} is not convex and counterclockwise", poly.triangle, poly.cell));
  CHECK(v.equidistant.passed);  // the same vertices
}

TEST_CASE("Mutation: a polygon read as a pentagram turns left at every vertex but is caught as non-convex",
          "[verification][mutation]") {
  Case c = valid_lrvd();
  Diagram& d = c.diagram;
  // A pentagon a b c d e read as a c e b d: every turn has the pentagon's sign, but the edges wind
  // twice around, so a vertex lies right of some edge.
  int target = -1;
  for (int p = 0; p < static_cast<int>(d.polygons.size()) && target < 0; ++p)
    if (d.polygons[p].vertex_count == 5) target = p;
  REQUIRE(target >= 0);
  const CellPolygon poly = d.polygons[target];
  const std::vector<SymbolicVertex> was(d.vertices.begin() + poly.first_vertex,
                                        d.vertices.begin() + poly.first_vertex + 5);
  for (int k = 0; k < 5; ++k) d.vertices[poly.first_vertex + k] = was[(2 * k) % 5];
  const DiagramVerification v = verify_diagram(c.mesh, c.samples, d);
  require_only_broken(v, v.disjoint,
                      fmt::format("triangle {}: polygon of cell {} is not convex and counterclockwise", poly.triangle, poly.cell));
  CHECK(v.equidistant.passed);  // the same vertices
}

TEST_CASE("Mutation: a sample on no triangle or outside its triangle breaks sample_in_cell", "[verification][mutation]") {
  const int sample = 4;
  SECTION("no triangle") {
    Case c = valid_lrvd();
    c.samples.triangles[sample] = -1;
    const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
    require_only_broken(v, v.sample_in_cell, fmt::format("sample {}: not located on a triangle", sample));
    CHECK(v.sample_in_cell.violations == 1);
  }
  SECTION("a triangle past the mesh's") {
    Case c = valid_lrvd();
    c.samples.triangles[sample] = c.mesh.triangle_count();
    const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
    require_only_broken(v, v.sample_in_cell, fmt::format("sample {}: not located on a triangle", sample));
  }
  SECTION("a negative barycentric coordinate") {
    Case c = valid_lrvd();
    const int t = c.samples.triangles[sample];
    c.samples.barycentric[sample] = {-0.25, 0.75, 0.5};
    const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
    require_only_broken(v, v.sample_in_cell,
                        fmt::format("sample {}: barycentric (-0.25, 0.75, 0.5) is outside its triangle {}", sample, t));
    CHECK(v.sample_in_cell.violations == 1);
  }
  SECTION("barycentric coordinates all zero or not finite") {
    for (const Vec3 b : {Vec3{0, 0, 0}, Vec3{std::nan(""), 0.5, 0.5}}) {
      Case c = valid_lrvd();
      c.samples.barycentric[sample] = b;
      const DiagramVerification v = verify_diagram(c.mesh, c.samples, c.diagram);
      require_only_broken(v, v.sample_in_cell, fmt::format("sample {}: barycentric", sample));
    }
  }
}

TEST_CASE("Mutation: a type B vertex moved to another bisector on one side of a mesh edge breaks conformity",
          "[verification][mutation]") {
  Case c = valid_lrvd();
  Diagram& d = c.diagram;
  // A type B vertex of triangle t, and a cell with no polygon in t: in t's polygons the vertex
  // becomes the point where that cell's bisector with the vertex's first cell crosses the edge.
  // Both triangles still see the same cells along the edge, split at different points.
  int t = -1;
  SymbolicVertex q, wrong;
  for (const CellPolygon& poly : d.polygons) {
    for (int k = 0; k < poly.vertex_count && t < 0; ++k) {
      const SymbolicVertex& x = d.polygon_vertices(poly)[k];
      if (x.type != SymbolicVertex::Type::B) continue;
      for (int third = 0; third < d.sample_count; ++third)
        if (!cell_in_triangle(d, poly.triangle, third)) {
          q = x;
          wrong = SymbolicVertex::on_edge(x.v[0], x.v[1], x.label[0], third);
          t = poly.triangle;
          break;
        }
    }
    if (t >= 0) break;
  }
  REQUIRE(t >= 0);
  int replaced = 0;
  for (int p : polygons_of(d, t))
    for (int k = 0; k < d.polygons[p].vertex_count; ++k)
      if (d.vertices[d.polygons[p].first_vertex + k] == q) {
        d.vertices[d.polygons[p].first_vertex + k] = wrong;
        ++replaced;
      }
  CHECK(replaced == 2);  // the two polygons the bisector separates
  const DiagramVerification v = verify_diagram(c.mesh, c.samples, d);
  const int lo = std::min(q.v[0], q.v[1]), hi = std::max(q.v[0], q.v[1]);
  require_only_broken(v, v.conforming, fmt::format("edge ({}, {}): triangles", lo, hi));
  CHECK(names(v.conforming, "but split it at different points"));
  // Both lists of split points are shown: the moved vertex on one side, the original on the other.
  CHECK(names(v.conforming, verify_detail::describe(wrong)));
  CHECK(names(v.conforming, verify_detail::describe(q)));
}

TEST_CASE("Cell components recomputed without polygon_along are those the builder recorded", "[verification]") {
  // cell_components reads Diagram::polygon_along when it is there and recomputes the edges each
  // polygon runs along otherwise (a diagram built by hand); away from ties the two agree.
  const std::vector<std::pair<std::string, SurfaceMesh>> meshes = {
      {"icosphere(2)", test::icosphere(2)},
      {"grid(8, 8)", test::grid(8, 8)},
      {"nearby sheets", test::merge(test::grid(6, 6), test::grid(6, 6), {0, 0, 0.05})}};
  int split_cells = 0, joined = 0;
  for (const auto& [name, mesh] : meshes)
    for (std::uint64_t seed : {1u, 2u, 3u})
      for (DiagramKind kind : {DiagramKind::Lrvd, DiagramKind::Rvd}) {
        const Samples samples = sample_uniform(mesh, 6 + 4 * static_cast<int>(seed), seed);
        const Diagram d = compute_diagram(mesh, samples, kind);
        INFO(name << " seed " << seed << " " << to_string(kind));
        REQUIRE(d.polygon_along.size() == d.polygons.size());
        const CellComponents recorded = cell_components(d, mesh);
        Diagram bare = d;
        bare.polygon_along.clear();
        const CellComponents recomputed = cell_components(bare, mesh);
        CHECK(recomputed.polygon_component == recorded.polygon_component);
        CHECK(recomputed.count == recorded.count);
        for (int c : recorded.count) split_cells += c > 1;
        for (int i = 0; i < d.sample_count; ++i) {
          int polygons = 0;
          for (const CellPolygon& poly : d.polygons) polygons += poly.cell == i;
          joined += polygons > 1 && recorded.count[i] == 1;  // a cell of several polygons, joined into one
        }
      }
  CHECK(split_cells > 0);  // the RVD on nearby sheets splits cells
  CHECK(joined > 0);
}

TEST_CASE("The per-triangle filters give the exact signs at ties, and a broken degenerate diagram is caught through them",
          "[verification][degenerate]") {
  // The checks read each triangle's vertices as FrameVertex (enclosures side by side, the mesh
  // edges they lie on as bits) and compare power distances through SiteTerms; every sign they
  // decide must be the rationals' sign, also where the rationals give zero (samples on mesh
  // vertices and edge midpoints: bisectors through vertices and along edges, cospherical sites).
  const SurfaceMesh grid = test::grid(4, 4);
  const SurfaceMesh sphere = test::icosphere(2);
  std::vector<Vec3> mixed;
  for (int v = 0; v < sphere.vertex_count(); v += 5) mixed.push_back(sphere.position(v));
  for (int t = 0; t < sphere.triangle_count(); t += 17) {
    const Triangle& tri = sphere.triangle(t);
    mixed.push_back(0.5 * (sphere.position(tri[0]) + sphere.position(tri[1])));
  }
  const std::vector<std::tuple<std::string, const SurfaceMesh*, Samples>> cases = {
      {"samples on grid vertices", &grid, locate_points(grid, grid.positions())},
      {"sphere vertices and edge midpoints", &sphere, locate_points(sphere, mixed)},
      {"all sphere vertices (cospherical)", &sphere, locate_points(sphere, sphere.positions())}};
  for (const auto& [name, mesh, samples] : cases) {
    INFO(name);
    Diagram d = compute_diagram(*mesh, samples, DiagramKind::Lrvd);
    REQUIRE(verify_diagram(*mesh, samples, d).passed);
    const SymbolicContext ctx = d.context(*mesh);
    const std::vector<verify_detail::SiteTerms> terms = verify_detail::site_terms(d.sites);
    int orient_zeros = 0, power_zeros = 0;
    int target = -1;  // a polygon of four or more vertices turning strictly left at its second
    for (int t = 0; t < mesh->triangle_count(); ++t) {
      const Triangle& tri = mesh->triangle(t);
      std::vector<verify_detail::ExactVertex> corners;
      for (int c = 0; c < 3; ++c) corners.push_back(verify_detail::ExactVertex::of(SymbolicVertex::mesh_vertex(tri[c]), ctx));
      const verify_detail::Frame f = verify_detail::triangle_frame(*mesh, t, {&corners[0], &corners[1], &corners[2]});
      REQUIRE(f.valid);
      const int drop = predicates::projection_axis(mesh->position(tri[0]), mesh->position(tri[1]), mesh->position(tri[2]));
      CHECK(f.u == (drop + 1) % 3);
      std::vector<SymbolicVertex> symbolic;
      std::vector<int> cells, first;
      for (int p = d.triangle_offsets[t]; p < d.triangle_offsets[t + 1]; ++p) {
        cells.push_back(d.polygons[p].cell);
        first.push_back(static_cast<int>(symbolic.size()));
        for (int k = 0; k < d.polygons[p].vertex_count; ++k) symbolic.push_back(d.polygon_vertices(d.polygons[p])[k]);
      }
      std::vector<verify_detail::ExactVertex> points;
      for (const SymbolicVertex& q : symbolic) points.push_back(verify_detail::ExactVertex::of(q, ctx));
      std::vector<verify_detail::FrameVertex> frame;
      for (size_t k = 0; k < symbolic.size(); ++k) {
        const std::uint8_t edges = verify_detail::edges_of(symbolic[k], tri);
        for (int e = 0; e < 3; ++e) CHECK(((edges >> e) & 1) == symbolic[k].on_mesh_edge(tri[e], tri[(e + 1) % 3]));
        frame.push_back({points[k].box[f.u], points[k].box[f.v], &points[k], edges});
      }
      for (int p = d.triangle_offsets[t]; p < d.triangle_offsets[t + 1] && target < 0; ++p) {
        const int k = first[p - d.triangle_offsets[t]];
        if (d.polygons[p].vertex_count >= 4 &&
            verify_detail::orient_exact(points[k], points[k + 1], points[k + 2], f) == Sign::Positive)
          target = p;
      }
      for (size_t a = 0; a < frame.size(); ++a)
        for (size_t b = a + 1; b < frame.size(); ++b)
          for (size_t c = b + 1; c < frame.size(); ++c) {
            Sign fast;
            {
              CGAL::Protect_FPU_rounding<true> upward;
              fast = verify_detail::orient_upward(frame[a], frame[b], frame[c], f);
            }
            const Sign exact = verify_detail::orient_exact(points[a], points[b], points[c], f);
            CHECK(fast == exact);
            orient_zeros += exact == Sign::Zero && symbolic[a] != symbolic[b] && symbolic[b] != symbolic[c] &&
                            symbolic[a] != symbolic[c];
          }
      for (size_t k = 0; k < points.size(); ++k)
        for (int i : cells)
          for (int j : cells) {
            const Sign exact = verify_detail::compare_power_distance_exact(points[k], d.sites[i], d.sites[j]);
            Sign fast;
            {
              CGAL::Protect_FPU_rounding<true> upward;
              fast = verify_detail::filtered_sign(terms[i].e(points[k]) - terms[j].e(points[k]));
            }
            CHECK((fast == Sign::Zero || fast == exact));  // Zero: undecided, the rationals decide
            power_zeros += i != j && exact == Sign::Zero;
          }
    }
    CHECK(orient_zeros > 0);  // three distinct vertices on one line: ties the filter left to the rationals
    CHECK(power_zeros > 0);

    // Broken through the same paths: a polygon read as a bow tie (a, c, b, ...: b is right of
    // a -> c, since a, b, c turned strictly left), and a polygon listed twice.
    REQUIRE(target >= 0);
    const CellPolygon poly = d.polygons[target];
    Diagram bow_tie = d;
    std::swap(bow_tie.vertices[poly.first_vertex + 1], bow_tie.vertices[poly.first_vertex + 2]);
    const DiagramVerification v = verify_diagram(*mesh, samples, bow_tie);
    require_only_broken(v, v.disjoint,
                        fmt::format("triangle {}: polygon of cell {} is not convex and counterclockwise", poly.triangle, poly.cell));
    insert_polygon(d, target, poly);
    const DiagramVerification twice = verify_diagram(*mesh, samples, d);
    require_only_broken(twice, twice.disjoint, fmt::format("triangle {}: polygons of cells {} and {} overlap", poly.triangle,
                                                           poly.cell, poly.cell));
  }
}
