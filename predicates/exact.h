// Exact rational positions of symbolic vertices (paper §3.6), for verification only: this header
// pulls in GMP, so the hot code includes predicates/symbolic_vertex.h instead.
#pragma once

#include <CGAL/Gmpq.h>

#include "predicates/symbolic_vertex.h"

namespace lrvd {

//! A point with rational coordinates.
struct ExactPoint {
  CGAL::Gmpq x, y, z;
};

//! The exact position of q (the unperturbed point: the limit of the perturbed one). Type B lies on
//! the line of its edge, type C on the plane of its triangle; both exactly on their bisectors.
//! \pre the vertex exists: type B's edge is not parallel to its bisector, type C's plane and
//!      bisectors meet in one point. \throw std::domain_error otherwise.
ExactPoint exact_position(const SymbolicVertex& q, const SymbolicContext& ctx);

//! Exact power distance |q - p|^2 - w.
CGAL::Gmpq exact_power_distance(const ExactPoint& q, const Site& s);

//! Exact point from doubles.
ExactPoint to_exact(const Vec3& p);

//! Nearest doubles (each coordinate rounded independently).
Vec3 to_double(const ExactPoint& p);

}  // namespace lrvd
