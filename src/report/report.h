// What the `lrvd` command and the Python module share: the samples of a diagram on a mesh (refined
// when they would crowd it) and the JSON reports of compute, remesh, mps and quality (one schema).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "diagram/diagram.h"
#include "io/mesh_io.h"
#include "mesh/refine.h"
#include "metrics/quality.h"
#include "samples/samples.h"
#include "verification/remesh_check.h"

namespace lrvd {

//! Called with a short message at each stage of long work; may be empty.
using ProgressFn = std::function<void(const std::string&)>;

//! The most samples a command takes; the refinement they call for is bounded by
//! kMaxRefinedTriangles (mesh/refine.h), for the memory a verified diagram needs.
constexpr int kMaxSamples = 5'000'000;

//! "1 vertex", "3 vertices": a count with its noun in the right number.
std::string counted(long long count, const char* one, const char* many);

//! What --repair changed, as the console's "repair: ..." line lists it ("merged 8 vertices", ...).
std::vector<std::string> repair_changes(const RepairReport& report);

//! Which samples to make on Input::loaded, and the names the messages give the inputs.
struct SampleRequest {
  bool points_given = false;  //!< `points.points` are the samples; else `count` random ones
  PointFile points;           //!< given points, and their weights (also weights of random samples)
  int count = 0;
  std::uint64_t seed = 1;
  std::string refine = "auto";  //!< auto | off | a maximum edge length
  std::string mesh_name, points_name, weights_name;  //!< prefixes of the messages ("" for none)
  //! Called with the mesh as read and the sample count, before refining and sampling: a command's
  //! own bound on the count (remesh: the fewest vertices a mesh of the surface's topology has).
  std::function<void(const SurfaceMesh&, int)> check_count;
  ProgressFn on_progress;
  //! The most triangles a refinement may make (a smaller budget: the fuzz target).
  double max_refined_triangles = kMaxRefinedTriangles;
};

//! A mesh and the samples of a diagram on it.
struct Input {
  LoadedMesh loaded;              //!< as read (and repaired)
  bool repair_requested = false;  //!< --repair (or --weld) was given
  SurfaceMesh mesh;               //!< after refinement
  int refined_from = -1;          //!< triangle count before refinement, -1 if not refined
  Samples samples;
  //! Times the automatic refinement was halved because a localized diagram left a cell in pieces
  //! on the coarser mesh (compute_input_diagram)
  int connectivity_refinements = 0;
  //! What prepare_samples made the samples from: compute_input_diagram makes them again
  SampleRequest request;
  //! Given points: how many moved onto the surface by more than rounding (1e-9 of the
  //! bounding-box diagonal), and the farthest move
  bool points_given = false;
  int points_moved = 0;
  double points_max_move = 0;
};


//! Refines input.loaded.mesh into input.mesh when the samples would crowd its triangles (or as
//! `refine` says), then draws the random samples or locates the given points on it.
//! \throw InputError on any bad input.
void prepare_samples(Input& input, const SampleRequest& request);

//! How often compute_input_diagram halves the automatic refinement's length at most: each time
//! makes about four times the triangles.
constexpr int kMaxConnectivityRefinements = 3;

//! The diagram of `kind` of input.samples on input.mesh. A localized diagram (LRVD, LRPD) that
//! leaves a cell in pieces on an automatically refined mesh is computed again on the mesh refined
//! to half the length, with the samples made again by input.request on it (random ones are drawn
//! anew, given points located anew), up to kMaxConnectivityRefinements times: on coarse triangles
//! of folded or overlapping sheets the connectivity restoration can run into a cycle that finer
//! triangles do not have (docs/algorithms/lrvd.md, "Connectivity restoration"). `input` is then
//! the last one computed on. A refinement past the request's limits ends the retries; the diagram
//! is the last one made, in pieces, and its verification says so. `pieces`, when given, gets the
//! returned diagram's cell_components.
Diagram compute_input_diagram(Input& input, DiagramKind kind, CellComponents* pieces = nullptr);

//! Weights given for a power diagram (lrpd, rpd) and only then. \throw InputError otherwise.
void check_diagram_weights(const Samples& samples, const std::string& kind);

nlohmann::json input_json(const Input& input);
nlohmann::json predicates_json();
//! The `quality` object of a remesh report: the metrics plus closed_manifold, genus_preserved and
//! self_intersections from the remesh check.
nlohmann::json remesh_quality_json(const QualityMetrics& quality, const RemeshVerification& check);

//! Cells with more than one connected piece.
int cells_in_pieces(const CellComponents& components);
//! The report of `lrvd compute` without its `verification`: input, diagram and the predicates'
//! counts so far (take it before verifying, which calls predicates too).
nlohmann::json compute_report(const Input& input, const std::string& mesh_path, const std::string& kind,
                              const Diagram& diagram, const CellComponents& components);

//! What `lrvd quality` measures and reports.
struct QualityRun {
  bool measurable = false;  //!< the measured mesh has triangles
  QualityMetrics quality;
  RemeshVerification check;
  std::string frame_warning;  //!< "" unless the two meshes look to be in other units or frames
  nlohmann::json report;
};
//! Measures `soup` against `reference`; the names go into the report as given.
QualityRun run_quality(const LoadedMesh& reference, bool repair_requested, const PolygonSoup& soup,
                       const std::string& reference_name, const std::string& mesh_name);

}  // namespace lrvd
