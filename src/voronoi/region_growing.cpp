// Paper §3.2: the cell-to-vertex assignment by region growing.
#include "voronoi/region_growing.h"

#include <algorithm>
#include <functional>

namespace lrvd::detail {

void assign_vertices_to_cells(const SurfaceMesh& mesh, const Samples& samples, const std::vector<Site>& sites,
                              RegionGrowingWorkspace& work, std::vector<int>& vertex_label) {
  auto power_distance = [&](const Vec3& q, int i) { return squared_distance(q, sites[i].p) - sites[i].w; };
  const int nv = mesh.vertex_count();
  // A vertex goes to the least (power distance, sample) that reaches it; an entry that cannot
  // be that least one is never queued.
  using Entry = VertexEntry;
  work.claims.assign(nv, VertexClaim{});
  work.heap.clear();
  work.seeds.clear();
  // The least entry queued for v so far is (power distance to best_sample, best_sample): the
  // distance is computed again rather than kept, which halves the records the growth misses on.
  auto better = [&](double d, int i, int v) {
    VertexClaim& c = work.claims[v];
    if (c.best_sample >= 0) {
      const double best = power_distance(mesh.position(v), c.best_sample);
      if (d > best || (d == best && i >= c.best_sample)) return false;
    }
    c.best_sample = i;
    return true;
  };
  // The samples' own corners are most of the entries on a dense sampling (MPS): they are sorted
  // once and merged with the heap of the entries the growth adds, which stays small.
  for (int i = 0; i < samples.size(); ++i)
    for (int v : mesh.triangle(samples.triangles[i])) {
      const double d = power_distance(mesh.position(v), i);
      if (better(d, i, v)) work.seeds.emplace_back(d, i, v);
    }
  std::sort(work.seeds.begin(), work.seeds.end(), [](const Entry& a, const Entry& b) { return b > a; });
  size_t next_seed = 0;
  auto seed_first = [&] { return work.heap.empty() || (next_seed < work.seeds.size() && work.heap.front() > work.seeds[next_seed]); };
  while (next_seed < work.seeds.size() || !work.heap.empty()) {
    Entry top;
    if (seed_first()) {
      top = work.seeds[next_seed++];
    } else {
      std::pop_heap(work.heap.begin(), work.heap.end(), std::greater<Entry>());
      top = work.heap.back();
      work.heap.pop_back();
    }
    if (work.claims[top.vertex()].label >= 0) continue;
    work.claims[top.vertex()].label = top.sample();
    // On a large mesh the growth waits on memory: the entries come from all over the mesh. While
    // this vertex is handled, load what the likely next ones will read: the claims and
    // positions of the next entry's neighbours, and the neighbour lists of the entries after it
    // (the heap's two children of its front, the next seed). Only loads: the order is the same.
    if (next_seed < work.seeds.size() || !work.heap.empty()) {
      const int next = seed_first() ? work.seeds[next_seed].vertex() : work.heap.front().vertex();
      for (const int* u = mesh.vertex_neighbors_begin(next); u != mesh.vertex_neighbors_end(next); ++u) {
        __builtin_prefetch(&work.claims[*u]);
        __builtin_prefetch(&mesh.position(*u));
      }
      for (size_t c = 1; c <= 2 && c < work.heap.size(); ++c) __builtin_prefetch(mesh.vertex_neighbors_begin(work.heap[c].vertex()));
      if (next_seed + 1 < work.seeds.size()) __builtin_prefetch(mesh.vertex_neighbors_begin(work.seeds[next_seed + 1].vertex()));
    }
    const int grower = top.sample();
    for (const int* u = mesh.vertex_neighbors_begin(top.vertex()); u != mesh.vertex_neighbors_end(top.vertex()); ++u)
      if (work.claims[*u].label < 0) {
        const double d = power_distance(mesh.position(*u), grower);
        if (!better(d, grower, *u)) continue;
        work.heap.emplace_back(d, grower, *u);
        std::push_heap(work.heap.begin(), work.heap.end(), std::greater<Entry>());
      }
  }
  vertex_label.resize(nv);
  for (int v = 0; v < nv; ++v) vertex_label[v] = work.claims[v].label;
}

}  // namespace lrvd::detail
