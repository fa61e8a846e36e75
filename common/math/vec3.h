// Three-component vectors and points in double precision.
//
// The tracer works in double throughout: scenes translated by 10^8 or scaled by 10^-4 must
// keep enough bits for the error bounds of common/math/float_error.h to stay small.
#pragma once

#include <algorithm>
#include <cmath>

namespace tessera {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

  constexpr double operator[](int axis) const { return axis == 0 ? x : (axis == 1 ? y : z); }
  constexpr double& operator[](int axis) { return axis == 0 ? x : (axis == 1 ? y : z); }

  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  constexpr Vec3& operator-=(const Vec3& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  constexpr Vec3& operator*=(double s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

constexpr Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
constexpr Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
constexpr Vec3 operator*(Vec3 a, double s) { return a *= s; }
constexpr Vec3 operator*(double s, Vec3 a) { return a *= s; }
constexpr Vec3 operator/(const Vec3& a, double s) { return {a.x / s, a.y / s, a.z / s}; }

constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr Vec3 mul(const Vec3& a, const Vec3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline Vec3 abs(const Vec3& a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
inline Vec3 min(const Vec3& a, const Vec3& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 max(const Vec3& a, const Vec3& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
constexpr double length_squared(const Vec3& a) { return dot(a, a); }
inline double length(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline double max_component(const Vec3& a) { return std::max({a.x, a.y, a.z}); }
inline int max_axis(const Vec3& a) { return a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2); }
inline bool is_finite(const Vec3& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

// Normalizes `a`, or returns `fallback` when `a` has no usable direction (zero, subnormal
// length, or not finite). The tracer never divides by a zero length.
inline Vec3 normalize_or(const Vec3& a, const Vec3& fallback) {
  const double len = length(a);
  if (!(len > 1e-300) || !std::isfinite(len)) return fallback;
  return a / len;
}

// The unit vector along `v`, also for lengths whose square under- or overflows (1e-200,
// 1e300); zero when `v` has no direction (zero or not finite).
inline Vec3 unit_or_zero(const Vec3& v) {
  const double largest = max_component(abs(v));
  if (!(largest > 0) || !std::isfinite(largest)) return {};
  return normalize_or(v / largest, Vec3{});
}

}  // namespace tessera
