// Verification of a remesh (the dual of a diagram, or any triangle mesh checked against its
// input): vertex count, closed 2-manifold, genus per component, orientation, degenerate and
// self-intersecting triangles.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "mesh/surface_mesh.h"
#include "verification/report.h"

namespace lrvd {

struct RemeshVerification {
  bool passed = true;  //!< every promised property holds (`closed` is promised only for a closed input)
  double time_s = 0;
  PropertyResult vertex_count;        //!< exactly the requested number of vertices, all used
  PropertyResult manifold;            //!< every edge in one or two triangles, every vertex one fan, no repeated/duplicate triangle
  PropertyResult closed;              //!< no boundary edge when the input is closed
  PropertyResult oriented;            //!< each interior edge traversed once in each direction
  PropertyResult topology;            //!< same components and per-component Euler characteristic as the input
                                      //!< (for a closed input with each hole capped, so a hole fails `closed` only)
  PropertyResult non_degenerate;      //!< no triangle with (exactly) collinear corners
  PropertyResult no_self_intersection;  //!< no two triangles intersect beyond their shared elements
                                        //!< (but for the input's own: see inherited_intersecting_pairs)
  //! Of the output: components joined across edges, Σ of their V - E + F, Σ of their genus
  //! (2 - χ - boundary loops) / 2, or -1 when the output is not manifold.
  int components = 0, euler_characteristic = 0, genus = 0;
  int boundary_loops = 0, input_boundary_loops = 0;  //!< reported; promised equal only through `topology`
  int self_intersecting_pairs = 0;       //!< intersecting pairs that count as violations
  int inherited_intersecting_pairs = 0;  //!< pairs between two components lying on input components that meet
  nlohmann::json to_json() const;
  std::string summary() const;
};

//! Checks `triangles` over `positions` as a remesh of `input` that must have `expected_vertices`
//! vertices (pass -1 to skip that check).
RemeshVerification verify_remesh(const SurfaceMesh& input, const std::vector<Vec3>& positions,
                                 const std::vector<Triangle>& triangles, int expected_vertices);

}  // namespace lrvd
