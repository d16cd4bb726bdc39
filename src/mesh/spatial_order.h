// Points in the order of a Morton (Z-order) curve: points near each other along the curve are near
// each other in space, so work done point after point in that order finds its data in the caches
// and can start from the previous point's answer.
#pragma once

#include <vector>

#include "predicates/vec3.h"

namespace lrvd {

//! The indices of `points` along a Morton curve through their bounding box (21 bits an axis over
//! its longest side; points in the same cell by index): order[k] is the k-th point on the curve.
std::vector<int> morton_order(const std::vector<Vec3>& points);

}  // namespace lrvd
