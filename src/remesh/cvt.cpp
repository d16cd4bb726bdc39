// CVT on surfaces (paper §4.1): energy and gradient on the exact diagram, Lloyd and L-BFGS.
#include "remesh/cvt.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Core>
#include <LBFGS.h>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/error.h"
#include "common/timing.h"
#include "mesh/closest_point.h"
#include "mesh/curvature.h"
#include "voronoi/lrvd.h"

namespace lrvd {

namespace {

// The curvature density's smoothing passes at most: a mesh of T triangles costs T reads of three
// neighbours a pass, and one with more triangles a sample than this is smoothed over less than a
// cell's width.
constexpr int kMaxDensitySmoothingPasses = 500;

// LBFGS++'s backtracking line search, counting the line searches that end with a step taken: the
// L-BFGS iterations done, which the solver's return value gives only when it does not throw (a
// line search that fails ends the run with an exception).
thread_local int completed_line_searches = 0;
template <typename Scalar>
struct CountedBacktracking {
  template <typename Function, typename Vector>
  static void LineSearch(Function& f, Scalar& fx, Vector& x, Vector& grad, Scalar& step, const Vector& drt,
                         const Vector& xp, const LBFGSpp::LBFGSParam<Scalar>& param) {
    LBFGSpp::LineSearchBacktracking<Scalar>::LineSearch(f, fx, x, grad, step, drt, xp, param);
    ++completed_line_searches;
  }
};

// The mesh triangles of each sample's cell in a diagram: where a sample may be projected when the
// closest point of the whole mesh lies on a sheet facing the other way (see `project`).
using CellTriangles = std::vector<std::vector<int>>;
CellTriangles cell_triangles(const Diagram& diagram) {
  CellTriangles tris(diagram.sample_count);
  for (const CellPolygon& poly : diagram.polygons)
    if (tris[poly.cell].empty() || tris[poly.cell].back() != poly.triangle) tris[poly.cell].push_back(poly.triangle);
  for (std::vector<int>& t : tris) {
    std::sort(t.begin(), t.end());
    t.erase(std::unique(t.begin(), t.end()), t.end());
  }
  return tris;
}

// Records the closest triangle of every point; with `onto_surface`, also moves the point there.
// The samples' triangles before the move are the search hints (the points move little).
// With `cells` (the triangles of each sample's cell), a point whose closest triangle is outside
// its cell and faces the other way than the closest triangle of its cell (the other side of a
// thin wall or of a narrow gap: the centroid of a cell wrapping a thin part lies inside it) is
// projected into its cell instead: a sample does not jump to another sheet.
void project(const ClosestPointIndex& index, const std::vector<Vec3>& points, Samples& samples,
             bool onto_surface = true, const SurfaceMesh* mesh = nullptr, const CellTriangles* cells = nullptr) {
  samples.positions.resize(points.size());
  samples.triangles.resize(points.size(), -1);
  samples.barycentric.resize(points.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 256), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i != range.end(); ++i) {
      ClosestPoint c = index.query(points[i], samples.triangles[i]);
      // A sample keeps to its connected component: a site that crossed the gap between two parts
      // in a step would take a sample from one part (the last one, possibly) and give it to another.
      if (mesh && mesh->component_count() > 1 && samples.triangles[i] >= 0 && c.triangle >= 0) {
        const std::vector<int>& component = mesh->triangle_components();
        const int own = component[samples.triangles[i]];
        if (component[c.triangle] != own) c = index.query_within(points[i], component.data(), own, samples.triangles[i]);
      }
      if (cells && c.triangle >= 0 && i < cells->size() && !(*cells)[i].empty() &&
          !std::binary_search((*cells)[i].begin(), (*cells)[i].end(), c.triangle)) {
        ClosestPoint own;
        own.distance = std::numeric_limits<double>::infinity();
        for (int t : (*cells)[i]) {
          const Triangle& tri = mesh->triangle(t);
          ClosestPoint q = closest_point_on_triangle(points[i], mesh->position(tri[0]), mesh->position(tri[1]),
                                                     mesh->position(tri[2]));
          if (q.distance < own.distance) {
            own = q;
            own.triangle = t;
          }
        }
        if (own.triangle >= 0 && dot(mesh->triangle_normal(own.triangle), mesh->triangle_normal(c.triangle)) < 0) c = own;
      }
      samples.positions[i] = onto_surface ? c.point : points[i];
      samples.triangles[i] = c.triangle;
      samples.barycentric[i] = c.barycentric;
    }
  });
}

// The samples `movable` marks 0 back to where they are in `from`, exactly.
void restore_frozen(const Samples& from, const std::vector<char>& movable, Samples& samples) {
  for (size_t i = 0; i < movable.size(); ++i)
    if (!movable[i]) {
      samples.positions[i] = from.positions[i];
      samples.triangles[i] = from.triangles[i];
      samples.barycentric[i] = from.barycentric[i];
    }
}

std::vector<Vec3> to_points(const Eigen::VectorXd& x) {
  std::vector<Vec3> points(x.size() / 3);
  for (size_t i = 0; i < points.size(); ++i) points[i] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
  return points;
}

}  // namespace

namespace {

// The energy of `diagram`, whose layout is checked unless the caller computed it (`own`).
CvtEnergy energy_of(const SurfaceMesh& mesh, const Samples& samples, Diagram diagram,
                    const std::vector<double>* density, bool own) {
  CvtEnergy e;
  e.diagram = std::move(diagram);
  e.cells = own ? integrate_own_cells(e.diagram, mesh, samples, density)
                : integrate_cells(e.diagram, mesh, samples, density);
  e.energy = e.cells.total_energy;
  e.gradient.resize(samples.size());
  for (int i = 0; i < samples.size(); ++i)
    e.gradient[i] = 2.0 * e.cells.area[i] * (samples.positions[i] - e.cells.centroid[i]);
  return e;
}

}  // namespace

CvtEnergy cvt_energy(const SurfaceMesh& mesh, const Samples& samples, DiagramKind kind,
                     const std::vector<double>* density) {
  return energy_of(mesh, samples, compute_diagram(mesh, samples, kind), density, true);
}

CvtEnergy cvt_energy(const SurfaceMesh& mesh, const Samples& samples, Diagram diagram,
                     const std::vector<double>* density) {
  return energy_of(mesh, samples, std::move(diagram), density, false);
}

std::vector<double> curvature_density(const SurfaceMesh& mesh, int sample_count) {
  const int nt = mesh.triangle_count();
  const std::vector<double> kappa_at = mean_curvature(mesh);
  const double h = std::sqrt(2.0 * mesh.area() / (std::sqrt(3.0) * std::max(sample_count, 1)));
  std::vector<double> rho(nt);
  for (int t = 0; t < nt; ++t) {
    double kappa = 0;
    for (int v : mesh.triangle(t)) kappa += kappa_at[v];
    const double c = kappa / 3.0 * h;
    rho[t] = std::min(std::pow(1.0 + c * c, 2.0), 100.0);
  }
  // Smoothed by passes of averaging with the edge neighbours, as many as the mesh has triangles per
  // sample: that spreads a peak over about a cell's width (the mean triangle-to-neighbour step
  // times the square root of the passes). A cell integrates the density over its area, and a
  // density that changes within a cell's width only makes the cells irregular: with a single pass,
  // the armadillo took 29-36 repair rounds at 300-1000 vertices, and 9-16 with these passes
  // (docs/results.md, "`--density curvature`").
  const int passes = std::clamp(static_cast<int>(std::lround(static_cast<double>(nt) / std::max(sample_count, 1))), 1,
                                kMaxDensitySmoothingPasses);
  std::vector<double> smooth(nt);
  for (int pass = 0; pass < passes; ++pass) {
    for (int t = 0; t < nt; ++t) {
      double sum = rho[t], count = 1;
      for (int e = 0; e < 3; ++e)
        if (mesh.neighbor(t, e) >= 0) sum += rho[mesh.neighbor(t, e)], count += 1;
      smooth[t] = sum / count;
    }
    rho.swap(smooth);
  }
  // Then mean 1 by area.
  double mass = 0;
  for (int t = 0; t < nt; ++t) mass += rho[t] * mesh.triangle_area(t);
  const double scale = mesh.area() / mass;  // SurfaceMesh::area sums every triangle: once, not per triangle
  for (double& r : rho) r *= scale;
  return rho;
}

namespace {

void check_cvt_inputs(const SurfaceMesh& mesh, const Samples& initial, const CvtOptions& options,
                      const Diagram* diagram_of_initial) {
  if (initial.size() == 0) throw InputError("CVT needs at least one sample");
  check_samples(mesh, initial);
  if (options.iterations < 0 || options.lloyd_warmup < 0)
    throw InputError(fmt::format("the CVT's iterations ({}) and Lloyd warm-up steps ({}) may not be negative",
                                 options.iterations, options.lloyd_warmup));
  if (!(options.relative_gradient >= 0) || !(options.relative_energy_change >= 0))
    throw InputError("the CVT's stopping thresholds must be numbers of at least 0");
  if (!options.movable.empty() && options.movable.size() != static_cast<size_t>(initial.size()))
    throw InputError(fmt::format("the CVT's movable mask has {} entries for {} samples: it needs one per sample",
                                 options.movable.size(), initial.size()));
  if (diagram_of_initial && (diagram_of_initial->sample_count != initial.size() ||
                             diagram_of_initial->triangle_offsets.size() != static_cast<std::size_t>(mesh.triangle_count()) + 1))
    throw InputError("optimize_cvt: the diagram given is not of these samples on this mesh");
}

// The density the options ask for: theirs, checked; the curvature density, kept in `storage`; or
// none (uniform).
const std::vector<double>* cvt_density(const SurfaceMesh& mesh, const CvtOptions& options, int n,
                                       std::vector<double>& storage) {
  if (!options.triangle_density.empty()) {
    if (static_cast<int>(options.triangle_density.size()) != mesh.triangle_count())
      throw InputError("the CVT density needs one value per mesh triangle");
    const auto bad = std::find_if(options.triangle_density.begin(), options.triangle_density.end(),
                                  [](double rho) { return !(rho > 0) || !std::isfinite(rho); });
    if (bad != options.triangle_density.end())
      throw InputError(fmt::format("the CVT density of triangle {} is {}: it must be a positive number",
                                   bad - options.triangle_density.begin(), *bad));
    return &options.triangle_density;
  }
  if (options.density == CvtDensity::Curvature) {
    storage = curvature_density(mesh, n);
    return &storage;
  }
  return nullptr;
}

// The state optimize_cvt's steps share: the samples, the energy of the current state and the
// result being filled. The steps: Lloyd steps (the whole run, or a warm-up), then L-BFGS.
class CvtSolver {
 public:
  CvtSolver(const SurfaceMesh& mesh, const Samples& initial, const CvtOptions& options, const ClosestPointIndex& index,
            const std::vector<double>* density)
      : mesh_(mesh), initial_(initial), options_(options), index_(index), density_(density), n_(initial.size()),
        samples_(initial) {
    samples_.weights.clear();
  }

  CvtResult run(const Diagram* diagram_of_initial) {
    current_ = diagram_of_initial ? cvt_energy(mesh_, samples_, *diagram_of_initial, density_)
                                  : cvt_energy(mesh_, samples_, options_.diagram, density_);
    if (!diagram_of_initial) ++result_.diagram_evaluations;
    result_.energy_history.push_back(current_.energy);
    lloyd_steps();
    if (options_.optimizer == CvtOptimizer::Lbfgs && iteration_ < options_.iterations) lbfgs();
    result_.samples = samples_;
    result_.energy = current_.energy;
    result_.diagram = std::move(current_.diagram);
    result_.iterations = iteration_;
    return std::move(result_);
  }

 private:
  void report(double energy) {
    result_.energy_history.push_back(energy);
    if (options_.on_iteration) options_.on_iteration(iteration_, energy);
  }
  // The samples at `points` (on the surface, or only located), the frozen ones put back.
  void place(const std::vector<Vec3>& points, bool onto_surface, const CellTriangles& cells) {
    project(index_, points, samples_, onto_surface, &mesh_, &cells);
    restore_frozen(initial_, options_.movable, samples_);
  }
  void lloyd_steps();
  void lbfgs();
  void choose_lbfgs_units();
  double objective(const Eigen::VectorXd& x, Eigen::VectorXd& grad);

  const SurfaceMesh& mesh_;
  const Samples& initial_;
  const CvtOptions& options_;
  const ClosestPointIndex& index_;
  const std::vector<double>* density_;
  const int n_;
  Samples samples_;
  CvtEnergy current_;
  CvtResult result_;
  int iteration_ = 0;
  // L-BFGS: the best evaluated state, the sheets the sites keep to, the scales of energy and positions.
  Samples best_;
  double best_energy_ = 0;
  int lbfgs_evaluations_ = 0;
  std::vector<Vec3> start_points_;
  CellTriangles cells_;
  double scale_ = 1, unit_ = 1, cell_size_ = 0;
};

// Lloyd: every sample moves to its cell's centroid, then back onto the surface.
void CvtSolver::lloyd_steps() {
  const int lloyd_steps = options_.optimizer == CvtOptimizer::Lloyd ? options_.iterations
                                                                    : std::min(options_.lloyd_warmup, options_.iterations);
  for (int step = 0; step < lloyd_steps; ++step) {
    const double before = current_.energy;
    const CellTriangles cells = options_.keep_to_sheets ? cell_triangles(current_.diagram) : CellTriangles();
    place(current_.cells.centroid, true, cells);
    current_ = cvt_energy(mesh_, samples_, options_.diagram, density_);
    ++result_.diagram_evaluations;
    ++iteration_;
    report(current_.energy);
    if (std::abs(before - current_.energy) <= options_.relative_energy_change * before) break;
  }
}

// The solver's scales of the energy and of the positions.
void CvtSolver::choose_lbfgs_units() {
  // The solver sees the energy times a power of two that puts it above 2^30: its energy-change
  // test, |f_k - f_k+1| <= delta · max(|f_k|, |f_k+1|, 1), is then relative, as the option
  // promises, also on a small model (Igea, 0.16 across, at 4000 samples: F ≈ 4e-8, and the
  // absolute 1e-9 stopped L-BFGS after 4 iterations). A power of two scales every value the
  // solver computes exactly, so a model whose energy stays above 1 takes the same steps.
  const int exponent = current_.energy > 0 && std::isfinite(current_.energy) ? std::ilogb(current_.energy) : 30;
  scale_ = std::ldexp(1.0, std::clamp(30 - exponent, 0, 600));
  // The solver's variables are the positions in a unit tied to the mean cell size h: its first
  // step moves the sites by one unit, so in the model's own unit the run would depend on the
  // unit (elk 516 scaled by 2^5: 95 evaluations, Qmin 0.561; by 2^-40: failed line searches,
  // Qmin 0.464). A power of two between h/16 and h/8 scales exactly: the run is the same at any
  // scale of the model (elk 516 scaled by 2^-40 ... 2^40: the same 124 diagrams and Qmin 0.645;
  // test "A remesh is the same in any unit").
  cell_size_ = std::sqrt(mesh_.area() / n_);
  unit_ = cell_size_ > 0 && std::isfinite(cell_size_) ? std::ldexp(1.0, std::ilogb(cell_size_) - 3) : 1.0;
}

// L-BFGS on the positions with the sites free in space: the diagram is defined for any site
// (its triangle is the closest one), so the energy is smooth where cells do not appear or
// vanish, and 2 m_i (x_i - c_i) is its exact gradient. Projecting inside each evaluation made
// the line search fail early (elk 516: Qmin 0.35 against 0.59). The best evaluated state is
// kept and put on the surface at the end.
void CvtSolver::lbfgs() {
  best_ = samples_;
  best_energy_ = current_.energy;
  // The solver's first call is at the starting point, whose energy and gradient are `current_`.
  start_points_ = samples_.positions;
  // The sites keep to the sheets of their cells at the start of the run.
  cells_ = options_.keep_to_sheets ? cell_triangles(current_.diagram) : CellTriangles();
  choose_lbfgs_units();
  LBFGSpp::LBFGSParam<double> param;
  param.epsilon = options_.relative_gradient * scale_ * unit_ * current_.energy / cell_size_;
  param.epsilon_rel = 0;
  param.past = 1;
  param.delta = options_.relative_energy_change;
  param.max_iterations = options_.iterations - iteration_;
  param.max_linesearch = 20;
  LBFGSpp::LBFGSSolver<double, CountedBacktracking> solver(param);
  Eigen::VectorXd x(3 * n_);
  for (int i = 0; i < n_; ++i)
    for (int c = 0; c < 3; ++c) x[3 * i + c] = samples_.positions[i][c] / unit_;
  double fx = 0;
  int lbfgs_iterations = 0;
  completed_line_searches = 0;
  auto f = [this](const Eigen::VectorXd& at, Eigen::VectorXd& grad) { return objective(at, grad); };
  try {
    lbfgs_iterations = solver.minimize(f, x, fx);
  } catch (const std::exception&) {
    // The line search can fail where the energy is not smooth (cells appearing or vanishing);
    // the best state seen so far stands. The iteration whose line search failed counts.
    result_.line_search_stopped = true;
    lbfgs_iterations = completed_line_searches + 1;
  }
  iteration_ += lbfgs_iterations;
  place(best_.positions, true, cells_);
  current_ = cvt_energy(mesh_, samples_, options_.diagram, density_);
  ++result_.diagram_evaluations;
  report(current_.energy);
}

// The scaled energy and gradient at the solver's x (positions in unit_), the best state kept.
double CvtSolver::objective(const Eigen::VectorXd& x, Eigen::VectorXd& grad) {
  ++lbfgs_evaluations_;
  const std::vector<Vec3> points = to_points(x * unit_);
  const bool at_start = lbfgs_evaluations_ == 1 && points == start_points_;
  place(points, false, cells_);
  const CvtEnergy evaluated = at_start ? CvtEnergy() : cvt_energy(mesh_, samples_, options_.diagram, density_);
  const CvtEnergy& e = at_start ? current_ : evaluated;
  if (!at_start) ++result_.diagram_evaluations;
  grad.resize(3 * n_);
  for (int i = 0; i < n_; ++i) {
    const bool moves = options_.movable.empty() || options_.movable[i];
    for (int c = 0; c < 3; ++c) grad[3 * i + c] = moves ? scale_ * unit_ * e.gradient[i][c] : 0.0;
  }
  if (e.energy < best_energy_) {
    best_energy_ = e.energy;
    best_ = samples_;
  }
  return scale_ * e.energy;
}

}  // namespace

CvtResult optimize_cvt(const SurfaceMesh& mesh, const Samples& initial, const CvtOptions& options,
                       const Diagram* diagram_of_initial, const ClosestPointIndex* shared_index) {
  check_cvt_inputs(mesh, initial, options, diagram_of_initial);
  const auto start = std::chrono::steady_clock::now();
  std::optional<ClosestPointIndex> own_index;
  if (!shared_index) own_index.emplace(mesh);
  const ClosestPointIndex& index = shared_index ? *shared_index : *own_index;
  std::vector<double> density_storage;
  const std::vector<double>* density = cvt_density(mesh, options, initial.size(), density_storage);
  CvtResult result = CvtSolver(mesh, initial, options, index, density).run(diagram_of_initial);
  result.time_s = seconds_since(start);
  return result;
}

}  // namespace lrvd
