// Small 3D vectors over an exact or interval number type, for the predicates' own .cpp files
// (exact positions, ball-triangle tests): not part of the predicates' interface.
#pragma once

#include "predicates/vec3.h"

namespace lrvd::detail {

// A vector of any number type (CGAL::Gmpq for exact values, CGAL::Interval_nt for enclosures).
template <class NT>
struct V3 {
  NT x, y, z;
};

template <class NT>
V3<NT> lift(const Vec3& a) {
  return {NT(a.x), NT(a.y), NT(a.z)};
}
template <class NT>
V3<NT> operator-(const V3<NT>& a, const V3<NT>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class NT>
V3<NT> operator+(const V3<NT>& a, const V3<NT>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class NT>
V3<NT> operator*(const NT& s, const V3<NT>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class NT>
NT dot(const V3<NT>& a, const V3<NT>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class NT>
V3<NT> cross(const V3<NT>& a, const V3<NT>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

}  // namespace lrvd::detail
