// The scenes `lrvd render` draws: a mesh, a diagram's cells with their stray pieces hatched, and a
// mesh coloured by triangle quality or by the remesh checks its triangles fail.
#include "render/render_scenes.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "common/error.h"
#include "diagram/cells_output.h"
#include "diagram/diagram.h"
#include "io/mesh_writers.h"
#include "mesh/self_intersections.h"
#include "mesh/surface_mesh.h"
#include "metrics/quality.h"
#include "samples/samples.h"

namespace lrvd {

RenderScene mesh_scene(const SurfaceMesh& mesh) {
  RenderScene scene;
  scene.positions = mesh.positions();
  scene.triangles.reserve(mesh.triangle_count());
  for (const auto& t : mesh.triangles()) scene.triangles.push_back({t[0], t[1], t[2]});
  return scene;
}

RenderScene mesh_scene(const std::vector<Vec3>& positions, const std::vector<std::array<int, 3>>& triangles) {
  RenderScene scene;
  scene.positions = positions;
  scene.triangles = triangles;
  return scene;
}

Rgb quality_color(double q) {
  struct Stop {
    double q;
    double rgb[3];
  };
  static const Stop stops[] = {{0.0, {150, 0, 30}},   {0.3, {215, 48, 39}},   {0.5, {250, 150, 80}},
                               {0.7, {254, 230, 150}}, {0.9, {220, 225, 232}}, {1.0, {220, 225, 232}}};
  q = std::isfinite(q) ? std::clamp(q, 0.0, 1.0) : 0.0;
  int k = 0;
  while (k + 2 < static_cast<int>(std::size(stops)) && q > stops[k + 1].q) ++k;
  const double f = (q - stops[k].q) / (stops[k + 1].q - stops[k].q);
  Rgb out;
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<unsigned char>(std::lround(stops[k].rgb[c] + f * (stops[k + 1].rgb[c] - stops[k].rgb[c])));
  return out;
}

double color_by_quality(RenderScene& scene) {
  check_render_scene(scene);
  // Q does not depend on the scale; measured on the scene brought to about unit size, so that the
  // areas and lengths of a model 1e100 or 1e-100 across neither overflow nor vanish.
  double extent = 0;
  for (const auto& tri : scene.triangles)
    for (int v : tri)
      for (int c = 0; c < 3; ++c) extent = std::max(extent, std::abs(scene.positions[v][c] - scene.positions[tri[0]][c]));
  const double to_unit = extent > 0 && std::isfinite(1 / extent) ? 1 / extent : 1;
  double worst = 1;
  scene.color.resize(scene.triangles.size());
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const auto& tri = scene.triangles[t];
    const Vec3& o = scene.positions[tri[0]];
    const double q = triangle_quality(Vec3{}, (scene.positions[tri[1]] - o) * to_unit, (scene.positions[tri[2]] - o) * to_unit);
    scene.color[t] = quality_color(q);
    worst = std::min(worst, std::isfinite(q) ? q : 0.0);
  }
  return worst;
}

DiagramScene diagram_scene(const Diagram& diagram, const SurfaceMesh& mesh, const Samples& samples) {
  if (samples.size() != diagram.sample_count)
    throw InputError(fmt::format("render: {} samples for a diagram of {}", samples.size(), diagram.sample_count));
  const PolygonMesh cells = diagram_polygon_mesh(diagram, mesh);
  const CellComponents components = cell_components(diagram, mesh);

  // The piece of each cell that holds its sample: its polygon in the sample's triangle.
  const int n = diagram.sample_count;
  std::vector<int> own(n, -1);
  for (int i = 0; i < n; ++i) {
    const int t = samples.triangles[i];
    if (t < 0 || t >= mesh.triangle_count()) continue;
    for (int p = diagram.triangle_offsets[t]; p < diagram.triangle_offsets[t + 1]; ++p)
      if (diagram.polygons[p].cell == i) own[i] = components.polygon_component[p];
  }

  DiagramScene out;
  for (int c : components.count) out.cells_in_pieces += c > 1;
  RenderScene& scene = out.scene;
  scene.positions = cells.positions;
  for (std::size_t p = 0; p < cells.faces.size(); ++p) {
    const std::vector<int>& face = cells.faces[p];
    const int cell = cells.face_cell[p], piece = components.polygon_component[p];
    const bool stray = piece >= 0 && components.count[cell] > 1 && piece != own[cell];
    out.stray_polygons += stray;
    for (std::size_t a = 1; a + 1 < face.size(); ++a) {
      scene.triangles.push_back({face[0], face[a], face[a + 1]});
      scene.color.push_back(cells.face_color[p]);
      scene.region.push_back(cell);
      scene.hatched.push_back(stray);
      scene.face.push_back(diagram.polygons[p].triangle);
    }
  }
  scene.points = samples.positions;
  return out;
}

MeshDefectCounts color_by_defects(RenderScene& scene) {
  check_render_scene(scene);
  const std::size_t nt = scene.triangles.size();
  std::vector<Triangle> triangles(scene.triangles.begin(), scene.triangles.end());
  const std::vector<char> proper = proper_triangles(scene.positions, triangles);
  // Triangles per undirected edge, from the sorted list of (edge, triangle).
  std::vector<std::pair<std::pair<int, int>, int>> edges;
  edges.reserve(3 * nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const std::size_t first = edges.size();
    for (int e = 0; e < 3; ++e) {
      const int a = triangles[t][e], b = triangles[t][(e + 1) % 3];
      const std::pair<int, int> edge{std::min(a, b), std::max(a, b)};
      // A triangle that repeats a corner has one edge twice: it is on that edge once.
      bool listed = a == b;
      for (std::size_t k = first; k < edges.size(); ++k) listed |= edges[k].first == edge;
      if (!listed) edges.push_back({edge, static_cast<int>(t)});
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<char> non_manifold(nt, 0), boundary(nt, 0), crossing(nt, 0);
  for (std::size_t i = 0, j = 0; i < edges.size(); i = j) {
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    for (std::size_t k = i; k < j; ++k) {
      if (j - i >= 3) non_manifold[edges[k].second] = 1;
      if (j - i == 1) boundary[edges[k].second] = 1;
    }
  }
  for (const auto& [f, g] : find_self_intersections(scene.positions, triangles, proper)) crossing[f] = crossing[g] = 1;
  // Triangles on the same three corners, which share every edge with each other: repeated.
  std::vector<std::pair<Triangle, int>> corners(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    corners[t] = {triangles[t], static_cast<int>(t)};
    std::sort(corners[t].first.begin(), corners[t].first.end());
  }
  std::sort(corners.begin(), corners.end());
  for (std::size_t k = 1; k < nt; ++k)
    if (corners[k].first == corners[k - 1].first && proper[corners[k].second])
      non_manifold[corners[k].second] = non_manifold[corners[k - 1].second] = 1;

  MeshDefectCounts counts;
  // Vertices no triangle uses (a remesh's samples whose cells made no triangle) as dots.
  std::vector<char> used(scene.positions.size(), 0);
  for (const Triangle& t : triangles)
    for (int v : t) used[v] = 1;
  scene.points.clear();
  for (std::size_t v = 0; v < used.size(); ++v)
    if (!used[v]) scene.points.push_back(scene.positions[v]);
  counts.unused_vertices = static_cast<int>(scene.points.size());
  scene.color.assign(nt, kRenderGrey);
  for (std::size_t t = 0; t < nt; ++t) {
    counts.degenerate += !proper[t];
    counts.non_manifold += non_manifold[t];
    counts.crossing += crossing[t];
    counts.boundary += boundary[t];
    if (!proper[t]) scene.color[t] = {120, 0, 20};
    else if (non_manifold[t]) scene.color[t] = {225, 30, 30};
    else if (crossing[t]) scene.color[t] = {250, 140, 0};
    else if (boundary[t]) scene.color[t] = {60, 110, 230};
  }
  return counts;
}

}  // namespace lrvd
