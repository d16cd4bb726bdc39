// Vec3: the plain double 3-vector every layer of lrvd uses for positions.
#pragma once

#include <cmath>

namespace lrvd {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  double& operator[](int c) { return c == 0 ? x : (c == 1 ? y : z); }
  double operator[](int c) const { return c == 0 ? x : (c == 1 ? y : z); }
  Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
  Vec3& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
};

inline Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
inline Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
inline Vec3 operator*(Vec3 a, double s) { return a *= s; }
inline Vec3 operator*(double s, Vec3 a) { return a *= s; }
inline Vec3 operator/(Vec3 a, double s) { return a *= (1.0 / s); }
inline bool operator==(const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
inline bool operator!=(const Vec3& a, const Vec3& b) { return !(a == b); }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double squared_norm(const Vec3& a) { return dot(a, a); }
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline double squared_distance(const Vec3& a, const Vec3& b) { return squared_norm(a - b); }
inline double distance(const Vec3& a, const Vec3& b) { return norm(a - b); }
inline bool is_finite(const Vec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
//! a / |a|, or the zero vector for the zero vector.
inline Vec3 unit(const Vec3& a) {
  const double n = norm(a);
  return n > 0 ? a / n : Vec3{};
}
//! The unit normal of triangle (a, b, c), counterclockwise; the zero vector when it has no area.
inline Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c) { return unit(cross(b - a, c - a)); }

}  // namespace lrvd
