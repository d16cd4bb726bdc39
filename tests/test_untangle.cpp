// Untangling crossing triangles of a dual, and the crossings an input has of its own (remesh/untangle.h).
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
