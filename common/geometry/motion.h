// Moving instances (SDL §3.2.6, §4.5): an instance whose transform depends on the ray's time.
// Only objects with mbEnable pay for it: the instance keeps its pose at time 0, and a ray at
// another time is intersected with a copy posed for that time. The scene BVH holds the bounds
// of the whole motion over the shutter, so it never culls a moving object.
#pragma once

#include <optional>

#include "common/geometry/instance.h"
#include "common/scene/motion.h"

namespace tessera {

// The object-to-world transform at shutter time `time` (common/scene/motion.h).
Affine transform_at(const Affine& transform, const ObjectMotion& motion, double time);

// `instance` posed at `time`, without motion; nullopt when that pose is singular or not finite.
std::optional<Instance> instance_at(const Instance& instance, double time);

// An instance moving by `motion` during the shutter [-shutter / 2, shutter / 2], its world
// bounds covering every pose in it; nullopt when the pose at time 0 is singular.
std::optional<Instance> make_moving_instance(const ShapeGeometry& geometry, const Affine& transform,
                                             const ObjectMotion& motion, double shutter,
                                             const MeshAccel* mesh);

}  // namespace tessera
