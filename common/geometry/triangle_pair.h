// Four triangles of a mesh leaf laid out to be tested against a ray at once, or two at a time as
// its halves (intersect_triangle_pair.h): MeshAccel::leaf_quads.
#pragma once

#include "common/math/vec3.h"

namespace tessera {

// Four triangles' corners, structure of arrays: corner[c][axis][lane], so that one aligned load
// brings a coordinate of all four (AVX2), or of a half's two (SSE2). A lane whose corners are NaN
// is never hit (its determinant is not finite): it stands for degenerate triangles and pads
// leaves whose size is not a multiple of four.
struct alignas(32) TriangleQuad {
  double corner[3][3][4];
};

inline Vec3 quad_corner(const TriangleQuad& quad, int c, int lane) {
  return {quad.corner[c][0][lane], quad.corner[c][1][lane], quad.corner[c][2][lane]};
}

inline void set_quad_corner(TriangleQuad& quad, int c, int lane, const Vec3& p) {
  quad.corner[c][0][lane] = p.x;
  quad.corner[c][1][lane] = p.y;
  quad.corner[c][2][lane] = p.z;
}

}  // namespace tessera
