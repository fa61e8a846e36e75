// Balls inside opaque solids, as seen from a point light: the far side of the light buffer
// (light_buffer.h). A hard feeler to the light whose line passes through such a ball, from an
// origin beyond it, is blocked by the solid whatever else lies there, and the solid's own
// occlusion test says so (why, for each shape, in inscribed_balls.cpp).
#pragma once

#include <vector>

#include <cstdint>
#include <span>

#include "common/geometry/instance.h"
#include "common/math/vec3.h"
#include "common/scene/scene.h"

namespace tessera {

struct InscribedBall {
  Vec3 centre;  // world space
  // A feeler from origin o to the light whose line passes within `radius` of the centre, with
  // |o - light| > |centre - light| + radius and |o - light| < longest, is blocked by the solid.
  double radius = 0;
  double longest = 0;
};

// The balls of the instance for the light at `light` (none when the instance is not a sphere
// or a torus, moves, or the light is inside its bounds or too near them, or rounding could
// decide its test: see the .cpp). The caller checks that the object is opaque.
std::vector<InscribedBall> inscribed_balls(const Instance& instance, const Vec3& light);

// The balls of the opaque objects among `instances[ids]` (objects of `scene`), for the light at
// `light`: a feeler that meets an opaque object has the factor 0 whatever else it meets.
std::vector<InscribedBall> opaque_balls(const Scene& scene, std::span<const Instance> instances,
                                        std::span<const std::uint32_t> ids, const Vec3& light);

// The least and greatest singular values of the transform's linear part: the least rounded
// down, the greatest rounded up (by far more than their rounding).
struct SingularValues {
  double least = 0, greatest = 0;
};
SingularValues singular_values(const Affine& a);

}  // namespace tessera
