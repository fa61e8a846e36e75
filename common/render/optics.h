// The directions of reflection and refraction (eq. 4.13, 4.15-4.16), kept apart from the tracer
// so that their edge cases can be tested directly: the critical angle, cosines a rounding step
// outside [-1, 1].
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "common/math/vec3.h"

namespace tessera {

// Eq. 4.13: `r` mirrored about the plane of unit normal `n`.
inline Vec3 reflect(const Vec3& r, const Vec3& n) { return r - n * (2 * dot(n, r)); }

// Snell's law by speeds of light, eta = c2 / c1 (eq. 4.15-4.16, with 1 - (N.r)^2 under the
// root): the unit direction into the second medium of the unit ray `r` through a surface whose
// unit normal `n` faces against it; none beyond the critical angle (total internal reflection).
// The cosine is clamped because unit vectors are unit only to rounding: |N.r| may exceed 1 by
// an ulp. At the critical angle itself the root is of zero and the ray leaves along the surface.
inline std::optional<Vec3> refract(const Vec3& r, const Vec3& n, double eta) {
  const double cos_i = std::clamp(-dot(n, r), 0.0, 1.0);
  const double k = 1 - eta * eta * (1 - cos_i * cos_i);
  if (k < 0) return std::nullopt;
  return normalize_or(r * eta + n * (eta * cos_i - std::sqrt(k)), r);
}

}  // namespace tessera
