// Local repair rounds: a window of cells round the defects, optimised on the sub-mesh it covers.
#include "remesh/local_repair.h"

#include <algorithm>
#include <chrono>
#include <numeric>

#include "common/error.h"
#include "common/timing.h"
#include "voronoi/lrvd.h"

namespace lrvd {

namespace {

// Cell adjacency of a diagram as sorted neighbour lists: two cells are adjacent when they share a
// diagram vertex.
struct CellAdjacency {
  std::vector<int> offsets, cells;
  explicit CellAdjacency(const Diagram& diagram) {
    std::vector<std::pair<int, int>> pairs;
    for (const SymbolicVertex& q : diagram.vertices)
      for (int a = 0; a < q.num_labels(); ++a)
        for (int b = 0; b < q.num_labels(); ++b) {
          const int i = q.label[a], j = q.label[b];
          if (i >= 0 && j >= 0 && i != j) pairs.push_back({i, j});
        }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    offsets.assign(diagram.sample_count + 1, 0);
    for (const auto& p : pairs) ++offsets[p.first + 1];
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    cells.reserve(pairs.size());
    for (const auto& p : pairs) cells.push_back(p.second);
  }
  const int* begin(int c) const { return cells.data() + offsets[c]; }
  const int* end(int c) const { return cells.data() + offsets[c + 1]; }
};

// Marks every triangle round a vertex where the marked triangles form more than one fan (a
// sub-mesh must be a manifold: one fan per vertex), until no such vertex is left.
void close_pinched_vertices(const SurfaceMesh& mesh, std::vector<char>& marked) {
  std::vector<int> pending;
  std::vector<char> queued(mesh.vertex_count(), 0);
  for (int t = 0; t < mesh.triangle_count(); ++t)
    if (marked[t])
      for (int v : mesh.triangle(t))
        if (!queued[v]) queued[v] = 1, pending.push_back(v);
  std::vector<int> around, parent;
  while (!pending.empty()) {
    const int v = pending.back();
    pending.pop_back();
    queued[v] = 0;
    around.clear();
    for (const int* t = mesh.vertex_triangles_begin(v); t != mesh.vertex_triangles_end(v); ++t)
      if (marked[*t]) around.push_back(*t);
    std::sort(around.begin(), around.end());
    parent.resize(around.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    int fans = static_cast<int>(around.size());
    for (size_t a = 0; a < around.size(); ++a)
      for (int e = 0; e < 3; ++e) {
        const Triangle& tri = mesh.triangle(around[a]);
        if (tri[e] != v && tri[(e + 1) % 3] != v) continue;  // only edges through v join fans at v
        const int across = mesh.neighbor(around[a], e);
        const auto it = std::lower_bound(around.begin(), around.end(), across);
        if (across < 0 || it == around.end() || *it != across) continue;
        const int x = find(static_cast<int>(a)), y = find(static_cast<int>(it - around.begin()));
        if (x != y) parent[x] = y, --fans;
      }
    if (fans <= 1) continue;
    for (const int* t = mesh.vertex_triangles_begin(v); t != mesh.vertex_triangles_end(v); ++t) {
      if (marked[*t]) continue;
      marked[*t] = 1;
      for (int u : mesh.triangle(*t))
        if (!queued[u]) queued[u] = 1, pending.push_back(u);
    }
  }
}

// The density of the CVT on `mesh`: the options' own, the curvature density, or none (uniform).
std::vector<double> density_of(const SurfaceMesh& mesh, int samples, const CvtOptions& options) {
  if (!options.triangle_density.empty()) return options.triangle_density;
  if (options.density == CvtDensity::Curvature) return curvature_density(mesh, samples);
  return {};
}

}  // namespace

std::vector<char> repair_window(const Diagram& diagram, const std::vector<int>& seeds, int rings) {
  const CellAdjacency adjacency(diagram);
  std::vector<char> window(diagram.sample_count, 0);
  std::vector<int> front;
  for (int s : seeds)
    if (s >= 0 && s < diagram.sample_count && !window[s]) window[s] = 1, front.push_back(s);
  for (int ring = 0; ring <= rings && !front.empty(); ++ring) {
    // The last pass marks the frozen ring (2) round the `rings` rings that move (1).
    const char mark = ring == rings ? 2 : 1;
    std::vector<int> next;
    for (int c : front)
      for (const int* d = adjacency.begin(c); d != adjacency.end(c); ++d)
        if (!window[*d]) window[*d] = mark, next.push_back(*d);
    front.swap(next);
  }
  return window;
}

CvtResult optimize_cvt_in_window(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram,
                                 const std::vector<char>& window, const CvtOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int n = samples.size();
  if (static_cast<int>(window.size()) != n || diagram.sample_count != n)
    throw InputError("optimize_cvt_in_window: the window and the diagram need one entry per sample");
  const std::vector<double> density = density_of(mesh, n, options);
  // The triangles the window's cells (moving and frozen) cover, and the samples' own.
  std::vector<char> marked(mesh.triangle_count(), 0);
  for (const CellPolygon& poly : diagram.polygons)
    if (window[poly.cell]) marked[poly.triangle] = 1;
  std::vector<int> in_window;
  for (int i = 0; i < n; ++i)
    if (window[i]) in_window.push_back(i), marked[samples.triangles[i]] = 1;
  close_pinched_vertices(mesh, marked);
  // The sub-mesh, its vertices and triangles in the mesh's order (ties of the predicates are
  // broken by index: the order is kept).
  std::vector<int> new_vertex(mesh.vertex_count(), -1), new_triangle(mesh.triangle_count(), -1), old_triangle;
  for (int t = 0; t < mesh.triangle_count(); ++t)
    if (marked[t])
      for (int v : mesh.triangle(t)) new_vertex[v] = 0;
  std::vector<Vec3> positions;
  for (int v = 0; v < mesh.vertex_count(); ++v)
    if (new_vertex[v] == 0) new_vertex[v] = static_cast<int>(positions.size()), positions.push_back(mesh.position(v));
  std::vector<Triangle> triangles;
  for (int t = 0; t < mesh.triangle_count(); ++t)
    if (marked[t]) {
      const Triangle& tri = mesh.triangle(t);
      new_triangle[t] = static_cast<int>(triangles.size());
      old_triangle.push_back(t);
      triangles.push_back({new_vertex[tri[0]], new_vertex[tri[1]], new_vertex[tri[2]]});
    }
  const SurfaceMesh sub(std::move(positions), std::move(triangles));
  Samples local;
  CvtOptions sub_options = options;
  sub_options.movable.clear();
  for (int i : in_window) {
    local.positions.push_back(samples.positions[i]);
    local.triangles.push_back(new_triangle[samples.triangles[i]]);
    local.barycentric.push_back(samples.barycentric[i]);
    sub_options.movable.push_back(window[i] == 1);
  }
  sub_options.triangle_density.clear();
  for (int t : old_triangle) sub_options.triangle_density.push_back(density.empty() ? 1.0 : density[t]);
  const ClosestPointIndex sub_index(sub);
  const CvtResult moved = optimize_cvt(sub, local, sub_options, nullptr, &sub_index);
  // Back on the whole mesh: the moving samples' new places, then the one diagram of all.
  CvtResult result;
  result.samples = samples;
  result.samples.weights.clear();
  for (size_t k = 0; k < in_window.size(); ++k) {
    if (window[in_window[k]] != 1) continue;
    const int i = in_window[k];
    result.samples.positions[i] = moved.samples.positions[k];
    result.samples.triangles[i] = old_triangle[moved.samples.triangles[k]];
    result.samples.barycentric[i] = moved.samples.barycentric[k];
  }
  const std::vector<double>* rho = density.empty() ? nullptr : &density;
  const double before = integrate_cells(diagram, mesh, samples, rho).total_energy;
  CvtEnergy after = cvt_energy(mesh, result.samples, options.diagram, rho);
  result.diagram = std::move(after.diagram);
  result.energy = after.energy;
  result.energy_history = {before, after.energy};
  result.iterations = moved.iterations;
  result.diagram_evaluations = moved.diagram_evaluations + 1;
  result.line_search_stopped = moved.line_search_stopped;
  result.time_s = seconds_since(start);
  return result;
}

CvtResult repair_round_cvt(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram,
                           const std::vector<int>& acted_on, const CvtOptions& options, const LocalRepairOptions& local, int round, int rounds_without_progress,
                           const ClosestPointIndex& index, LocalRound* account) {
  LocalRound unused;
  LocalRound& said = account ? *account : unused;
  const int n = samples.size();
  std::vector<int> moved;
  for (int i = 0; i < n && i < static_cast<int>(diagram.sites.size()); ++i)
    if (!(diagram.sites[i].p == samples.positions[i])) moved.push_back(i);
  const bool current = moved.empty() && diagram.sample_count == n;
  if (round < local.whole_first || rounds_without_progress >= local.whole_after || diagram.sample_count != n) {
    said.whole_because = round < local.whole_first ? "first rounds" : "no progress";
    return optimize_cvt(mesh, samples, options, current ? &diagram : nullptr, &index);
  }
  // Samples moved since the diagram (into defect cells): they and the cells they left move too,
  // on the diagram of where they are now.
  std::vector<int> seeds(acted_on);
  Diagram fresh;
  if (!current) {
    const std::vector<char> left = repair_window(diagram, moved, 0);
    for (int i = 0; i < n; ++i)
      if (left[i]) seeds.push_back(i);
    fresh = compute_diagram(mesh, samples, options.diagram);
  }
  const Diagram& now = current ? diagram : fresh;
  const std::vector<char> window = repair_window(now, seeds, local.rings + rounds_without_progress);
  const auto size = std::count_if(window.begin(), window.end(), [](char w) { return w != 0; });
  said.window = static_cast<int>(size);
  said.moving = static_cast<int>(std::count(window.begin(), window.end(), 1));
  if (static_cast<double>(size) > local.max_window_share * n) {
    said.whole_because = "window too large";
    CvtResult whole = optimize_cvt(mesh, samples, options, &now, &index);
    whole.diagram_evaluations += current ? 0 : 1;
    return whole;
  }
  CvtResult result = optimize_cvt_in_window(mesh, samples, now, window, options);
  result.diagram_evaluations += current ? 0 : 1;
  return result;
}

}  // namespace lrvd
