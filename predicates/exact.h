// Exact rational positions of symbolic vertices (paper §3.6), for verification only: this header
// pulls in GMP, so the hot code includes predicates/symbolic_vertex.h instead.
#pragma once

#include <array>
#include <optional>

#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>

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

//! The exact parameter of a type B vertex along its edge: 0 at v[0], 1 at v[1].
//! \throw std::domain_error when the edge is parallel to the bisector (the vertex does not exist).
CGAL::Gmpq exact_edge_parameter(const SymbolicVertex& q, const SymbolicContext& ctx);

//! Intervals that hold the exact position of a vertex (and, type B, its edge parameter),
//! evaluated from the defining doubles in interval arithmetic: a filter in front of the rationals.
struct PositionEnclosure {
  std::array<CGAL::Interval_nt<false>, 3> box;
  CGAL::Interval_nt<false> parameter{0};  //!< type B only: encloses exact_edge_parameter
};
//! The enclosure of q's position, with finite bounds; nullopt when the intervals cannot tell
//! whether q exists (its formula's denominator holds zero) or overflow, and exact_position decides.
std::optional<PositionEnclosure> enclose_position(const SymbolicVertex& q, const SymbolicContext& ctx);

//! Exact power distance |q - p|^2 - w.
CGAL::Gmpq exact_power_distance(const ExactPoint& q, const Site& s);

//! The sign of the power distance of q's exact position to s, from q's interval enclosure; nullopt
//! when the enclosure cannot tell it, and exact_power_distance(exact_position(q, ctx), s) decides.
std::optional<CGAL::Sign> enclosed_power_sign(const SymbolicVertex& q, const Site& s, const SymbolicContext& ctx);

//! Exact point from doubles.
ExactPoint to_exact(const Vec3& p);
//! Whether the open ball B(x, √w) meets the closed triangle abc, in rationals (ball_triangle.h
//! decides it for a centre given in doubles).
bool ball_meets_triangle(const ExactPoint& x, const CGAL::Gmpq& w, const Vec3& a, const Vec3& b, const Vec3& c);

//! Nearest doubles (each coordinate rounded independently).
Vec3 to_double(const ExactPoint& p);

}  // namespace lrvd
