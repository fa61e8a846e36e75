#include "common/texture/solid_texture.h"

#include <cmath>
#include <numbers>

#include "common/math/portable_math.h"
#include "common/texture/perlin_noise.h"

namespace tessera {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
// Octaves of marble's turbulence, and the noise frequency of cow spots (spots about a third
// of a generic shape across): neither is a parameter in the manual.
constexpr int kMarbleOctaves = 6;
constexpr double kCowSpotFrequency = 3;

// A coordinate measured in units of `scale`; 0 when the scale is 0.
double scaled(double coordinate, double scale) { return scale != 0 ? coordinate / scale : 0; }

bool is_even_cell(double v) { return std::fmod(std::floor(v), 2.0) == 0; }

Rgb grey(double v) { return {v, v, v}; }

// White on the contour lines (d an integer), black half-way between them.
double contour(double d) { return (1 + tessera::cos(kTwoPi * d)) / 2; }

double distance2(DistanceMeasure measure, double u, double v) {
  switch (measure) {
    case DistanceMeasure::Euclid:
      return std::hypot(u, v);
    case DistanceMeasure::Manhattan:
      return std::fabs(u) + std::fabs(v);
    case DistanceMeasure::SinSin:
      return tessera::sin(kTwoPi * u) * tessera::sin(kTwoPi * v);
    case DistanceMeasure::SinCos:
      return tessera::sin(kTwoPi * u) * tessera::cos(kTwoPi * v);
  }
  return 0;
}

struct Evaluate {
  const Vec3& p;

  Vec3 cell_coordinates(const Vec3& scale) const {
    return {scaled(p.x, scale.x), scaled(p.y, scale.y), scaled(p.z, scale.z)};
  }

  Rgb operator()(const Checkerboard3D& c) const {
    const Vec3 q = cell_coordinates(c.scale);
    return grey(is_even_cell(std::floor(q.x) + std::floor(q.y) + std::floor(q.z)) ? 1 : 0);
  }
  Rgb operator()(const ColourBars& c) const {
    const Vec3 q = cell_coordinates(c.scale);
    return {is_even_cell(q.x) ? 1.0 : 0.0, is_even_cell(q.y) ? 1.0 : 0.0,
            is_even_cell(q.z) ? 1.0 : 0.0};
  }
  Rgb operator()(const RgbCubes& c) const {
    const Vec3 q = cell_coordinates(c.scale);
    return {q.x - std::floor(q.x), q.y - std::floor(q.y), q.z - std::floor(q.z)};
  }
  Rgb operator()(const Contours1& c) const { return grey(contour(scaled(p[c.axis], c.scale))); }
  Rgb operator()(const Contours2& c) const {
    const double u = scaled(p[c.first_axis], c.first_scale);
    const double v = scaled(p[c.second_axis], c.second_scale);
    return grey(contour(distance2(c.measure, u, v)));
  }
  Rgb operator()(const Contours3& c) const {
    const Vec3 q = cell_coordinates(c.scale);
    const double d = c.measure == DistanceMeasure::Manhattan
                         ? std::fabs(q.x) + std::fabs(q.y) + std::fabs(q.z)
                         : std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
    return grey(contour(d));
  }
  Rgb operator()(const WoodGrain& w) const {
    const double r = std::hypot(p.x, p.y);
    const double theta = tessera::atan2(p.y, p.x);
    const double q = scaled(r, w.ring_thickness) +
                     w.wobble_strength * tessera::sin(w.wobbles * theta + w.twist * p.z);
    if (!w.smooth) return is_even_cell(q) ? w.first : w.second;
    const double f =
        (1 - tessera::cos(std::numbers::pi * q)) / 2;  // first at even q, second at odd
    return w.first * (1 - f) + w.second * f;
  }
  Rgb operator()(const Marble& m) const {
    const double phase = kTwoPi * p[m.axis] + m.turbulence * turbulence(p, kMarbleOctaves);
    return m.weights * ((1 + tessera::sin(phase)) / 2);
  }
  Rgb operator()(const CowSpots& c) const {
    const double n = (1 + perlin_noise(p * kCowSpotFrequency)) / 2;
    return grey(n > c.threshold ? 0 : 1);
  }
};

}  // namespace

std::optional<SolidPattern> make_solid_pattern(const SolidTexture& texture) {
  const std::vector<double>& a = texture.params;
  const auto axis = [&](std::size_t i) { return static_cast<int>(a.at(i)); };
  const auto vec = [&](std::size_t i) { return Vec3{a.at(i), a.at(i + 1), a.at(i + 2)}; };
  const auto rgb = [&](std::size_t i) { return Rgb{a.at(i), a.at(i + 1), a.at(i + 2)}; };
  const auto measure = [&](std::size_t i) { return static_cast<DistanceMeasure>(axis(i)); };
  switch (texture.type) {
    case 1:
      return Checkerboard3D{vec(0)};
    case 2:
      return ColourBars{vec(0)};
    case 3:
      return RgbCubes{vec(0)};
    case 4:
      return Contours1{axis(0), a.at(1)};
    case 5: {
      // The manual's planes: 0 is X and Y, 1 is Y and Z, 2 is X and Z.
      constexpr int kFirst[3] = {0, 1, 0}, kSecond[3] = {1, 2, 2};
      return Contours2{kFirst[axis(0)], kSecond[axis(0)], measure(1), a.at(2), a.at(3)};
    }
    case 6:
      return Contours3{measure(0), vec(1)};
    case 7:
      return WoodGrain{a.at(0), a.at(1), a.at(2), a.at(3), rgb(4), rgb(7), a.at(10) != 0};
    case 8:
      return Marble{axis(0), a.at(1), rgb(2)};
    case 9:
      return CowSpots{a.at(0)};
    default:
      return std::nullopt;
  }
}

Rgb solid_texture_colour(const SolidPattern& pattern, const Vec3& p) {
  return std::visit(Evaluate{p}, pattern);
}

}  // namespace tessera
