// Maximal Poisson-disk sampling samples the feature lines first by default (docs/algorithms/mps.md,
// "Features"): a cube's edges and corners, an open sheet's boundary; a mesh without any is sampled
// as with the features off; `lrvd mps` says so on its console and in its report, and --no-features
// samples with darts alone.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

#include "diagram/dual.h"
#include "io/mesh_io.h"
#include "io/mesh_writers.h"
#include "mps/mps.h"
#include "report/mps_report.h"
#include "test_meshes.h"
#include "verification/mps_check.h"
#include "verification/remesh_check.h"
#include "voronoi/lrvd.h"

using namespace lrvd;

namespace {

SurfaceMesh unit_cube() {
  return SurfaceMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
                     {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                      {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}});
}

// Pairs of points closer than the larger of their radii (weights are radii squared), over all pairs.
int close_pairs(const std::vector<Vec3>& points, const std::vector<double>& weights) {
  int close = 0;
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size(); ++j)
      close += squared_distance(points[i], points[j]) < std::max(weights[i], weights[j]);
  return close;
}

// The LRRT of a sampling passes verify_remesh.
bool lrrt_valid(const SurfaceMesh& input, const MpsResult& r) {
  LrvdOptions power;
  power.weighted = true;
  const DualMesh dual = compute_dual(compute_lrvd(r.mesh, r.samples, power), r.mesh, r.samples);
  const RemeshVerification check = verify_remesh(input, dual.positions, dual.triangles, r.samples.size());
  INFO(check.summary());
  return check.passed;
}

bool on_a_mesh_edge(const Vec3& b) { return b.x == 0 || b.y == 0 || b.z == 0; }

}  // namespace

TEST_CASE("MPS samples a cube's edges and corners first by default: no two samples closer than r, a valid LRRT",
          "[mps][features]") {
  const SurfaceMesh cube = unit_cube();
  for (bool adaptive : {false, true})
    for (std::uint64_t seed : {1, 2}) {
      INFO((adaptive ? "adaptive" : "uniform") << ", seed " << seed);
      MpsOptions options;  // the defaults but for these
      options.radius = 0.1;
      options.adaptive = adaptive;
      options.seed = seed;
      const MpsResult r = maximal_poisson_disk_sampling(cube, options);
      CHECK(r.feature_edges == 12);
      CHECK(r.boundary_edges == 0);
      CHECK(r.feature_corners == 8);
      REQUIRE(r.feature_samples > 8);
      for (int i = 0; i < r.feature_samples; ++i) CHECK(on_a_mesh_edge(r.samples.barycentric[i]));
      CHECK(close_pairs(r.samples.positions, r.samples.weights) == 0);
      const MpsVerification v = verify_mps(r.mesh, r.samples);
      INFO(v.summary());
      CHECK(v.passed);
      CHECK(lrrt_valid(cube, r));

      // Off: the same feature lines counted, none sampled first; darts from the first sample on.
      options.sample_features = false;
      const MpsResult off = maximal_poisson_disk_sampling(cube, options);
      CHECK(off.feature_edges == 12);
      CHECK(off.feature_corners == 8);
      CHECK(off.feature_samples == 0);
      CHECK(!on_a_mesh_edge(off.samples.barycentric[0]));
    }
}

TEST_CASE("MPS samples an open sheet's boundary first by default", "[mps][features]") {
  // The unit square of 3 x 3 quads: 12 boundary edges, flat inside. Each side is a line from corner
  // to corner; its samples are spread evenly, neighbours less than sqrt(2) r apart.
  const SurfaceMesh sheet = test::grid(3, 3);
  MpsOptions options;
  options.radius = 0.08;
  const MpsResult r = maximal_poisson_disk_sampling(sheet, options);
  CHECK(r.feature_edges == 12);
  CHECK(r.boundary_edges == 12);
  CHECK(r.feature_corners == 4);
  REQUIRE(r.feature_samples > 4);
  const double radius = r.radius;
  // Per side (x = 0, x = 1, y = 0, y = 1): the coordinate along it of each feature sample there.
  std::vector<double> along[4];
  for (int i = 0; i < r.feature_samples; ++i) {
    const Vec3& p = r.samples.positions[i];
    const double to_side[4] = {p.x, 1 - p.x, p.y, 1 - p.y};
    int sides = 0;
    for (int s = 0; s < 4; ++s)
      if (std::abs(to_side[s]) < 1e-15) {
        along[s].push_back(s < 2 ? p.y : p.x);
        ++sides;
      }
    INFO("feature sample " << i << " at " << p.x << " " << p.y);
    CHECK(sides >= 1);  // on the boundary
  }
  for (std::vector<double>& side : along) {
    std::sort(side.begin(), side.end());
    REQUIRE(side.size() >= 2);
    CHECK(side.front() == 0);
    CHECK(side.back() == 1);
    for (size_t k = 1; k < side.size(); ++k) {
      CHECK(side[k] - side[k - 1] >= radius);
      CHECK(side[k] - side[k - 1] < std::sqrt(2.0) * radius);
    }
  }
  const MpsVerification v = verify_mps(r.mesh, r.samples);
  INFO(v.summary());
  CHECK(v.passed);
  CHECK(lrrt_valid(sheet, r));
}

TEST_CASE("MPS of a mesh without feature lines is the same with the features on or off", "[mps][features]") {
  const SurfaceMesh sphere = test::icosphere(3);
  for (bool adaptive : {false, true}) {
    INFO((adaptive ? "adaptive" : "uniform"));
    MpsOptions options;
    options.radius = 0.05;
    options.adaptive = adaptive;
    const MpsResult on = maximal_poisson_disk_sampling(sphere, options);
    options.sample_features = false;
    const MpsResult off = maximal_poisson_disk_sampling(sphere, options);
    CHECK(on.feature_edges == 0);
    CHECK(on.feature_corners == 0);
    CHECK(on.feature_samples == 0);
    REQUIRE(on.samples.size() == off.samples.size());
    for (int i = 0; i < on.samples.size(); ++i) {
      REQUIRE(on.samples.positions[i] == off.samples.positions[i]);
      REQUIRE(on.samples.weights[i] == off.samples.weights[i]);
    }
  }
}

namespace {

struct CliRun {
  int status = -1;
  std::string console;
  nlohmann::json report;
};

// `lrvd mps ARGS --report ...`, its exit status, its standard output and its report (null when it
// wrote none).
CliRun run_mps_cli(const std::string& dir, const std::string& args) {
  const std::string report = dir + "report.json", console = dir + "console.txt";
  std::remove(report.c_str());
  const int raw =
      std::system((std::string(LRVD_CLI_PATH) + " mps " + args + " --report " + report + " > " + console + " 2>&1").c_str());
  CliRun run;
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream said(console);
  run.console.assign(std::istreambuf_iterator<char>(said), std::istreambuf_iterator<char>());
  std::ifstream in(report);
  if (in.good()) run.report = nlohmann::json::parse(in);
  return run;
}

}  // namespace

TEST_CASE("lrvd mps samples the features first without being asked, says so, and --no-features turns it off",
          "[mps][features][cli]") {
  const std::string dir = std::string(LRVD_BINARY_DIR) + "/test_mps_features_";
  const std::string cube = dir + "cube.off";
  write_mesh(cube, unit_cube());

  // No flag: the cube's edges and corners first, no two samples closer than r, a valid LRRT.
  const CliRun on = run_mps_cli(dir, cube + " --radius 0.1 --seed 1 -o " + dir + "on.xyz --remesh " + dir + "on.off");
  INFO(on.console);
  CHECK(on.status == 0);
  REQUIRE(on.report.is_object());
  const nlohmann::json& f = on.report["features"];
  CHECK(f["on"].get<bool>());
  CHECK(f["sampled"].get<bool>());
  CHECK(f["angle_deg"].get<double>() == 60);
  CHECK(f["edges"].get<int>() == 12);
  CHECK(f["boundary_edges"].get<int>() == 0);
  CHECK(f["corners"].get<int>() == 8);
  const int feature_samples = f["samples"].get<int>();
  CHECK(feature_samples > 8);
  CHECK(on.console.find("features: 12 edges where the surface turns by more than 60 degrees, 8 corners: sampled first (" +
                        std::to_string(feature_samples) + " samples; --no-features turns this off)\n") !=
        std::string::npos);
  CHECK(on.report["mps_verification"]["passed"].get<bool>());
  CHECK(on.report["remesh"]["valid"].get<bool>());
  const PointFile samples = read_xyz(dir + "on.xyz");
  CHECK(close_pairs(samples.points, samples.weights) == 0);
  // --features is still accepted: the same samples.
  CHECK(run_mps_cli(dir, cube + " --radius 0.1 --seed 1 --features -o " + dir + "flag.xyz").status == 0);
  CHECK(read_xyz(dir + "flag.xyz").points == samples.points);

  // --no-features: the samples of the darts alone, the feature lines still counted and said.
  const CliRun off = run_mps_cli(dir, cube + " --radius 0.1 --seed 1 --no-features -o " + dir + "off.xyz");
  INFO(off.console);
  CHECK(off.status == 0);
  REQUIRE(off.report.is_object());
  CHECK(!off.report["features"]["on"].get<bool>());
  CHECK(!off.report["features"]["sampled"].get<bool>());
  CHECK(off.report["features"]["samples"].get<int>() == 0);
  CHECK(off.report["features"]["edges"].get<int>() == 12);
  CHECK(off.console.find("8 corners: not sampled first (--no-features)\n") != std::string::npos);
  MpsOptions darts_only;
  darts_only.radius = 0.1;
  darts_only.sample_features = false;
  CHECK(read_xyz(dir + "off.xyz").points == maximal_poisson_disk_sampling(unit_cube(), darts_only).samples.positions);

  // A mesh without feature lines: nothing said, the report says none were sampled.
  const std::string sphere = dir + "sphere.off";
  write_mesh(sphere, test::icosphere(2));
  const CliRun smooth = run_mps_cli(dir, sphere + " --radius 0.1 -o " + dir + "sphere.xyz");
  CHECK(smooth.status == 0);
  REQUIRE(smooth.report.is_object());
  CHECK(smooth.report["features"]["on"].get<bool>());
  CHECK(!smooth.report["features"]["sampled"].get<bool>());
  CHECK(smooth.report["features"]["edges"].get<int>() == 0);
  CHECK(smooth.console.find("features:") == std::string::npos);

  // Options that contradict each other.
  CHECK(run_mps_cli(dir, cube + " --radius 0.1 --features --no-features -o " + dir + "bad.xyz").status == 2);
  CHECK(run_mps_cli(dir, cube + " --radius 0.1 --no-features --feature-angle 45 -o " + dir + "bad.xyz").status == 2);
}
