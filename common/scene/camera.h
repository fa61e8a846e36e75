// The camera of a scene: where it looks from and to, which way is up, and how wide it sees.
// Both loaders produce one; a job's camera setting replaces it (scene_loader.h).
#pragma once

#include <string>

#include "common/math/vec3.h"

namespace tessera {

struct Camera {
  Vec3 eye{0, 0, 5};       // eyePoint
  Vec3 look_at{0, 0, 0};   // viewPoint
  Vec3 up{0, 1, 0};        // upDirection
  double view_angle = 45;  // vertical field of view in degrees (viewAngle)
  // VRML's fieldOfView spans the smaller side of the image (ISO/IEC 14772-1 §6.53): then
  // view_angle is the horizontal angle of a portrait image.
  bool view_angle_on_smaller_side = false;
  friend bool operator==(const Camera&, const Camera&) = default;
};

// The unit view direction, also for an eye and viewPoint 1e308 apart (their difference would
// overflow); zero when they coincide. The loader and the renderer share these two rules.
inline Vec3 view_direction(const Camera& camera) {
  Vec3 difference = camera.look_at - camera.eye;
  if (!is_finite(difference)) difference = camera.look_at * 0.5 - camera.eye * 0.5;
  return unit_or_zero(difference);
}

// The unit vector to the right of the view, also for a tiny upDirection (1e-200); zero when
// upDirection is zero or too nearly parallel to the view direction to give a frame.
inline Vec3 camera_right(const Camera& camera, const Vec3& view) {
  const Vec3 right = cross(view, unit_or_zero(camera.up));
  return length(right) > 1e-9 ? unit_or_zero(right) : Vec3{};
}

// A camera a scene offers by name: VRML's Viewpoints, for a page to list and select.
struct NamedCamera {
  std::string name;  // the Viewpoint's description, else where it is ("world.wrl:12:3")
  Camera camera;
  friend bool operator==(const NamedCamera&, const NamedCamera&) = default;
};

}  // namespace tessera
