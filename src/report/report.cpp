// The samples of a diagram on a mesh and the JSON reports the `lrvd` command and the Python
// module share (report.h).
#include "report/report.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "common/error.h"
#include "mesh/refine.h"
#include "predicates/predicates.h"
#include "voronoi/lrvd.h"

namespace lrvd {

namespace {

// A given point that its closest point moves by no more than this fraction of the bounding-box
// diagonal was on the surface but for rounding.
constexpr double kRoundingMove = 1e-9;

// A mesh measured against a reference of another size or place: its bounding box's diagonal more
// than 1.5 times the reference's or less than 1/1.5 of it, or its centre further from the
// reference's than half the reference's diagonal. "" when neither holds.
std::string frame_mismatch(const BoundingBox& reference, const BoundingBox& mesh) {
  constexpr double kSizeRatio = 1.5;
  const double size = mesh.diagonal() / reference.diagonal();
  const double offset = distance(0.5 * (mesh.min + mesh.max), 0.5 * (reference.min + reference.max));
  if (size <= kSizeRatio && size >= 1 / kSizeRatio && offset <= 0.5 * reference.diagonal()) return std::string();
  return fmt::format("the mesh's bounding box has {:.3g} times the reference's diagonal ({:.4g} against {:.4g}) and "
                     "its centre is {:.3g} reference diagonals away: the distances measure that; are both in one unit "
                     "and frame?",
                     size, mesh.diagonal(), reference.diagonal(), offset / reference.diagonal());
}

}  // namespace

std::string counted(long long count, const char* one, const char* many) {
  return fmt::format("{} {}", count, count == 1 ? one : many);
}

std::vector<std::string> repair_changes(const RepairReport& r) {
  std::vector<std::string> changes;
  const int merged = r.welded_vertices + r.merged_vertices;
  if (merged > 0)
    changes.push_back(fmt::format("merged {}{}", counted(merged, "vertex", "vertices"),
                                  r.welded_vertices > 0 ? fmt::format(" ({} within --weld)", r.welded_vertices)
                                                        : std::string()));
  if (r.removed_degenerate_faces > 0)
    changes.push_back("removed " + counted(r.removed_degenerate_faces, "degenerate face", "degenerate faces"));
  if (r.removed_internal_faces > 0)
    changes.push_back("removed " + counted(r.removed_internal_faces, "internal wall face", "internal wall faces"));
  if (r.removed_duplicate_faces > 0)
    changes.push_back("removed " + counted(r.removed_duplicate_faces, "duplicate face", "duplicate faces"));
  if (r.removed_unreferenced_vertices > 0)
    changes.push_back("removed " +
                      counted(r.removed_unreferenced_vertices, "unreferenced vertex", "unreferenced vertices"));
  if (r.reoriented_faces > 0) changes.push_back("reoriented " + counted(r.reoriented_faces, "face", "faces"));
  if (r.stitched_edges > 0) changes.push_back("stitched " + counted(r.stitched_edges, "edge", "edges"));
  if (r.split_edges > 0) changes.push_back("split " + counted(r.split_edges, "edge at T-junctions", "edges at T-junctions"));
  if (r.duplicated_nonmanifold_vertices > 0)
    changes.push_back("copied " + counted(r.duplicated_nonmanifold_vertices, "non-manifold vertex",
                                          "non-manifold vertices"));
  if (r.triangulated_faces > 0)
    changes.push_back("triangulated " + counted(r.triangulated_faces, "polygon", "polygons"));
  return changes;
}

nlohmann::json input_json(const Input& input) {
  const SurfaceMesh& mesh = input.loaded.mesh;
  nlohmann::json j = {{"path", ""},
                      {"vertices", mesh.vertex_count()},
                      {"triangles", mesh.triangle_count()},
                      {"area", mesh.area()},
                      {"bbox_diagonal", mesh.bounding_box().diagonal()},
                      {"components", mesh.component_count()},
                      {"closed", mesh.is_closed()},
                      {"euler_characteristic", mesh.euler_characteristic()}};
  if (input.refined_from >= 0)
    j["refined"] = {{"triangles", input.mesh.triangle_count()},
                    {"max_edge_length", input.mesh.max_edge_length()},
                    {"halved_for_connected_cells", input.connectivity_refinements}};
  if (input.repair_requested) j["repair_changes"] = repair_changes(input.loaded.repair);
  if (!input.loaded.repair.notes.empty()) j["repair"] = input.loaded.repair.notes;
  if (input.points_given)
    j["points"] = {{"count", input.samples.size()}, {"moved", input.points_moved}, {"max_move", input.points_max_move}};
  return j;
}

nlohmann::json predicates_json() {
  const PredicateStats s = predicate_stats();
  return {{"calls", s.total.calls},
          {"filter_failures", s.total.filter_failures},
          {"exact", s.total.exact},
          {"perturbations", s.total.perturbations}};
}

nlohmann::json remesh_quality_json(const QualityMetrics& quality, const RemeshVerification& check) {
  nlohmann::json q = quality.to_json();
  q["closed_manifold"] = check.manifold.passed && check.closed.passed;
  q["genus_preserved"] = check.topology.passed;
  q["self_intersections"] = check.self_intersecting_pairs;
  return q;
}

void prepare_samples(Input& input, const SampleRequest& request) {
  const int n = !request.points_given ? request.count : static_cast<int>(request.points.points.size());
  if (!request.points_given && n < 1)
    throw InputError(request.count == 0 ? std::string("give a sample count -n >= 1 or a point file --points")
                                    : fmt::format("give a sample count -n >= 1 or a point file --points (got -n {})", request.count));
  if (n > kMaxSamples)
    throw InputError(fmt::format("{} samples are more than lrvd takes (limit {})", n, kMaxSamples));
  if (request.check_count) request.check_count(input.loaded.mesh, n);

  double length = 0;
  if (request.refine == "auto") {
    length = suggested_refinement_length(input.loaded.mesh, n);
    for (int h = 0; h < input.connectivity_refinements; ++h)
      length = (length > 0 ? length : input.loaded.mesh.max_edge_length()) / 2;
  } else if (request.refine != "off") {
    try {
      size_t used = 0;
      length = std::stod(request.refine, &used);
      if (used != request.refine.size() || !(length > 0)) throw std::invalid_argument(request.refine);
    } catch (const std::exception&) {
      throw InputError(fmt::format("--refine takes 'auto', 'off' or a positive edge length, not '{}'", request.refine));
    }
  }
  if (length > 0 && input.loaded.mesh.max_edge_length() > length) {
    const double expected = expected_refined_triangle_count(input.loaded.mesh, length);
    if (kRefinedTriangleMargin * expected > request.max_refined_triangles)
      throw InputError(fmt::format("refining to edges of {:.6g} would make about {:.3g} triangles, up to {:.3g} (limit "
                                   "{:.3g}): use {}",
                                   length, expected, kRefinedTriangleMargin * expected, request.max_refined_triangles,
                                   request.refine == "auto" ? "fewer samples" : "a longer --refine length or 'off'"));
    if (request.on_progress) request.on_progress(fmt::format("refining the mesh: edges longer than {:.6g}, about {:.3g} triangles", length, expected));
    input.refined_from = input.loaded.mesh.triangle_count();
    // The automatic refinement stops far beyond its estimate: there triangles far longer than wide
    // (a vertex drawn away from the surface) split into many more pieces than their area asks for.
    const double most = std::min(request.refine == "auto" ? auto_refinement_limit(expected) : kMaxRefinedTriangles,
                                 request.max_refined_triangles);
    try {
      input.mesh = refine_long_edges(input.loaded.mesh, length, nullptr, RefineOrder::Input, most);
    } catch (const RefinementLimitError& e) {
      if (most < request.max_refined_triangles)
        throw InputError(fmt::format("{}: refining to edges of {:.6g} for {} would make more than {:.3g} triangles, "
                                     "{:.0f} times the estimate from its area: the mesh has triangles far longer than they are "
                                     "wide: {}; fix the mesh, or use --refine off",
                                     request.mesh_name, length, counted(n, "sample", "samples"), most, most / expected,
                                     thinnest_long_triangle(input.loaded.mesh, length)));
      throw InputError(fmt::format("{}: {}: use {}", request.mesh_name, e.what(),
                                   request.refine == "auto" ? "--refine off (a triangle may then hold several samples)"
                                                        : "a longer --refine length or 'off'"));
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", request.mesh_name, e.what()));
    }
  } else {
    input.mesh = input.loaded.mesh;
  }

  if (&request != &input.request) input.request = request;
  if (!request.points_given) {
    input.samples = sample_uniform(input.mesh, n, request.seed);
    if (!request.points.weights.empty()) {
      if (static_cast<int>(request.points.weights.size()) != n)
        throw InputError(fmt::format("{}{} weights were given for {} samples",
                                     request.weights_name.empty() ? std::string() : request.weights_name + ": ",
                                     request.points.weights.size(), n));
      input.samples.weights = request.points.weights;
    }
  } else {
    try {
      input.samples = locate_points(input.mesh, request.points.points, request.points.weights, request.points.lines);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", request.points_name, e.what()));
    }
    input.points_given = true;
    // A move of more than rounding is counted: a point written on a triangle comes back from its
    // closest point a few ulps away, others the caller says were moved.
    const double diagonal = input.mesh.bounding_box().diagonal();
    for (std::size_t i = 0; i < request.points.points.size(); ++i) {
      const double move = distance(request.points.points[i], input.samples.positions[i]);
      input.points_max_move = std::max(input.points_max_move, move);
      if (move > kRoundingMove * diagonal) ++input.points_moved;
    }
  }
}

Diagram compute_input_diagram(Input& input, DiagramKind kind, CellComponents* pieces) {
  Diagram diagram = compute_diagram(input.mesh, input.samples, kind);
  const bool retry = is_localized(kind) && input.request.refine == "auto";
  if (!retry && !pieces) return diagram;
  CellComponents components = cell_components(diagram, input.mesh);
  while (retry && input.connectivity_refinements < kMaxConnectivityRefinements) {
    const auto split = std::find_if(components.count.begin(), components.count.end(), [](int c) { return c > 1; });
    if (split == components.count.end()) break;
    Input finer = input;
    ++finer.connectivity_refinements;
    try {
      prepare_samples(finer, finer.request);
    } catch (const InputError&) {
      break;  // past the refinement's limits: the diagram in pieces is the answer, judged as such
    }
    if (input.request.on_progress)
      input.request.on_progress(fmt::format("cell {} is in {} pieces on {}: computing again on {}",
                                            split - components.count.begin(), *split,
                                            counted(input.mesh.triangle_count(), "triangle", "triangles"),
                                            counted(finer.mesh.triangle_count(), "triangle", "triangles")));
    diagram = compute_diagram(finer.mesh, finer.samples, kind);
    input = std::move(finer);
    components = cell_components(diagram, input.mesh);
  }
  if (pieces) *pieces = std::move(components);
  return diagram;
}

void check_diagram_weights(const Samples& samples, const std::string& kind) {
  const bool power = is_power(diagram_kind_from_string(kind));
  if (power && !samples.weighted())
    throw InputError(fmt::format("--diagram {} needs weights: give --weights or a 4th column in --points", kind));
  if (!power && samples.weighted())
    throw InputError(fmt::format("weights were given but --diagram {} is not a power diagram (use lrpd or rpd)", kind));
}

int cells_in_pieces(const CellComponents& components) {
  int multiple = 0;
  for (int c : components.count) multiple += c > 1;
  return multiple;
}

nlohmann::json compute_report(const Input& input, const std::string& mesh_path, const std::string& kind,
                              const Diagram& diagram, const CellComponents& components) {
  nlohmann::json report;
  report["input"] = input_json(input);
  report["input"]["path"] = mesh_path;
  report["diagram"] = {{"kind", kind},
                       {"samples", input.samples.size()},
                       {"polygons", diagram.polygons.size()},
                       {"cells_with_multiple_components", cells_in_pieces(components)},
                       {"time_s", diagram.stats.time_s},
                       {"clipped_triangles", diagram.stats.clipped_triangles},
                       {"connectivity_rounds", diagram.stats.connectivity_rounds},
                       {"forbidden_labels", diagram.stats.forbidden_labels},
                       {"pinned_labels", diagram.stats.pinned_labels}};
  report["predicates"] = predicates_json();
  return report;
}

QualityRun run_quality(const LoadedMesh& loaded, bool repair_requested, const PolygonSoup& soup,
                       const std::string& reference_name, const std::string& mesh_name) {
  // A mesh of vertices only (what remesh writes when its dual has no triangle) is checked, not measured.
  QualityRun run;
  const SurfaceMesh& reference = loaded.mesh;
  const bool measurable = run.measurable = !soup.triangles.empty();
  if (measurable) run.quality = quality_metrics(reference, soup.positions, soup.triangles);
  run.check = verify_remesh(reference, soup.positions, soup.triangles, -1);
  nlohmann::json& report = run.report;
  report = {{"reference", reference_name}, {"mesh", mesh_name}};
  if (repair_requested) report["reference_repair_changes"] = repair_changes(loaded.repair);
  if (!loaded.repair.notes.empty()) report["reference_repair"] = loaded.repair.notes;
  // Two meshes in different units or frames give distances that measure that, not the remesh. The
  // distances read the triangles only, so does the frame: a vertex no triangle uses does not count.
  std::vector<Vec3> used;
  {
    std::vector<char> in_triangle(soup.positions.size(), 0);
    for (const Triangle& t : soup.triangles)
      for (int v : t)
        if (v >= 0 && static_cast<std::size_t>(v) < in_triangle.size()) in_triangle[v] = 1;
    for (std::size_t v = 0; v < soup.positions.size(); ++v)
      if (in_triangle[v]) used.push_back(soup.positions[v]);
  }
  run.frame_warning =
      measurable && !used.empty() ? frame_mismatch(reference.bounding_box(), bounding_box(used)) : std::string();
  if (!run.frame_warning.empty()) report["frame_warning"] = run.frame_warning;
  report["quality"] = measurable ? remesh_quality_json(run.quality, run.check) : nlohmann::json(nullptr);
  report["verification"] = run.check.to_json();
  return run;
}

}  // namespace lrvd
