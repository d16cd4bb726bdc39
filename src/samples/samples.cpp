// Samples: uniform random sampling by area and location of given points by closest point.
#include "samples/samples.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <queue>
#include <stdexcept>
#include <sstream>

#include <fmt/format.h>

#include "common/error.h"
#include "common/text.h"
#include "io/mesh_writers.h"
#include "mesh/closest_point.h"
#include "mesh/surface_mesh.h"

namespace lrvd {

namespace {

uint64_t splitmix64(uint64_t& x) {
  uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

Vec3 point_in_triangle(const SurfaceMesh& mesh, int t, double u1, double u2, Vec3& bary) {
  const double r = std::sqrt(u1);
  bary = {1 - r, r * (1 - u2), r * u2};
  const Triangle& tri = mesh.triangle(t);
  return bary.x * mesh.position(tri[0]) + bary.y * mesh.position(tri[1]) + bary.z * mesh.position(tri[2]);
}

Random::Random(uint64_t seed) {
  for (auto& s : state_) s = splitmix64(seed);
}

uint64_t Random::next() {  // xoshiro256**
  const uint64_t result = rotl(state_[1] * 5, 7) * 9;
  const uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = rotl(state_[3], 45);
  return result;
}

double Random::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

void check_samples(const SurfaceMesh& mesh, const Samples& samples) {
  const std::size_t n = samples.positions.size();
  const auto length = [n](std::size_t size, const char* field) {
    if (size != n)
      throw InputError(fmt::format("the samples have {} positions but {} {}: one each", n, size, field));
  };
  length(samples.triangles.size(), "triangles");
  length(samples.barycentric.size(), "barycentric coordinates");
  if (!samples.weights.empty()) length(samples.weights.size(), "weights");
  for (std::size_t i = 0; i < n; ++i) {
    if (samples.triangles[i] < 0 || samples.triangles[i] >= mesh.triangle_count())
      throw InputError(fmt::format("sample {} is not located on a triangle of the mesh (triangle {} of {})", i,
                                   samples.triangles[i], mesh.triangle_count()));
    if (!is_finite(samples.positions[i])) throw InputError(fmt::format("sample {} has a non-finite coordinate", i));
    if (!samples.weights.empty() && !std::isfinite(samples.weights[i]))
      throw InputError(fmt::format("sample {} has a non-finite weight", i));
  }
}

Samples sample_uniform(const SurfaceMesh& mesh, int n, uint64_t seed) {
  if (n < 1) throw InputError(fmt::format("the number of samples must be at least 1 (got {})", n));
  require_workable_model(mesh, "sampling");
  const int components = mesh.component_count();
  if (n < components)
    throw InputError(fmt::format("{} sample{} cannot cover the mesh's {} connected components: each needs one",
                                 n, n == 1 ? "" : "s", components));
  const int m = mesh.triangle_count();
  std::vector<double> cumulative(m);
  double total = 0;
  for (int t = 0; t < m; ++t) cumulative[t] = (total += mesh.triangle_area(t));

  // Per-component cumulative areas for the first sample of each component.
  std::vector<std::vector<int>> component_triangles(components);
  for (int t = 0; t < m; ++t) component_triangles[mesh.triangle_components()[t]].push_back(t);

  Random random(seed);
  Samples samples;
  samples.positions.resize(n);
  samples.triangles.resize(n);
  samples.barycentric.resize(n);
  auto pick = [&](const std::vector<int>* subset) {
    if (!subset) {
      const double target = random.uniform() * total;
      return std::min<int>(static_cast<int>(std::upper_bound(cumulative.begin(), cumulative.end(), target) -
                                            cumulative.begin()), m - 1);
    }
    double area = 0;
    for (int t : *subset) area += mesh.triangle_area(t);
    const double target = random.uniform() * area;
    double running = 0;
    for (int t : *subset)
      if ((running += mesh.triangle_area(t)) > target) return t;
    return subset->back();
  };
  for (int i = 0; i < n; ++i) {
    const int t = pick(i < components ? &component_triangles[i] : nullptr);
    const double u1 = random.uniform(), u2 = random.uniform();
    samples.triangles[i] = t;
    samples.positions[i] = point_in_triangle(mesh, t, u1, u2, samples.barycentric[i]);
  }
  return samples;
}

Samples sample_by_component(const SurfaceMesh& mesh, int n, uint64_t seed, const std::vector<int>& minimum) {
  require_workable_model(mesh, "sampling");
  if (n < 1) throw InputError(fmt::format("the number of samples must be at least 1 (got {})", n));
  if (std::any_of(minimum.begin(), minimum.end(), [](int m) { return m < 1; }))
    throw std::invalid_argument("sample_by_component: every component's minimum is at least 1");
  const int components = mesh.component_count();
  if (static_cast<int>(minimum.size()) != components)
    throw std::invalid_argument("sample_by_component: one minimum per component");
  const long long fewest = std::accumulate(minimum.begin(), minimum.end(), 0LL);
  if (n < fewest)
    throw InputError(fmt::format("{} sample{} too few for the mesh's {} components: they need {} at least", n,
                                 n == 1 ? " is" : "s are", components, fewest));
  // Each component's triangles with their cumulative areas.
  std::vector<std::vector<int>> triangles(components);
  std::vector<std::vector<double>> cumulative(components);
  std::vector<double> area(components, 0.0);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const int c = mesh.triangle_components()[t];
    triangles[c].push_back(t);
    cumulative[c].push_back(area[c] += mesh.triangle_area(t));
  }
  const double total = std::accumulate(area.begin(), area.end(), 0.0);
  // Each further sample to the component furthest below its share n · area / total (the least
  // index among ties).
  std::vector<int> count(minimum);
  std::priority_queue<std::pair<double, int>> below;  // (shortfall, -component)
  for (int c = 0; c < components; ++c) below.push({n * area[c] / total - count[c], -c});
  for (long long given = fewest; given < n; ++given) {
    auto [short_by, c] = below.top();
    below.pop();
    ++count[-c];
    below.push({short_by - 1, c});
  }
  Random random(seed);
  Samples samples;
  samples.positions.resize(n);
  samples.triangles.resize(n);
  samples.barycentric.resize(n);
  int i = 0;
  for (int c = 0; c < components; ++c)
    for (int k = 0; k < count[c]; ++k, ++i) {
      const std::vector<double>& cum = cumulative[c];
      const double target = random.uniform() * area[c];
      const size_t at = std::min<size_t>(std::upper_bound(cum.begin(), cum.end(), target) - cum.begin(), cum.size() - 1);
      const int t = triangles[c][at];
      const double u1 = random.uniform(), u2 = random.uniform();
      samples.triangles[i] = t;
      samples.positions[i] = point_in_triangle(mesh, t, u1, u2, samples.barycentric[i]);
    }
  return samples;
}

Samples locate_points(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const std::vector<double>& weights,
                      const std::vector<int>& lines) {
  if (points.empty()) throw InputError("no sample points were given");
  require_workable_size(mesh, "locating points");
  if (!weights.empty() && weights.size() != points.size())
    throw InputError(fmt::format("{} weights were given for {} points", weights.size(), points.size()));
  const auto label = [&](std::size_t i) {
    return i < lines.size() ? fmt::format("{} (line {})", i, lines[i]) : std::to_string(i);
  };
  const double diagonal = mesh.bounding_box().diagonal();
  const double tolerance = 0.01 * diagonal;
  ClosestPointIndex index(mesh);
  Samples samples;
  samples.weights = weights;
  std::vector<char> component_hit(mesh.component_count(), 0);
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (!is_finite(p)) throw InputError(fmt::format("point {} has a non-finite coordinate", label(i)));
    if (!weights.empty() && !std::isfinite(weights[i]))
      throw InputError(fmt::format("point {} has a non-finite weight", label(i)));
    const ClosestPoint c = index.query(p);
    if (c.distance > tolerance) {
      // Three digits, or as many as tell the two apart.
      std::string far = fmt::format("{:.3g}", c.distance), limit = fmt::format("{:.3g}", tolerance);
      if (far == limit) far = fmt::format("{:.17g}", c.distance), limit = fmt::format("{:.17g}", tolerance);
      throw InputError(fmt::format("point {} at ({}, {}, {}) is {} the surface, farther than {} (1% of the "
                                   "bounding-box diagonal, {:.4g}), up to which a point is moved onto it",
                                   label(i), p.x, p.y, p.z,
                                   std::isfinite(c.distance) ? far + " from" : std::string("too far to measure from"),
                                   limit, diagonal));
    }
    samples.positions.push_back(c.point);
    samples.triangles.push_back(c.triangle);
    // Inside the triangle near an edge, 1 - v - w can round to a hair below zero (a point given
    // on a refined mesh's edge): the closest point is in the closed triangle, so its coordinates
    // are not negative.
    samples.barycentric.push_back({std::max(c.barycentric.x, 0.0), std::max(c.barycentric.y, 0.0),
                                   std::max(c.barycentric.z, 0.0)});
    component_hit[mesh.triangle_components()[c.triangle]] = 1;
  }
  // Coincident samples have no bisector between them: refuse them, naming the first point that
  // repeats an earlier one, and that one.
  std::vector<int> order(points.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  auto less = [&](int a, int b) {
    const Vec3 &pa = samples.positions[a], &pb = samples.positions[b];
    return std::tie(pa.x, pa.y, pa.z, a) < std::tie(pb.x, pb.y, pb.z, b);
  };
  std::sort(order.begin(), order.end(), less);
  // In each run of equal positions the first entry has the lowest index and the second repeats it.
  int first = -1, repeat = -1;
  for (size_t k = 1; k < order.size(); ++k)
    if (samples.positions[order[k]] == samples.positions[order[k - 1]] &&
        (k == 1 || samples.positions[order[k - 1]] != samples.positions[order[k - 2]]) &&
        (repeat < 0 || order[k] < repeat))
      first = order[k - 1], repeat = order[k];
  if (repeat >= 0)
    throw InputError(fmt::format("points {} and {} coincide on the surface; remove one", label(first), label(repeat)));
  for (int c = 0; c < mesh.component_count(); ++c)
    if (!component_hit[c]) {
      int first = 0;
      while (mesh.triangle_components()[first] != c) ++first;
      throw InputError(fmt::format("connected component {} of the mesh (containing triangle {}) has no sample "
                                   "point; every component needs at least one",
                                   c, first));
    }
  return samples;
}

namespace {

// The file at `path` opened for reading, or InputError naming it as a `kind` file ("point",
// "weight"): a folder, a file that is not a regular one, a file that cannot be opened.
std::ifstream open_input_file(const std::string& path, const char* kind) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InputError(fmt::format("{} file '{}' is a folder", kind, path));
  if (std::string problem = special_file_problem(path); !problem.empty())
    throw InputError(fmt::format("{} file '{}' {}", kind, path, problem));
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("cannot read {} file '{}'", kind, path));
  return in;
}

}  // namespace

PointFile read_xyz(const std::string& path) {
  std::ifstream in = open_input_file(path, "point");
  PointFile file;
  std::string line;
  int columns = 0;
  for (int number = 1; std::getline(in, line); ++number) {
    if (number == 1) skip_byte_order_mark(line);
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    std::vector<double> values;
    std::string token;
    while (fields >> token) {
      try {
        size_t used = 0;
        values.push_back(std::stod(token, &used));
        if (used != token.size()) throw std::invalid_argument(token);
      } catch (const std::exception&) {
        throw InputError(fmt::format("{}:{}: '{}' is not a number", path, number, shown(token)));
      }
    }
    if (values.size() != 3 && values.size() != 4)
      throw InputError(fmt::format("{}:{}: expected 'x y z' or 'x y z w', got {} values", path, number, values.size()));
    if (columns == 0) columns = static_cast<int>(values.size());
    if (columns != static_cast<int>(values.size()))
      throw InputError(fmt::format("{}:{}: every line must have the same number of columns ({})", path, number, columns));
    file.points.push_back({values[0], values[1], values[2]});
    file.lines.push_back(number);
    if (columns == 4) file.weights.push_back(values[3]);
  }
  if (file.points.empty()) throw InputError(fmt::format("point file '{}' holds no points", path));
  return file;
}

std::vector<double> read_weights(const std::string& path) {
  std::ifstream in = open_input_file(path, "weight");
  std::vector<double> weights;
  std::string line;
  // One weight a line, as the points it goes with; blank lines and '#' comments as in point files.
  for (int number = 1; std::getline(in, line); ++number) {
    if (number == 1) skip_byte_order_mark(line);
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    std::string token, more;
    fields >> token;
    try {
      size_t used = 0;
      weights.push_back(std::stod(token, &used));
      if (used != token.size() || !std::isfinite(weights.back())) throw std::invalid_argument(token);
    } catch (const std::exception&) {
      throw InputError(fmt::format("{}:{}: '{}' is not a finite number", path, number, shown(token)));
    }
    if (fields >> more)
      throw InputError(fmt::format("{}:{}: expected one weight a line, got '{}' after it", path, number, shown(more)));
  }
  if (weights.empty()) throw InputError(fmt::format("weight file '{}' holds no weights", path));
  return weights;
}

void write_xyz(const std::string& path, const std::vector<Vec3>& points, const std::vector<double>& weights) {
  if (!weights.empty() && weights.size() != points.size())
    throw InputError(fmt::format("write_xyz: {} weights for {} points", weights.size(), points.size()));
  fmt::memory_buffer out;
  for (size_t i = 0; i < points.size(); ++i) {
    fmt::format_to(std::back_inserter(out), "{:.17g} {:.17g} {:.17g}", points[i].x, points[i].y, points[i].z);
    if (!weights.empty()) fmt::format_to(std::back_inserter(out), " {:.17g}", weights[i]);
    out.push_back('\n');
  }
  write_text_file(path, {out.data(), out.size()});
}

}  // namespace lrvd
