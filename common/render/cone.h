// Non-weighted jittered discrete cone tracing (§4.1.4), shared by gloss, translucency (eq.
// 4.18-4.19) and soft shadows (eq. 4.25-4.26): of a cone's rays, the first is its central
// axis, not jittered; the others are spread evenly around its rim and jittered; the cone's
// value is the plain mean of its rays' values.
#pragma once

#include <array>
#include <cmath>
#include <numbers>

#include "common/math/portable_math.h"
#include "common/math/vec3.h"
#include "common/render/sampler.h"

namespace tessera {

// The angle around the axis of rim ray k (1 <= k < count) of a cone of `count` rays.
inline double rim_angle(int k, int count) { return 2 * std::numbers::pi * (k - 1) / (count - 1); }

// Its sine and cosine. Cones are traced at every glossy or translucent hit and soft shadow, at
// the same few angles each time, and sincos costs some 180 instructions, so for counts up to
// kTabledConeRays (the command line's limit) they are computed once, the same values.
inline constexpr int kTabledConeRays = 64;
inline SinCos rim_sincos(int k, int count) {
  if (count > kTabledConeRays) return tessera::sincos(rim_angle(k, count));
  static const auto table = [] {
    std::array<std::array<SinCos, kTabledConeRays>, kTabledConeRays + 1> rows{};
    for (int n = 2; n <= kTabledConeRays; ++n)
      for (int j = 1; j < n; ++j) rows[n][j] = tessera::sincos(rim_angle(j, n));
    return rows;
  }();
  return table[count][k];
}

class Cone {
 public:
  // A cone around the unit `axis` whose rim is `radius` from the axis one unit along it
  // (r_c = strength / 2, eq. 4.18 and 4.25); its rays are jittered by j = r_c / 4 (eq. 4.19
  // and 4.26), as ±j/2 along each of two directions across the axis, the way pixel samples
  // are jittered (eq. 4.52).
  Cone(const Vec3& axis, double radius) : axis_(axis), radius_(radius) {
    // Duff et al., "Building an orthonormal basis, revisited" (JCGT 2017): no normalization,
    // no branch but the sign, continuous in the axis except across z = 0.
    const double sign = std::copysign(1.0, axis.z);
    const double a = -1 / (sign + axis.z);
    const double b = axis.x * axis.y * a;
    u_ = {1 + sign * axis.x * axis.x * a, sign * b, -sign * axis.x};
    v_ = {b, sign + axis.y * axis.y * a, -axis.y};
  }

  // The unit direction of rim ray k (1 <= k < count) of a cone of `count` rays; draws two
  // numbers from `rng`.
  Vec3 rim_direction(int k, int count, SampleStream& rng) const {
    const double jitter = radius_ / 4;
    const SinCos rim = rim_sincos(k, count);
    const double du = radius_ * rim.cos + (rng.next() - 0.5) * jitter;
    const double dv = radius_ * rim.sin + (rng.next() - 0.5) * jitter;
    return normalize_or(axis_ + u_ * du + v_ * dv, axis_);
  }

  // The mean of `trace_along(direction)` over the `count` rays of the cone, in ray order
  // (count >= 1; the random numbers are drawn in that order too).
  template <typename Value, typename TraceAlong>
  Value mean(int count, SampleStream& rng, TraceAlong&& trace_along) const {
    Value sum = trace_along(axis_);
    for (int k = 1; k < count; ++k) sum += trace_along(rim_direction(k, count, rng));
    return sum * (1.0 / count);
  }

 private:
  Vec3 axis_, u_, v_;
  double radius_;
};

}  // namespace tessera
