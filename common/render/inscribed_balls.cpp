#include "common/render/inscribed_balls.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

#include "common/math/float_error.h"

namespace tessera {

namespace {

// A torus gets this many balls, centred on a circle about its axis (below): a cell of the light
// buffer is settled by one ball that covers it alone, and more balls (128) settled 0.2 % more
// feelers on features/torus.sdl.
constexpr int kTorusBalls = 32;

// A ball's radius, as a share of the largest that fits: the feeler's line passes within this
// share of it from the centre (the cells' test, in world space)...
constexpr double kCovered = 0.97;
// ...and, after the rounding of the object ray (bounded below to the difference), within this
// share in object space, where the shape's test decides.
constexpr double kInside = 0.98;

// The instance's transform taken as |world point| + |translation|, over the least singular
// value: a bound on the object-space size of a feeler's points and of the terms its transform
// adds up, for a feeler of length `length` (its points are at most |light| + length from the
// world origin).
struct ObjectSize {
  double light_part, per_length;  // size = light_part + per_length * length
};

// The longest feeler (world length) whose object-space size stays under `size_limit`.
double longest_feeler(const ObjectSize& size, double size_limit) {
  return (size_limit - size.light_part) / size.per_length;
}

// A torus (shapes.h; solid where the torus function F = ((rho - R)^2 + z^2 - r^2)
// ((rho + R)^2 + z^2 - r^2) < 0). Its balls are centred on the circle rho = c = max(R, r), z = 0,
// of radius up to m = min(r, R): in a meridian half-plane, where a ball's points lie within its
// radius of its centre's (rho is 1-Lipschitz), the disc of radius m about (c, 0) lies inside the
// tube's disc about (R, 0) (|c - R| + m = r) and outside the far one about (-R, 0) (c + R - m =
// max(R, r) >= r), whose overlap, a spindle's lemon, has F > 0. (A ring or horn torus has c = R,
// m = r; a spindle's balls, about the core circle, could be no larger than 2R - r.)
// Why a feeler through a ball is blocked: its object ray passes through a point q within
// b = kInside m of the circle, where F <= -(r^2 - (|c - R| + b)^2)((c + R - b)^2 - r^2) < 0
// (the near factor at most (|c - R| + b)^2 - r^2; the far one at least (c + R - b)^2 - r^2). The
// ray then goes on to the light, outside the torus's padded box (torus.cpp's `padded_box_span`,
// which "certainly holds the rounded surface": the quartic the search forms is positive beyond
// the box). So the search's quartic, clearly negative at q (below the bound that
// `crosses_into_tube` takes for its rounding, 2^15 eps (R + r)^3 (R + r + |o|_1 + |d|_1 t)), is
// positive just past the span's end, which lies before the light (t < 1 = t_max): it has a root
// between, at least |o - q| from the origin, so further than any hit's error bound; the search
// reports it, or an earlier hit. Every proof that ends that search early (a miss, or an exit for
// good) is of the exact ray, which meets the solid at q, or of a quartic without a root.
void torus_balls(const Torus& torus, const Instance& instance, const Vec3& light,
                 const SingularValues& sv, const ObjectSize& size,
                 std::vector<InscribedBall>& out) {
  const double big_r = torus.torus_radius, r = torus.tube_radius, e = big_r + r;
  const double c = std::max(big_r, r), m = std::min(big_r, r);
  if (!(m > 0)) return;
  const Vec3 l = instance.to_object.apply_point(light);
  constexpr double kLightMargin = 1 + 1e-6;  // the box is padded by 1e-9
  if (!(std::fabs(l.x) > e * kLightMargin || std::fabs(l.y) > e * kLightMargin ||
        std::fabs(l.z) > r * kLightMargin))
    return;
  const double world_radius = kCovered * m * sv.least * (1 - 1e-9);
  // The hits' largest error bound (on the axis, torus.cpp) is 4 sqrt(eps) (R + r): a root at
  // least |o - q| >= world_radius / greatest from the origin is far beyond it.
  if (!(world_radius / sv.greatest > 1e-5 * e)) return;
  const double b = kInside * m;
  const double near = std::fabs(c - big_r) + b, far = c + big_r - b;
  const double inside = (r * r - near * near) * (far * far - r * r);
  // The longest feeler for which (1) the quartic's rounding stays under half of `inside`, with
  // |o|_1 + |d|_1 t <= 6 size; (2) the object ray's rounding (16 eps size, generously) moves q
  // by under (kInside - kCovered) m and the light by under a tenth of its margin from the box.
  const double rounding = 32768 * kMachineEpsilon * e * e * e;
  const double size_limit =
      std::min((inside / (2 * rounding) - e) / 6,
               std::min((kInside - kCovered) * m, 1e-7 * r) / (16 * kMachineEpsilon));
  const double longest = longest_feeler(size, size_limit);
  if (!(longest > 0)) return;
  for (int k = 0; k < kTorusBalls; ++k) {
    const double angle = 2 * std::numbers::pi * k / kTorusBalls;
    const Vec3 centre{c * std::cos(angle), c * std::sin(angle), 0};
    out.push_back({instance.to_world.apply_point(centre), world_radius, longest});
  }
}

// A unit sphere. A feeler through the ball of radius kInside about its centre, from an origin
// beyond it, to a light outside it: its object ray has its roots t0 < t_q < t1 < 1 about the
// point q, with error bounds far below t_q (the origin is at least |o - q| before q) and below
// the light's margin; occluded_sphere reports t0 when it is beyond its error, else t1, and
// neither of its early misses (an origin outside moving away, a line outside the sphere) applies.
void sphere_balls(const Instance& instance, const Vec3& light, const SingularValues& sv,
                  const ObjectSize& size, std::vector<InscribedBall>& out) {
  const Vec3 l = instance.to_object.apply_point(light);
  if (!(dot(l, l) > (1 + 1e-6) * (1 + 1e-6))) return;
  const double size_limit = std::min(kInside - kCovered, 1e-7) / (16 * kMachineEpsilon);
  const double longest = longest_feeler(size, size_limit);
  if (!(longest > 0)) return;
  out.push_back(
      {instance.to_world.apply_point({0, 0, 0}), kCovered * sv.least * (1 - 1e-9), longest});
}

}  // namespace

SingularValues singular_values(const Affine& a) {
  // The eigenvalues of A^T A, by cyclic Jacobi rotations (converged to rounding long before the
  // last sweep).
  double s[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      s[i][j] = 0;
      for (int k = 0; k < 3; ++k) s[i][j] += a.m[k][i] * a.m[k][j];
    }
  for (int sweep = 0; sweep < 16; ++sweep)
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (s[p][q] == 0) continue;
        const double theta = (s[q][q] - s[p][p]) / (2 * s[p][q]);
        const double t = (theta >= 0 ? 1 : -1) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), sn = t * c;
        for (int k = 0; k < 3; ++k) {
          const double kp = s[k][p], kq = s[k][q];
          s[k][p] = c * kp - sn * kq;
          s[k][q] = sn * kp + c * kq;
        }
        for (int k = 0; k < 3; ++k) {
          const double pk = s[p][k], qk = s[q][k];
          s[p][k] = c * pk - sn * qk;
          s[q][k] = sn * pk + c * qk;
        }
      }
  // Jacobi's eigenvalues are accurate to rounding of the largest; 1e-12 of it is far more.
  const double greatest = std::max({s[0][0], s[1][1], s[2][2]});
  const double least = std::min({s[0][0], s[1][1], s[2][2]}) - 1e-12 * greatest;
  if (!(least > 0) || !std::isfinite(greatest)) return {};
  return {std::sqrt(least) * (1 - 1e-9), std::sqrt(greatest * (1 + 1e-12)) * (1 + 1e-9)};
}

std::vector<InscribedBall> inscribed_balls(const Instance& instance, const Vec3& light) {
  std::vector<InscribedBall> out;
  // A moving object's pose depends on the feeler's time; a boolean object's surface is its
  // children's.
  if (instance.motion) return out;
  const SingularValues sv = singular_values(instance.to_world);
  if (!(sv.least > 0)) return out;
  const Vec3 translation{instance.to_world.m[0][3], instance.to_world.m[1][3],
                         instance.to_world.m[2][3]};
  const ObjectSize size{(length(light) + length(translation)) / sv.least, 1 / sv.least};
  if (const auto* torus = std::get_if<Torus>(&instance.geometry))
    torus_balls(*torus, instance, light, sv, size, out);
  else if (std::holds_alternative<Sphere>(instance.geometry))
    sphere_balls(instance, light, sv, size, out);
  return out;
}

std::vector<InscribedBall> opaque_balls(const Scene& scene, std::span<const Instance> instances,
                                        std::span<const std::uint32_t> ids, const Vec3& light) {
  std::vector<InscribedBall> out;
  for (const std::uint32_t id : ids) {
    const Instance& instance = instances[id];
    if (scene.objects[instance.object].material.transparency != 0) continue;
    for (const InscribedBall& ball : inscribed_balls(instance, light)) out.push_back(ball);
  }
  return out;
}

}  // namespace tessera
