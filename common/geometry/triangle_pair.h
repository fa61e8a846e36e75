// Two triangles of a mesh leaf laid out to be tested against a ray at once, or four as two
// adjacent pairs (intersect_triangle_pair.h): MeshAccel::leaf_pairs.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/math/vec3.h"

namespace tessera {

// Two triangles' corners, structure of arrays: corner[c][axis][lane], so that one load brings a
// coordinate of both. A lane whose corners are NaN is never hit (its determinant is not finite):
// it stands for degenerate triangles and pads leaves of odd size.
struct alignas(16) TrianglePair {
  double corner[3][3][2];
};

inline Vec3 pair_corner(const TrianglePair& pair, int c, int lane) {
  return {pair.corner[c][0][lane], pair.corner[c][1][lane], pair.corner[c][2][lane]};
}

inline void set_pair_corner(TrianglePair& pair, int c, int lane, const Vec3& p) {
  pair.corner[c][0][lane] = p.x;
  pair.corner[c][1][lane] = p.y;
  pair.corner[c][2][lane] = p.z;
}

}  // namespace tessera

namespace tessera {

// Four triangles' corners in float, rounded to nearest, structure of arrays as TrianglePair,
// with each lane's largest |coordinate| rounded up (`magnitude`, for the error bound of
// triangle_float_lanes.h): MeshAccel::leaf_quads. A lane whose magnitude is NaN holds no
// triangle (a gap, or a degenerate triangle) and is never hit.
struct alignas(16) FloatTriangleQuad {
  float corner[3][3][4];
  float magnitude[4];
};

// Lane `lane` of `quad` holds the triangle p[0] p[1] p[2] (its corners rounded to nearest).
inline void set_float_quad_lane(FloatTriangleQuad& quad, int lane, const Vec3* p) {
  double magnitude = 0;
  for (int c = 0; c < 3; ++c)
    for (int a = 0; a < 3; ++a) {
      quad.corner[c][a][lane] = static_cast<float>(p[c][a]);
      magnitude = std::max(magnitude, std::fabs(p[c][a]));
    }
  // Rounded up: float's nearest, then one step of 2^-20 more than its error.
  quad.magnitude[lane] = static_cast<float>(magnitude) * (1 + 0x1p-20f);
}

// Lane `lane` of `quad` holds no triangle and is never hit.
inline void set_float_quad_lane_never_hit(FloatTriangleQuad& quad, int lane) {
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  for (int c = 0; c < 3; ++c)
    for (int a = 0; a < 3; ++a) quad.corner[c][a][lane] = kNaN;
  quad.magnitude[lane] = kNaN;
}

}  // namespace tessera
