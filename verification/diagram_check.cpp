// verify_diagram: the LRVD properties of paper §2.3 checked exactly. The triangles in parallel,
// each on its own copy of its vertices (diagram_triangle.cpp): (3) equidistance and the local
// Voronoi property of every polygon vertex, (4) convex, counterclockwise polygons inside the
// triangle and pairwise interior-disjoint, (5) exact area sums, (1) its samples lie in their cells;
// then along mesh edges (2) and (6) (diagram_edges.cpp). Here: the diagram's layout, the order of
// the passes, the merging of their results and the counts of distinct vertices and rational points.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "verification/diagram_checker.h"
#include "verification/diagram_edges.h"
#include "verification/diagram_triangle.h"
#include "verification/diagram_vertices.h"

namespace lrvd {

namespace verify_detail {

DiagramInput::DiagramInput(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram,
                           const VerifyOptions& options)
    : mesh(mesh), samples(samples), d(diagram), options(options), context(diagram.context(mesh)),
      terms(site_terms(diagram.sites)), polygon_state(diagram.polygons.size(), 0) {
  const int nt = mesh.triangle_count();
  sample_first.assign(nt + 1, 0);
  auto triangle_of = [&](int i) {  // -1: the sample is on no triangle
    const int t = i < static_cast<int>(samples.triangles.size()) ? samples.triangles[i] : -1;
    return t >= 0 && t < nt && i < static_cast<int>(samples.barycentric.size()) ? t : -1;
  };
  for (int i = 0; i < samples.size(); ++i)
    if (const int t = triangle_of(i); t >= 0) ++sample_first[t + 1];
  for (int t = 0; t < nt; ++t) sample_first[t + 1] += sample_first[t];
  sample_order.resize(sample_first[nt]);
  std::vector<int> next(sample_first.begin(), sample_first.end() - 1);
  for (int i = 0; i < samples.size(); ++i)
    if (const int t = triangle_of(i); t >= 0) sample_order[next[t]++] = i;
}

std::uint64_t DiagramInput::irregular_key(const SymbolicVertex& q) const {
  if (const auto it = irregular_.find(q); it != irregular_.end()) return it->second;
  // Two threads may number q at once: the first to insert wins, and both take its number.
  const std::uint64_t key = std::uint64_t{1} << 62 | next_irregular_++;
  return irregular_.emplace(q, key).first->second;
}

}  // namespace verify_detail

namespace {

using namespace verify_detail;

// Diagram layout the checks index through; a failure here stops the verification.
std::string structure_error(const SurfaceMesh& mesh, const Samples& samples, const Diagram& d) {
  const int nt = mesh.triangle_count();
  if (d.sample_count != samples.size())
    return fmt::format("diagram has {} cells for {} samples", d.sample_count, samples.size());
  if (static_cast<int>(d.sites.size()) != d.sample_count)
    return fmt::format("diagram has {} sites for {} cells", d.sites.size(), d.sample_count);
  // The checks read the sites: they must be the samples given (a non-finite one would reach the
  // rationals, which cannot hold it).
  if (!samples.weights.empty() && samples.weights.size() != samples.positions.size())
    return fmt::format("{} weights for {} samples", samples.weights.size(), samples.positions.size());
  for (int i = 0; i < d.sample_count; ++i) {
    const Site& s = d.sites[i];
    const double w = is_power(d.kind) ? samples.weight(i) : 0.0;
    if (!(s.p == samples.positions[i]) || !(s.w == w) || s.id != i)
      return fmt::format("site {} is not sample {} (its position, weight or id differs)", i, i);
    if (!is_finite(s.p) || !std::isfinite(s.w)) return fmt::format("site {} is not finite", i);
  }
  if (static_cast<int>(d.triangle_offsets.size()) != nt + 1)
    return fmt::format("diagram has {} triangle offsets for {} triangles", d.triangle_offsets.size(), nt);
  if (d.triangle_offsets[0] != 0 || d.triangle_offsets[nt] != static_cast<int>(d.polygons.size()))
    return "triangle offsets do not span the polygon list";
  for (int t = 0; t < nt; ++t) {
    if (d.triangle_offsets[t + 1] < d.triangle_offsets[t]) return fmt::format("triangle {}: offsets decrease", t);
    for (int p = d.triangle_offsets[t]; p < d.triangle_offsets[t + 1]; ++p) {
      const CellPolygon& poly = d.polygons[p];
      if (poly.triangle != t) return fmt::format("polygon {} is listed under triangle {} but names triangle {}", p, t, poly.triangle);
      if (poly.first_vertex < 0 || poly.vertex_count < 0 ||
          static_cast<std::int64_t>(poly.first_vertex) + poly.vertex_count > static_cast<std::int64_t>(d.vertices.size()))
        return fmt::format("polygon {} in triangle {}: vertex range out of bounds", p, t);
    }
  }
  return {};
}

// Whether the polygons' vertex ranges follow each other in polygon order and cover the vertex
// list: then every vertex is some polygon's, once (how the builders lay a diagram out).
bool consecutive_ranges(const Diagram& d) {
  std::int64_t next = 0;
  for (const CellPolygon& poly : d.polygons) {
    if (poly.first_vertex != next) return false;
    next += poly.vertex_count;
  }
  return next == static_cast<std::int64_t>(d.vertices.size());
}

// The distinct well-formed symbolic vertices of the diagram and the mesh vertices, one by one: for a
// diagram the triangle pass cannot count (vertices of other triangles, ranges that overlap or
// leave vertices out).
std::int64_t count_distinct(const SurfaceMesh& mesh, const Diagram& d) {
  SymbolicVertexIndex index;
  index.reserve(mesh.vertex_count());
  for (int v = 0; v < mesh.vertex_count(); ++v) index.insert(SymbolicVertex::mesh_vertex(v));
  for (const SymbolicVertex& q : d.vertices)
    if (well_formed(q, mesh.vertex_count(), d.sample_count)) index.insert(q);
  return static_cast<std::int64_t>(index.size());
}

// (1)'s offenders, by sample: those on no triangle, and those the triangle pass found.
void report_samples(const Samples& samples, const std::vector<TriangleChunk>& chunks, const DiagramInput& in,
                    PropertyResult& out) {
  std::vector<std::pair<int, std::string>> failures;
  for (int i = 0; i < samples.size(); ++i) {
    const int t = i < static_cast<int>(samples.triangles.size()) ? samples.triangles[i] : -1;
    if (t < 0 || t >= in.mesh.triangle_count() || i >= static_cast<int>(samples.barycentric.size()))
      failures.emplace_back(i, fmt::format("sample {}: not located on a triangle", i));
  }
  for (const TriangleChunk& c : chunks) failures.insert(failures.end(), c.sample_failures.begin(), c.sample_failures.end());
  std::sort(failures.begin(), failures.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  out.checked = samples.size();
  for (const auto& [i, offender] : failures) out.fail(offender);
}

// The vertices whose rationals some check made: counted, and (3) for their own labels, which
// check_equidistance counts as equidistant by construction: where a check made a vertex's rational
// point anyway, at ties, the construction is checked too, for free. Offenders in the order the
// vertices first occur in the diagram.
void check_rational_vertices(const DiagramInput& in, DiagramVerification& out) {
  std::vector<SymbolicVertex> offenders;
  in.rationals.for_each([&](const SymbolicVertex& q, const RationalPoint& entry) {
    out.rational_points += entry.made();
    if (!entry.point || q.num_labels() == 0) return;
    const ExactVertex x = ExactVertex::of(q, in.context, &in.rationals);
    for (int k = 1; k < q.num_labels(); ++k)
      if (compare_power_distance(x, in.d.sites[q.label[0]], in.d.sites[q.label[k]]) != Sign::Zero) {
        offenders.push_back(q);
        break;
      }
  });
  if (offenders.empty()) return;
  std::unordered_map<SymbolicVertex, std::size_t, SymbolicVertexHash> first;
  for (const SymbolicVertex& q : offenders) first.emplace(q, in.d.vertices.size());
  for (std::size_t k = in.d.vertices.size(); k-- > 0;)
    if (const auto it = first.find(in.d.vertices[k]); it != first.end()) it->second = k;
  std::sort(offenders.begin(), offenders.end(),
            [&](const SymbolicVertex& a, const SymbolicVertex& b) { return first[a] < first[b]; });
  for (const SymbolicVertex& q : offenders)
    out.equidistant.fail(fmt::format("vertex {} is not equidistant from its cells", describe(q)));
}

void check_all(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram, const VerifyOptions& options,
               DiagramVerification& out) {
  DiagramInput in(mesh, samples, diagram, options);
  const int nt = mesh.triangle_count();
  std::vector<TriangleChunk> chunks((nt + kCheckChunk - 1) / kCheckChunk);
  std::vector<EdgeChunk> edges(chunks.size());
  tbb::parallel_for(0, static_cast<int>(chunks.size()), [&](int c) {
    TriangleChecker(in, chunks[c]).check_triangles(c * kCheckChunk, std::min(nt, (c + 1) * kCheckChunk));
    check_inner_edges(in, chunks, c, edges[c]);
  });
  bool irregular = !consecutive_ranges(diagram);
  std::int64_t counted = mesh.vertex_count();
  for (const TriangleChunk& c : chunks) {
    for (auto member : {&DiagramVerification::equidistant, &DiagramVerification::disjoint, &DiagramVerification::coverage})
      merge_into(out.*member, c.part.*member);
    out.rational_points += c.part.rational_points;
    counted += c.c_count;
    irregular = irregular || c.irregular;
  }
  report_samples(samples, chunks, in, out.sample_in_cell);
  counted += check_edges(in, chunks, edges, out);
  out.distinct_vertices = irregular ? count_distinct(mesh, diagram) : counted;
  check_rational_vertices(in, out);
}

}  // namespace

DiagramVerification verify_diagram(const SurfaceMesh& mesh, const Samples& samples, const Diagram& diagram,
                                   const VerifyOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  DiagramVerification out;
  out.sample_in_cell.promised = !is_power(diagram.kind);
  out.connected.promised = is_localized(diagram.kind);
  const std::string broken = structure_error(mesh, samples, diagram);
  if (!broken.empty()) {
    for (PropertyResult* p : {&out.sample_in_cell, &out.connected, &out.equidistant, &out.disjoint, &out.coverage,
                              &out.conforming})
      p->fail("diagram is malformed: " + broken);
  } else {
    check_all(mesh, samples, diagram, options, out);
  }
  out.passed = true;
  for (const PropertyResult* p : {&out.sample_in_cell, &out.connected, &out.equidistant, &out.disjoint, &out.coverage,
                                  &out.conforming})
    if (p->promised && !p->passed) out.passed = false;
  out.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace lrvd
