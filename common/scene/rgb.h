// Linear RGB triples: colours, intensities and weights of the lighting model.
#pragma once

#include <algorithm>
#include <cmath>

namespace tessera {

struct Rgb {
  double r = 0, g = 0, b = 0;

  constexpr Rgb() = default;
  constexpr Rgb(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}
  static constexpr Rgb gray(double v) { return {v, v, v}; }

  constexpr Rgb& operator+=(const Rgb& o) {
    r += o.r;
    g += o.g;
    b += o.b;
    return *this;
  }
  constexpr Rgb& operator*=(double s) {
    r *= s;
    g *= s;
    b *= s;
    return *this;
  }
  constexpr bool is_zero() const { return r == 0 && g == 0 && b == 0; }
  friend constexpr bool operator==(const Rgb&, const Rgb&) = default;
};

constexpr Rgb operator+(Rgb a, const Rgb& b) { return a += b; }
constexpr Rgb operator*(Rgb a, double s) { return a *= s; }
constexpr Rgb operator*(double s, Rgb a) { return a *= s; }
constexpr Rgb operator*(const Rgb& a, const Rgb& b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
inline bool is_finite(const Rgb& c) {
  return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
}

}  // namespace tessera
