// Samples: the generating points of a diagram, each located on the mesh (triangle + barycentric),
// with optional power weights. Random sampling by area, or points read from a .xyz file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "predicates/vec3.h"

namespace lrvd {

class SurfaceMesh;

struct Samples {
  std::vector<Vec3> positions;
  std::vector<double> weights;      // power weights (radius²); empty for a Voronoi diagram
  std::vector<int> triangles;       // triangle holding each sample
  std::vector<Vec3> barycentric;    // coordinates of each sample in its triangle

  int size() const { return static_cast<int>(positions.size()); }
  bool weighted() const { return !weights.empty(); }
  double weight(int i) const { return weights.empty() ? 0.0 : weights[i]; }
};

//! Refuses samples a diagram cannot be built from: vectors of different lengths (triangles,
//! barycentric, and weights when there are any, one per position), a triangle index outside the
//! mesh, a non-finite position or weight. Names the first offending sample or vector.
//! \throw InputError
void check_samples(const SurfaceMesh& mesh, const Samples& samples);

//! n points uniformly distributed by area, reproducible from the seed on every machine. Every
//! connected component of the mesh receives at least one sample (the first ones), the rest are
//! drawn over the whole surface.
//! \throw InputError when n < 1 or n is smaller than the number of components.
Samples sample_uniform(const SurfaceMesh& mesh, int n, uint64_t seed);

//! n points uniformly distributed by area within each connected component, the components given
//! counts in proportion to their areas but at least minimum[c] each (then each further sample to
//! the component furthest below its share). For a CVT, whose samples keep to their components.
//! \throw InputError when the mesh is empty, n < 1 or n is smaller than the sum of the minima;
//!        std::invalid_argument when `minimum` does not hold one count of at least 1 per component.
Samples sample_by_component(const SurfaceMesh& mesh, int n, uint64_t seed, const std::vector<int>& minimum);

//! Locates points on the mesh by closest point and moves each onto it. `lines`, when given (one
//! per point: where a file has it), is named with the point in the messages.
//! \throw InputError when a point is not finite, farther from the surface than 1% of the bounding
//!        box diagonal, when two points coincide, or when a component of the mesh gets no point.
Samples locate_points(const SurfaceMesh& mesh, const std::vector<Vec3>& points,
                      const std::vector<double>& weights = {}, const std::vector<int>& lines = {});

struct PointFile {
  std::vector<Vec3> points;
  std::vector<double> weights;  // empty unless every line has a 4th column
  std::vector<int> lines;       // the line of each point in the file, from 1
};

//! Reads `x y z [w]` lines (blank lines and lines starting with '#' are skipped).
//! \throw InputError on an unreadable file, a malformed line, or a mix of 3- and 4-column lines.
PointFile read_xyz(const std::string& path);

//! Reads one finite weight a line (blank lines and lines starting with '#' are skipped), as
//! --weights gives them.
//! \throw InputError on an unreadable file, a malformed line or a file without weights.
std::vector<double> read_weights(const std::string& path);
void write_xyz(const std::string& path, const std::vector<Vec3>& points, const std::vector<double>& weights = {});

//! The point of triangle t at barycentric coordinates (1 - r, r (1 - u2), r u2), r = sqrt(u1), which
//! `bary` receives: uniform by area over the triangle for u1 and u2 uniform in [0, 1).
Vec3 point_in_triangle(const SurfaceMesh& mesh, int t, double u1, double u2, Vec3& bary);

//! Reproducible uniform doubles in [0, 1) from a 64-bit seed (same on every platform).
class Random {
 public:
  explicit Random(uint64_t seed);
  double uniform();
  uint64_t next();

 private:
  uint64_t state_[4];
};

}  // namespace lrvd
