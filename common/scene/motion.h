// An object's motion during the shutter (SDL §3.2.6): mbScale, mbRotate and mbTranslate, each
// completed over one frame of time. At shutter time t (in frames, 0 in the middle of the
// frame) the object's transform is
//     T(t * translation) * CT * R(t * angle about axis) * S(scale ^ t),
// so t = 0 is the pose the CT describes: scaling and rotation act in the object's own frame,
// about its origin, and the translation in world space. Scaling is geometric (scale^t), so
// it stays positive over any shutter and t = 1 scales by exactly `scale`.
#pragma once

#include "common/math/vec3.h"

namespace tessera {

// The most motion-blur time samples per camera sample, from a scene or from the settings: a
// bound on what one pixel can cost.
inline constexpr int kMaxTimeSamples = 256;

struct ObjectMotion {
  Vec3 scale{1, 1, 1};  // positive components
  double angle_degrees = 0;
  Vec3 axis{0, 0, 1};  // non-zero when angle_degrees is
  Vec3 translation{0, 0, 0};
  bool moves() const {
    return scale != Vec3{1, 1, 1} || angle_degrees != 0 || translation != Vec3{0, 0, 0};
  }
  friend bool operator==(const ObjectMotion&, const ObjectMotion&) = default;
};

}  // namespace tessera
