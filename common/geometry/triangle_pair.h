// Two triangles of a mesh leaf laid out to be tested against a ray at once, or four as two
// adjacent pairs (intersect_triangle_pair.h): MeshAccel::leaf_pairs.
#pragma once

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
