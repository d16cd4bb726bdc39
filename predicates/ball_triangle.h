// Whether a ball meets a triangle, decided exactly: the region growing of maximal Poisson-disk
// sampling (paper §4.2: "until the disk does not intersect with a neighboring triangle") and its
// verification both decide it here. Interval filter, rational fallback.
#pragma once

#include "predicates/vec3.h"

namespace lrvd {

//! Whether the open ball B(x, √w) meets the closed triangle abc: its distance from x is below √w,
//! exactly (x and the corners taken as the doubles they are). A degenerate triangle is its
//! segment or point.
bool ball_meets_triangle(const Vec3& x, double w, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace lrvd
