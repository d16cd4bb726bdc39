// CVT remeshing with repair of the dual by moving samples into under-sampled thin parts.
#include "remesh/remesh.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>

#include "metrics/self_intersections.h"
#include "predicates/predicates.h"


namespace lrvd {

DualDefects find_dual_defects(const DualMesh& dual, bool input_closed) {
  std::map<std::pair<int, int>, int> edge_count;
  std::map<Triangle, int> vertex_sets;
  for (const Triangle& t : dual.triangles) {
    for (int e = 0; e < 3; ++e) ++edge_count[{std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3])}];
    Triangle sorted = t;
    std::sort(sorted.begin(), sorted.end());
    ++vertex_sets[sorted];
  }
  std::set<int> defect;
  for (const auto& [edge, count] : edge_count)
    if (count > 2 || (count == 1 && input_closed)) defect.insert({edge.first, edge.second});
  for (const auto& [tri, count] : vertex_sets)
    if (count > 1) defect.insert(tri.begin(), tri.end());
  for (int t : dual.merged_into) defect.insert(dual.triangles[t].begin(), dual.triangles[t].end());
  // A sample in no triangle: its cell meets fewer than two others at a triple point (an island).
  std::vector<char> used(dual.positions.size(), 0);
  for (const Triangle& t : dual.triangles)
    for (int v : t) used[v] = 1;
  for (size_t i = 0; i < used.size(); ++i)
    if (!used[i]) defect.insert(static_cast<int>(i));
  // Triangles that cut through each other (nearby sheets sampled too coarsely).
  std::vector<char> testable(dual.triangles.size(), 1);
  for (size_t t = 0; t < dual.triangles.size(); ++t) {
    const Triangle& f = dual.triangles[t];
    testable[t] = f[0] != f[1] && f[1] != f[2] && f[0] != f[2] &&
                  !predicates::collinear(dual.positions[f[0]], dual.positions[f[1]], dual.positions[f[2]]);
  }
  std::set<int> crossing;
  for (const auto& [s, t] : find_self_intersections(dual.positions, dual.triangles, testable)) {
    crossing.insert(dual.triangles[s].begin(), dual.triangles[s].end());
    crossing.insert(dual.triangles[t].begin(), dual.triangles[t].end());
  }
  return {{defect.begin(), defect.end()}, {crossing.begin(), crossing.end()}};
}

namespace {

// Doubles the density on the triangles of the defect cells and of their neighbours, so that the
// CVT draws more samples into the thin part they wrap.
void raise_density(const Diagram& diagram, const std::vector<int>& defect, std::vector<double>& density) {
  std::vector<char> involved(diagram.sample_count, 0);
  for (int i : defect) involved[i] = 1;
  for (const SymbolicVertex& q : diagram.vertices)
    for (int a = 0; a < q.num_labels(); ++a)
      if (involved[q.label[a]] == 1)
        for (int b = 0; b < q.num_labels(); ++b)
          if (!involved[q.label[b]]) involved[q.label[b]] = 2;
  std::vector<char> raised(density.size(), 0);
  for (const CellPolygon& poly : diagram.polygons)
    if (involved[poly.cell] && !raised[poly.triangle]) {
      raised[poly.triangle] = 1;
      density[poly.triangle] *= 2;
    }
}

}  // namespace

RemeshResult remesh_cvt(const SurfaceMesh& reference, const SurfaceMesh& mesh, const Samples& initial,
                        const RemeshOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  RemeshResult result;
  result.cvt = optimize_cvt(mesh, initial, options.cvt);
  result.total_iterations = result.cvt.iterations;
  result.dual = compute_dual(result.cvt.diagram, mesh, result.cvt.samples);
  CvtOptions again = options.cvt;
  again.iterations = options.repair_iterations;
  again.lloyd_warmup = 1;
  if (again.triangle_density.empty())
    again.triangle_density = options.cvt.density == CvtDensity::Curvature
                                 ? curvature_density(mesh, initial.size())
                                 : std::vector<double>(mesh.triangle_count(), 1.0);
  // Each round raises the density where the worst kind of defect is (topology first, crossings
  // next); the state with the fewest defects is the result.
  DualDefects defects = find_dual_defects(result.dual, reference.is_closed());
  RemeshResult best = result;
  DualDefects best_defects = defects;
  for (int round = 0; round < options.repair_rounds && !defects.empty(); ++round) {
    raise_density(result.cvt.diagram, defects.topological.empty() ? defects.crossing : defects.topological,
                  again.triangle_density);
    ++result.repair_rounds;
    result.cvt = optimize_cvt(mesh, result.cvt.samples, again);
    result.total_iterations += result.cvt.iterations;
    result.dual = compute_dual(result.cvt.diagram, mesh, result.cvt.samples);
    defects = find_dual_defects(result.dual, reference.is_closed());
    if (defects.fewer_than(best_defects)) {
      best_defects = defects;
      best = result;
    }
  }
  best.repair_rounds = result.repair_rounds;
  best.total_iterations = result.total_iterations;
  result = std::move(best);
  result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace lrvd
