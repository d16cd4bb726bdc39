// Self-intersections of a triangle mesh or soup, decided exactly.
#pragma once

#include <utility>
#include <vector>

#include "mesh/surface_mesh.h"

namespace lrvd {

//! Vertices of at least this many tested triangles are hubs to find_self_intersections.
inline constexpr int kCrossingHubValence = 64;

//! Pairs (s, t), s < t, of triangles that meet anywhere but in the vertices or the edge they share,
//! in increasing order. Only triangles with testable[t] != 0 take part (all when it is empty);
//! \pre the tested triangles have three distinct, non-collinear corners.
//! Round a vertex of `hub_valence` or more tested triangles (a hub: a fan's centre), whose boxes all
//! hold it, the search meets a pair of its triangles only when the edge of one away from the hub
//! comes near the other (not every pair); the answer does not depend on `hub_valence`, which tests
//! vary.
std::vector<std::pair<int, int>> find_self_intersections(const std::vector<Vec3>& positions,
                                                         const std::vector<Triangle>& triangles,
                                                         const std::vector<char>& testable = {},
                                                         int hub_valence = kCrossingHubValence);

//! Whether triangles f and g meet anywhere but in the vertices or the edge they share: the pair
//! test of find_self_intersections (exact). \pre f and g have three distinct, non-collinear corners.
bool triangles_cross(const std::vector<Vec3>& positions, const Triangle& f, const Triangle& g);

//! The triangles find_self_intersections can take: three distinct corners, not collinear (exact).
std::vector<char> proper_triangles(const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles);

//! The pairs (a, b), a < b, of connected components (SurfaceMesh::triangle_components) that meet,
//! sorted: where a self-intersecting surface such as two interpenetrating spheres (paper Fig. 11)
//! cuts through itself.
std::vector<std::pair<int, int>> intersecting_component_pairs(const SurfaceMesh& mesh);

//! Connected component of each triangle of a triangle soup (triangles joined through shared
//! vertices); -1 for triangles with testable[t] == 0.
std::vector<int> soup_components(int vertex_count, const std::vector<Triangle>& triangles,
                                 const std::vector<char>& testable);

}  // namespace lrvd
