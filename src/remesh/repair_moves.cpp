// The repair rounds' moves of densities and samples (remesh/repair_moves.h).
#include "remesh/repair_moves.h"

#include <algorithm>
#include <limits>
#include <tuple>

#include "diagram/clip.h"
#include "mesh/closest_point.h"
#include "remesh/cvt.h"

namespace lrvd {

namespace {

// Per cell: 1 for the defect cells, 2 for the cells that share a diagram vertex with one, else 0.
std::vector<char> defect_neighbourhood(const Diagram& diagram, const std::vector<int>& defect) {
  std::vector<char> involved(diagram.sample_count, 0);
  for (int i : defect) involved[i] = 1;
  for (const SymbolicVertex& q : diagram.vertices)
    for (int a = 0; a < q.num_labels(); ++a)
      if (involved[q.label[a]] == 1)
        for (int b = 0; b < q.num_labels(); ++b)
          if (!involved[q.label[b]]) involved[q.label[b]] = 2;
  return involved;
}

}  // namespace

// Multiplies the density on the triangles of the defect cells and of their neighbours, so that the
// CVT draws more samples into the thin part they wrap. Returns how many triangles it raised: all of
// them when every cell is at a defect or next to one, which leaves the CVT as it was (its energy
// and gradient only scale).
std::size_t raise_density(const Diagram& diagram, const std::vector<int>& defect, double factor,
                          std::vector<double>& density) {
  const std::vector<char> involved = defect_neighbourhood(diagram, defect);
  std::vector<char> raised(density.size(), 0);
  std::size_t count = 0;
  for (const CellPolygon& poly : diagram.polygons)
    if (involved[poly.cell] && !raised[poly.triangle]) {
      raised[poly.triangle] = 1;
      density[poly.triangle] *= factor;
      ++count;
    }
  return count;
}

// Divides the density on the triangles of the given cells (their own, not their neighbours'), so
// that the CVT makes those cells larger.
void lower_density(const Diagram& diagram, const std::vector<int>& cells, double factor, std::vector<double>& density) {
  std::vector<char> lowered_cell(diagram.sample_count, 0), lowered(density.size(), 0);
  for (int c : cells) lowered_cell[c] = 1;
  for (const CellPolygon& poly : diagram.polygons)
    if (lowered_cell[poly.cell] && !lowered[poly.triangle]) {
      lowered[poly.triangle] = 1;
      density[poly.triangle] /= factor;
    }
}

// Moves samples into the defect cells: for each one, the sample of the lightest cell away from
// every defect (from a component that keeps more than the fewest vertices its topology needs) goes
// to the point of the defect cell farthest from its sample (across the tube a ring cell wraps,
// the tip a cap cell covers). A raised density draws samples into a thin part only as far as a
// CVT round carries them; this brings them there at once, also from another component. Returns
// how many samples moved.
int relocate_samples(const Diagram& diagram, const SurfaceMesh& mesh, const std::vector<double>& density,
                     const std::vector<int>& defect, Samples& samples) {
  const int n = samples.size();
  const std::vector<char> involved = defect_neighbourhood(diagram, defect);
  const std::vector<int>& component = mesh.triangle_components();
  auto component_of = [&](int sample) { return component[samples.triangles[sample]]; };
  std::vector<int> count(mesh.component_count(), 0);
  for (int i = 0; i < n; ++i) ++count[component_of(i)];
  const std::vector<int> fewest = mesh.minimum_vertex_counts();
  const CellIntegrals cells = integrate_cells(diagram, mesh, samples, &density);
  std::vector<int> donors;
  for (int i = 0; i < n; ++i)
    if (!involved[i]) donors.push_back(i);
  std::sort(donors.begin(), donors.end(), [&](int a, int b) { return std::tie(cells.area[a], a) < std::tie(cells.area[b], b); });
  struct Farthest {
    double d2 = -1;
    Vec3 p;
    int triangle = -1;
  };
  std::vector<Farthest> far(n);
  const SymbolicContext ctx = diagram.context(mesh);
  for (const CellPolygon& poly : diagram.polygons) {
    if (involved[poly.cell] != 1) continue;
    const SymbolicVertex* v = diagram.polygon_vertices(poly);
    for (int k = 0; k < poly.vertex_count; ++k) {
      const Vec3 p = position(v[k], ctx);
      const double d2 = squared_distance(p, samples.positions[poly.cell]);
      if (d2 > far[poly.cell].d2) far[poly.cell] = {d2, p, poly.triangle};
    }
  }
  std::vector<int> targets(defect);
  std::sort(targets.begin(), targets.end());
  targets.erase(std::unique(targets.begin(), targets.end()), targets.end());
  int moved = 0;
  size_t next = 0;
  std::vector<Vec3> placed;  // two defect cells may share their farthest point (a vertex of both)
  for (int d : targets) {
    if (far[d].triangle < 0 || std::find(placed.begin(), placed.end(), far[d].p) != placed.end()) continue;
    placed.push_back(far[d].p);
    while (next < donors.size() && count[component_of(donors[next])] <= fewest[component_of(donors[next])]) ++next;
    if (next == donors.size()) break;
    const int s = donors[next++];
    --count[component_of(s)];
    const Triangle& tri = mesh.triangle(far[d].triangle);
    const ClosestPoint c = closest_point_on_triangle(far[d].p, mesh.position(tri[0]), mesh.position(tri[1]), mesh.position(tri[2]));
    samples.positions[s] = c.point;
    samples.triangles[s] = far[d].triangle;
    samples.barycentric[s] = c.barycentric;
    ++count[component[far[d].triangle]];
    ++moved;
  }
  return moved;
}

// When a defect sample of `kept` lies on a component that holds at most one sample more than its
// topology needs in `start` (the samples the runs began from), moves two samples onto every such
// component of `start`: each from the component with the most samples above its fewest (which
// keeps at least two above), its highest-index one, to the centroid of the receiving component's
// triangle farthest from that component's samples. Returns how many samples moved (0: no defect
// there, one component, or none to spare).
int add_samples_to_starved_components(const SurfaceMesh& mesh, const Samples& kept, const std::vector<int>& defect,
                                      Samples& start) {
  constexpr int kMargin = 2;
  const int components = mesh.component_count();
  if (components < 2) return 0;
  const std::vector<int>& component = mesh.triangle_components();
  const std::vector<int> fewest = mesh.minimum_vertex_counts();
  std::vector<int> count(components, 0);
  for (int t : start.triangles) ++count[component[t]];
  // Any defect on such a component: every such component gets the margin (the others' samples
  // move too, so a component spared now may fail next).
  const bool defect_on_starved = std::any_of(defect.begin(), defect.end(), [&](int s) {
    const int c = component[kept.triangles[s]];
    return count[c] <= fewest[c] + 1;
  });
  if (!defect_on_starved) return 0;
  std::vector<int> starved;
  for (int c = 0; c < components; ++c)
    if (count[c] <= fewest[c] + 1) starved.push_back(c);
  std::vector<char> is_starved(components, 0);
  for (int c : starved) is_starved[c] = 1;
  std::vector<std::vector<int>> triangles_of(components);
  for (int t = 0; t < mesh.triangle_count(); ++t)
    if (is_starved[component[t]]) triangles_of[component[t]].push_back(t);
  const auto centroid = [&](int t) {
    const Triangle& tri = mesh.triangle(t);
    return (mesh.position(tri[0]) + mesh.position(tri[1]) + mesh.position(tri[2])) / 3.0;
  };
  int moved = 0;
  for (int c : starved)
    for (int k = 0; k < kMargin; ++k) {
      int donor = -1;
      for (int d = 0; d < components; ++d)
        if (!is_starved[d] && count[d] - 1 >= fewest[d] + kMargin &&
            (donor < 0 || count[d] - fewest[d] > count[donor] - fewest[donor]))
          donor = d;
      if (donor < 0) return moved;
      int sample = start.size() - 1;
      while (component[start.triangles[sample]] != donor) --sample;
      // The farthest triangle centroid of c from c's samples (distances to the nearest one); c holds
      // a few samples, so they are gathered first.
      std::vector<Vec3> own;
      for (int s = 0; s < start.size(); ++s)
        if (component[start.triangles[s]] == c) own.push_back(start.positions[s]);
      double best = -1;
      int best_triangle = -1;
      for (int t : triangles_of[c]) {
        const Vec3 p = centroid(t);
        double nearest = std::numeric_limits<double>::infinity();
        for (const Vec3& q : own) nearest = std::min(nearest, squared_distance(p, q));
        if (nearest > best) best = nearest, best_triangle = t;
      }
      if (!(best > 0)) break;  // every centroid holds a sample already: no place left for another
      start.positions[sample] = centroid(best_triangle);
      start.triangles[sample] = best_triangle;
      start.barycentric[sample] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
      --count[donor];
      ++count[c];
      ++moved;
    }
  return moved;
}

}  // namespace lrvd
