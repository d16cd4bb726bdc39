// The renderer behind `lrvd render`: framing, the side the camera looks from, outlines between
// regions and none inside one, hatching, hidden samples, the diagrams' stray pieces, PNG output.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <string>

#include <unistd.h>

#include "common/error.h"
#include "diagram/cells_output.h"
#include "io/mesh_io.h"
#include "io/mesh_writers.h"
#include "mesh/stress.h"
#include "metrics/quality.h"
#include "render/render.h"
#include "render/render_scenes.h"
#include "test_meshes.h"
#include "voronoi/lrvd.h"
#include "voronoi/rvd.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

using namespace lrvd;

namespace {

bool white(const Image& image, int x, int y) {
  const Rgb p = image.pixel(x, y);
  return p[0] == 255 && p[1] == 255 && p[2] == 255;
}

int brightness(const Image& image, int x, int y) {
  const Rgb p = image.pixel(x, y);
  return p[0] + p[1] + p[2];
}

// Bounding box of the pixels that are not background: x0, y0, x1, y1 (inclusive).
std::array<int, 4> drawn_box(const Image& image) {
  std::array<int, 4> box = {image.width, image.height, -1, -1};
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (!white(image, x, y)) {
        box[0] = std::min(box[0], x), box[1] = std::min(box[1], y);
        box[2] = std::max(box[2], x), box[3] = std::max(box[3], y);
      }
  return box;
}

// Two triangles making the unit square in the z = 0 plane, split along its diagonal (0,0)-(1,1).
RenderScene square(bool two_regions) {
  RenderScene s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  s.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.region = {0, two_regions ? 1 : 0};
  return s;
}

// The view straight down the z axis onto the square (y up, camera on +z).
RenderOptions front(int size) {
  RenderOptions o;
  o.width = o.height = size;
  o.azimuth = 0;
  o.elevation = 0;
  return o;
}

// The darkest pixel on the square's diagonal, away from its corners and border.
int darkest_on_diagonal(const Image& image) {
  int darkest = 3 * 255;
  for (int k = image.width / 4; k < 3 * image.width / 4; ++k)
    darkest = std::min(darkest, brightness(image, k, image.height - 1 - k));
  return darkest;
}

}  // namespace

TEST_CASE("render frames the scene: it fills the picture but for the margin, and is centred", "[render]") {
  const RenderScene scene = mesh_scene(test::icosphere(3));
  RenderOptions o;
  o.width = 300;
  o.height = 200;
  const Image image = render(scene, o);
  REQUIRE(image.width == 300);
  REQUIRE(image.height == 200);
  REQUIRE(!white(image, 150, 100));
  REQUIRE(white(image, 2, 2));
  const auto box = drawn_box(image);
  const int tall = box[3] - box[1] + 1, wide = box[2] - box[0] + 1;
  // A sphere seen from anywhere is a disc: the height limits it, 92 % of 200 pixels.
  REQUIRE(std::abs(tall - 184) <= 3);
  REQUIRE(std::abs(wide - tall) <= 3);
  REQUIRE(std::abs((box[0] + box[2]) / 2 - 150) <= 2);
  REQUIRE(std::abs((box[1] + box[3]) / 2 - 100) <= 2);
}

TEST_CASE("render looks from the azimuth and elevation it is given, about the up axis", "[render]") {
  // A box 4 long in x, 1 in y and z: from +z (azimuth 0, up y) it is wide; from +x (azimuth 90) square.
  RenderScene scene;
  scene.positions = {{0, 0, 0}, {4, 0, 0}, {4, 1, 0}, {0, 1, 0}, {0, 0, 1}, {4, 0, 1}, {4, 1, 1}, {0, 1, 1}};
  scene.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                     {2, 3, 7}, {2, 7, 6}, {1, 2, 6}, {1, 6, 5}, {0, 4, 7}, {0, 7, 3}};
  auto aspect = [&](double azimuth, double elevation, int up) {
    RenderOptions o;
    o.width = o.height = 200;
    o.azimuth = azimuth;
    o.elevation = elevation;
    o.up_axis = up;
    const auto box = drawn_box(render(scene, o));
    return double(box[2] - box[0] + 1) / double(box[3] - box[1] + 1);
  };
  REQUIRE(aspect(0, 0, 1) == Approx(4).epsilon(0.05));
  REQUIRE(aspect(90, 0, 1) == Approx(1).epsilon(0.05));
  // Looking straight down the y axis (elevation 90) shows x against z: wide again.
  REQUIRE(aspect(0, 90, 1) == Approx(4).epsilon(0.05));
  // Up z: azimuth 0 looks from +x, where the box's 1 x 1 end is.
  REQUIRE(aspect(0, 0, 2) == Approx(1).epsilon(0.05));
}

TEST_CASE("render draws a dark line between regions and none inside one", "[render]") {
  const Image one = render(square(false), front(200));
  const Image two = render(square(true), front(200));
  REQUIRE(darkest_on_diagonal(two) < 200);
  REQUIRE(darkest_on_diagonal(one) > 450);
  // With edges on, the diagonal of one region shows as a lighter line.
  RenderOptions edges = front(200);
  edges.edges = true;
  const int light = darkest_on_diagonal(render(square(false), edges));
  REQUIRE(light < darkest_on_diagonal(one) - 100);
  REQUIRE(light > darkest_on_diagonal(two) + 100);
}

TEST_CASE("render stripes hatched triangles and leaves the others plain", "[render]") {
  RenderScene scene = square(false);
  scene.hatched = {1, 0};  // the lower right triangle
  const Image image = render(scene, front(200));
  int lo = 3 * 255, hi = 0;
  for (int x = 120; x < 180; ++x) {  // a row inside the hatched triangle, x > y on the picture
    lo = std::min(lo, brightness(image, x, 170));
    hi = std::max(hi, brightness(image, x, 170));
  }
  REQUIRE(hi - lo > 150);
  lo = 3 * 255, hi = 0;
  for (int x = 20; x < 80; ++x) {  // inside the plain one
    lo = std::min(lo, brightness(image, x, 30));
    hi = std::max(hi, brightness(image, x, 30));
  }
  REQUIRE(hi - lo < 4);
}

TEST_CASE("render draws the points the surface does not hide", "[render]") {
  RenderScene scene = mesh_scene(test::icosphere(3));
  RenderOptions o = front(200);
  o.point_radius = 4;
  const Image bare = render(scene, o);
  scene.points = {{0, 0, -1}};  // behind the sphere, at the picture's middle
  REQUIRE(render(scene, o).rgb == bare.rgb);
  scene.points = {{0, 0, 1}};  // in front
  const Image dot = render(scene, o);
  REQUIRE(brightness(dot, 100, 100) < 100);
  REQUIRE(brightness(bare, 100, 100) > 300);
}

TEST_CASE("render hatches the RVD's stray cell pieces and finds none in the LRVD", "[render]") {
  const SurfaceMesh mesh = make_stress_mesh("folded_sheet", 0.5);
  const Samples samples = sample_uniform(mesh, 60, 4);
  const DiagramScene rvd = diagram_scene(compute_rvd(mesh, samples), mesh, samples);
  const DiagramScene lrvd = diagram_scene(compute_lrvd(mesh, samples), mesh, samples);
  REQUIRE(rvd.cells_in_pieces > 0);
  REQUIRE(rvd.stray_polygons > 0);
  REQUIRE(lrvd.cells_in_pieces == 0);
  REQUIRE(lrvd.stray_polygons == 0);
  REQUIRE(lrvd.scene.points.size() == 60);
  REQUIRE(lrvd.scene.region.size() == lrvd.scene.triangles.size());
  std::set<std::pair<int, Rgb>> cell_colours;
  for (std::size_t t = 0; t < lrvd.scene.triangles.size(); ++t) cell_colours.insert({lrvd.scene.region[t], lrvd.scene.color[t]});
  REQUIRE(cell_colours.size() == 60);  // one colour a cell
}

TEST_CASE("write_png writes a PNG that reads back pixel for pixel", "[render]") {
  const Image image = render(square(true), front(64));
  const std::string path = "test_render_" + std::to_string(getpid()) + ".png";
  write_png(path, image);
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 3);
  REQUIRE(data != nullptr);
  REQUIRE(w == 64);
  REQUIRE(h == 64);
  const bool same = std::equal(image.rgb.begin(), image.rgb.end(), data);
  stbi_image_free(data);
  std::remove(path.c_str());
  REQUIRE(same);
  REQUIRE_THROWS_AS(write_png("/nonexistent-folder/x.png", image), InputError);
}

TEST_CASE("render refuses options out of range and scenes that do not hold together", "[render]") {
  const RenderScene scene = square(false);
  RenderOptions o;
  o.width = 8;
  REQUIRE_THROWS_AS(render(scene, o), InputError);
  o = RenderOptions{};
  o.elevation = 91;
  REQUIRE_THROWS_AS(render(scene, o), InputError);
  o = RenderOptions{};
  o.supersample = 0;
  REQUIRE_THROWS_AS(render(scene, o), InputError);
  RenderScene bad = scene;
  bad.triangles.push_back({0, 1, 7});
  REQUIRE_THROWS_WITH(render(bad), Catch::Contains("triangle 2 has vertex 7"));
  bad = scene;
  bad.color = {Rgb{1, 2, 3}};
  REQUIRE_THROWS_WITH(render(bad), Catch::Contains("1 colours for 2 triangles"));
  bad = scene;
  bad.positions[0].x = std::numeric_limits<double>::quiet_NaN();
  REQUIRE_THROWS_AS(render(bad), InputError);
  REQUIRE_THROWS_AS(render(RenderScene{}), InputError);
}

TEST_CASE("render colours triangles by quality: red where they are bad, grey where they are good", "[render]") {
  REQUIRE(quality_color(1.0) == quality_color(0.95));
  REQUIRE(quality_color(0.3) == Rgb{215, 48, 39});
  REQUIRE(quality_color(-1) == quality_color(0));
  REQUIRE(quality_color(std::numeric_limits<double>::quiet_NaN()) == quality_color(0));
  // Redder (less green) as Q falls to 0.7.
  for (double q = 0.05; q <= 0.7; q += 0.05) REQUIRE(quality_color(q)[1] >= quality_color(q - 0.05)[1]);
  RenderScene scene;
  scene.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}, {0, 0, 1}, {10, 0, 1}, {5, 0.1, 1}};
  scene.triangles = {{0, 1, 2}, {3, 4, 5}};
  const double worst = color_by_quality(scene);
  REQUIRE(worst < 0.1);
  REQUIRE(worst == Approx(triangle_quality(scene.positions[3], scene.positions[4], scene.positions[5])));
  REQUIRE(scene.color[0] == quality_color(1.0));
  REQUIRE(scene.color[1] == quality_color(worst));
}

TEST_CASE("render refuses a scene too large or too small to draw in doubles", "[render]") {
  RenderScene scene = square(false);
  for (Vec3& p : scene.positions) p = p * 1e308;
  scene.positions[0] = {-1e308, -1e308, 0};
  REQUIRE_THROWS_WITH(render(scene), Catch::Contains("too large"));
  scene = square(false);
  for (Vec3& p : scene.positions) p = p * 1e-320;
  REQUIRE_THROWS_WITH(render(scene), Catch::Contains("too small"));
}

TEST_CASE("render draws a flat sheet seen edge-on as a line, and takes any azimuth", "[render]") {
  RenderOptions o = front(100);
  o.up_axis = 2;  // up z, azimuth 0 looks from +x: along the square's plane
  const auto box = drawn_box(render(square(false), o));
  REQUIRE(box[2] - box[0] > 80);  // the whole width
  REQUIRE(box[3] - box[1] <= 3);  // one line
  o = front(100);
  o.azimuth = 1e308;  // reduced modulo 360 before it turns into radians
  REQUIRE(drawn_box(render(square(false), o))[2] > 0);
}

TEST_CASE("render leaves out dots and region lines that would cover the surface", "[render]") {
  // 10,000 regions and points on a 100 x 100 picture: a pixel each.
  RenderScene scene;
  const int n = 100;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) scene.positions.push_back({double(i) / n, double(j) / n, 0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      scene.triangles.push_back({a, a + 1, a + n + 2});
      scene.triangles.push_back({a, a + n + 2, a + n + 1});
      scene.region.push_back(j * n + i);
      scene.region.push_back(j * n + i);
      scene.points.push_back({(i + 0.5) / n, (j + 0.5) / n, 0});
    }
  const Image image = render(scene, front(100));
  int dark = 0;
  for (int y = 10; y < 90; ++y)
    for (int x = 10; x < 90; ++x) dark += brightness(image, x, y) < 300;
  REQUIRE(dark == 0);
}

TEST_CASE("render colours the triangles where a remesh check would fail", "[render]") {
  // An open grid: the triangles on its border, found here edge by edge against every triangle.
  RenderScene grid_scene = mesh_scene(test::grid(4, 4));
  MeshDefectCounts d = color_by_defects(grid_scene);
  int border = 0;
  for (const auto& t : grid_scene.triangles) {
    bool on_border = false;
    for (int e = 0; e < 3; ++e) {
      int uses = 0;
      for (const auto& u : grid_scene.triangles)
        for (int f = 0; f < 3; ++f)
          uses += (t[e] == u[f] && t[(e + 1) % 3] == u[(f + 1) % 3]) || (t[e] == u[(f + 1) % 3] && t[(e + 1) % 3] == u[f]);
      on_border |= uses == 1;
    }
    border += on_border;
  }
  REQUIRE(border == 14);
  REQUIRE(d.boundary == border);
  REQUIRE(d.non_manifold == 0);
  REQUIRE(d.crossing == 0);
  REQUIRE(d.degenerate == 0);

  // A closed octahedron with a third triangle on one of its edges, a collinear one, and a square
  // that cuts through it.
  RenderScene scene = mesh_scene(test::octahedron());
  scene.positions.push_back({2, 2, 2});           // 6
  scene.triangles.push_back({0, 2, 6});           // on edge (0, 2), which two faces have already
  scene.positions.push_back({0.5, 0, 0});         // 7, between vertices 0 and 1
  scene.triangles.push_back({0, 1, 7});           // collinear
  for (const Vec3& p : {Vec3{-2, -2, 0.5}, Vec3{2, -2, 0.5}, Vec3{2, 2, 0.5}}) scene.positions.push_back(p);
  scene.triangles.push_back({8, 9, 10});          // cuts the octahedron's upper half
  d = color_by_defects(scene);
  REQUIRE(d.degenerate == 1);
  REQUIRE(d.non_manifold >= 3);
  REQUIRE(d.crossing >= 2);
  REQUIRE(scene.color[9] == Rgb{120, 0, 20});    // the collinear one
  REQUIRE(scene.color[8] == Rgb{225, 30, 30});   // on the edge of three
  REQUIRE(scene.color[10] == Rgb{250, 140, 0});  // crossing (its edges are used once: crossing wins)

  // A triangle that repeats a corner is on its one edge once; a triangle given twice is repeated.
  RenderScene repeats;
  repeats.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  repeats.triangles = {{0, 1, 2}, {0, 0, 1}};
  d = color_by_defects(repeats);
  REQUIRE(d.degenerate == 1);
  REQUIRE(d.non_manifold == 0);  // edge (0, 1) has two triangles, not three
  REQUIRE(d.boundary == 1);      // (0, 1, 2), by its two other edges
  repeats.triangles = {{0, 1, 3}, {3, 1, 0}};
  d = color_by_defects(repeats);
  REQUIRE(d.non_manifold == 2);  // each edge has the two copies only: repeated
  REQUIRE(repeats.color[0] == Rgb{225, 30, 30});
}

TEST_CASE("render draws a model of any size the same, and measures its quality the same", "[render]") {
  RenderScene base = mesh_scene(test::octahedron());
  base.positions[0].x = 3;  // a less regular shape, so that the worst Q is not 1
  RenderOptions o = front(64);
  const Image reference = render(base, o);
  RenderScene copy = base;
  const double worst = color_by_quality(copy);
  REQUIRE(worst < 0.99);
  for (int e : {-660, -260, 130, 260, 660}) {  // powers of two: the scaled coordinates are exact
    const double s = std::ldexp(1.0, e);
    RenderScene scaled = base;
    for (Vec3& p : scaled.positions) p = p * s;
    INFO(s);
    REQUIRE(render(scaled, o).rgb == reference.rgb);
    REQUIRE(color_by_quality(scaled) == Approx(worst).epsilon(1e-9));
  }
}

TEST_CASE("render shows a degenerate triangle in its colour, and unused vertices as dots", "[render]") {
  RenderScene scene;
  scene.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  scene.triangles = {{0, 1, 2}, {0, 3, 4}};  // collinear, and a proper one
  scene.positions.push_back({2, 1, 0});      // 5: in no triangle
  const MeshDefectCounts d = color_by_defects(scene);
  REQUIRE(d.degenerate == 1);
  REQUIRE(d.unused_vertices == 1);
  REQUIRE(scene.points.size() == 1);
  const Image image = render(scene, front(120));
  int dark_red = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Rgb p = image.pixel(x, y);
      dark_red += p[0] > 90 && p[1] < 40 && p[2] < 60;  // (120, 0, 20), not greyed
    }
  REQUIRE(dark_red > 40);  // a line along the picture's width
  // The unused vertex's dot, at (2, 1): pixel (115, 32) (x 0..2 over 4.8..115.2, y centred).
  REQUIRE(brightness(image, 115, 32) < 150);
}

TEST_CASE("A cells PLY reads back with its face colours, one per triangle of each polygon", "[render]") {
  const SurfaceMesh mesh = test::icosphere(2);
  const Samples samples = sample_uniform(mesh, 12, 3);
  const PolygonMesh cells = diagram_polygon_mesh(compute_lrvd(mesh, samples), mesh);
  const std::string path = "test_render_cells_" + std::to_string(getpid()) + ".ply";
  write_cells_ply(path, cells);
  const PolygonSoup soup = read_polygon_soup(path, false, true);
  REQUIRE(read_polygon_soup(path).face_color.empty());  // only when asked for
  std::remove(path.c_str());
  REQUIRE(soup.face_color.size() == soup.triangles.size());
  // Polygons are fanned in order: a polygon of k corners gives k - 2 triangles in its colour.
  std::size_t t = 0;
  for (std::size_t f = 0; f < cells.faces.size(); ++f)
    for (std::size_t k = 2; k < cells.faces[f].size(); ++k, ++t) {
      INFO("face " << f << ", triangle " << t);
      REQUIRE(t < soup.face_color.size());
      REQUIRE(soup.face_color[t] == cells.face_color[f]);
    }
  REQUIRE(t == soup.triangles.size());
  // An OFF has no face colours.
  const std::string off = "test_render_cells_" + std::to_string(getpid()) + ".off";
  write_mesh(off, mesh);
  REQUIRE(read_polygon_soup(off, false, true).face_color.empty());
  std::remove(off.c_str());
}
