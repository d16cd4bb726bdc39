// The LRPD of maximal Poisson-disk sampling on the part of the mesh around a few triangles: the
// later gap rounds look only at the triangles that may still hold a gap, and a diagram of the
// whole mesh for a handful of them costs as much as the first one.
#include "mps/mps_lrpd_part.h"

#include <algorithm>
#include <cmath>

#include "voronoi/lrvd.h"

namespace lrvd::mps_detail {

namespace {

// The part reaches this many times the largest radius around each triangle asked for.
constexpr double kPartReach = 4;

// Adds to `in_part` the whole star of every vertex at which the part's triangles would form more
// than one fan (a SurfaceMesh has one fan per vertex), until there is none; `part` lists them.
void close_pinches(const SurfaceMesh& mesh, std::vector<char>& in_part, std::vector<int>& part) {
  std::vector<int> todo;
  for (int t : part)
    for (int v : mesh.triangle(t)) todo.push_back(v);
  while (!todo.empty()) {
    const int v = todo.back();
    todo.pop_back();
    // Fans = part triangles at v minus the part edges they share at v (each shared edge joins two).
    int triangles = 0, shared = 0;
    for (const int* s = mesh.vertex_triangles_begin(v); s != mesh.vertex_triangles_end(v); ++s) {
      if (!in_part[*s]) continue;
      ++triangles;
      const Triangle& tri = mesh.triangle(*s);
      for (int e = 0; e < 3; ++e) {
        if (tri[e] != v && tri[(e + 1) % 3] != v) continue;
        const int across = mesh.neighbor(*s, e);
        shared += across >= 0 && in_part[across];
      }
    }
    if (triangles - shared / 2 <= 1) continue;
    for (const int* s = mesh.vertex_triangles_begin(v); s != mesh.vertex_triangles_end(v); ++s) {
      if (in_part[*s]) continue;
      in_part[*s] = 1;
      part.push_back(*s);
      for (int u : mesh.triangle(*s)) todo.push_back(u);
    }
  }
}

}  // namespace

bool compute_lrpd_around(const SurfaceMesh& mesh, DiskIndex& disks, const std::vector<int>& triangles,
                         const std::vector<char>& shaped, GapLrpd& out) {
  const int limit = mesh.triangle_count() / 4;
  double largest = 0;  // of all disks, for a triangle no disk reaches
  for (int i = 0; i < disks.size(); ++i) largest = std::max(largest, disks.weight(i));
  std::vector<char> in_part(mesh.triangle_count(), 0);
  std::vector<int> part;
  for (int t : triangles) {
    double w = 0;
    disks.for_each_disk(t, [&](int j) { w = std::max(w, disks.weight(j)); });
    disks.for_each_center(t, [&](int j) { w = std::max(w, disks.weight(j)); });
    if (w == 0) w = largest;
    const double reach = kPartReach * std::sqrt(w) + disks.triangle_radius(t);
    for (int s : disks.met(disks.triangle_center(t), t, reach * reach)) {
      if (in_part[s]) continue;
      in_part[s] = 1;
      part.push_back(s);
    }
    if (static_cast<int>(part.size()) > limit) return false;
  }
  close_pinches(mesh, in_part, part);
  if (static_cast<int>(part.size()) > limit) return false;
  std::sort(part.begin(), part.end());

  // The part as a mesh: its vertices numbered in order of first use.
  std::vector<int> vertex_in_part(mesh.vertex_count(), -1);
  std::vector<Vec3> positions;
  std::vector<Triangle> part_triangles;
  part_triangles.reserve(part.size());
  for (int t : part) {
    Triangle tri = mesh.triangle(t);
    for (int& v : tri) {
      if (vertex_in_part[v] < 0) {
        vertex_in_part[v] = static_cast<int>(positions.size());
        positions.push_back(mesh.position(v));
      }
      v = vertex_in_part[v];
    }
    part_triangles.push_back(tri);
  }
  SurfaceMesh part_mesh(std::move(positions), std::move(part_triangles));
  std::vector<int> triangle_in_part(mesh.triangle_count(), -1);
  for (int k = 0; k < static_cast<int>(part.size()); ++k) triangle_in_part[part[k]] = k;

  Samples samples;
  std::vector<int> sample_of;
  std::vector<char> sampled(part_mesh.component_count(), 0);
  for (int i = 0; i < disks.size(); ++i) {
    const int t = triangle_in_part[disks.triangle(i)];
    if (t < 0) continue;
    samples.positions.push_back(disks.center(i));
    samples.weights.push_back(disks.weight(i));
    samples.triangles.push_back(t);
    samples.barycentric.push_back(disks.barycentric(i));
    sample_of.push_back(i);
    sampled[part_mesh.triangle_components()[t]] = 1;
  }
  if (std::find(sampled.begin(), sampled.end(), 0) != sampled.end()) return false;

  std::vector<char> shapeless(part.size());
  for (size_t k = 0; k < part.size(); ++k) shapeless[k] = !shaped[part[k]];
  LrvdOptions options;
  options.weighted = true;
  options.shapeless = &shapeless;
  out.diagram = compute_lrvd(part_mesh, samples, options);
  out.on_part = true;
  out.part = std::move(part_mesh);
  out.triangle_of = std::move(part);
  out.sample_of = std::move(sample_of);
  return true;
}

}  // namespace lrvd::mps_detail
