// Moving instances (motion.h).
//
// The swept bounds are the union of the instance's bounds at kPoses evenly spaced times over
// the shutter, padded by how far any point of the object can move between two neighbouring
// poses. A point p of the object's bounds moves, in object space, at speed
//     |d/dt R(t a) S(s^t) p| <= (|a| + max |ln s_i|) * max(s_i, 1/s_i)^|t| * |p|,
// which the CT's linear part stretches by at most its Frobenius norm; the translation adds
// |translation|. Half a step at that speed bounds the distance to the nearest pose.
#include "common/geometry/motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/geometry/shapes.h"
#include "common/math/portable_math.h"

namespace tessera {

namespace {

constexpr int kPoses = 17;

double frobenius_norm(const Affine& a) {
  double sum = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) sum += a.m[r][c] * a.m[r][c];
  return std::sqrt(sum);
}

// The largest distance from the origin of a corner of `b`.
double farthest_corner(const Bounds3& b) {
  const Vec3 far = max(abs(b.lo), abs(b.hi));
  return length(far);
}

// A bound on the world speed (units per unit of time) of every point of the object during
// the shutter.
double max_speed(const Affine& transform, const ObjectMotion& motion, const Bounds3& local,
                 double half_shutter) {
  double log_scale = 0, growth = 1;
  for (int i = 0; i < 3; ++i) {
    const double l = std::fabs(tessera::log(motion.scale[i]));
    log_scale = std::max(log_scale, l);
    growth = std::max(growth, tessera::exp(l * half_shutter));
  }
  const double angle = std::fabs(motion.angle_degrees) * std::numbers::pi / 180;
  const double object_speed = (angle + log_scale) * growth * farthest_corner(local);
  return length(motion.translation) + frobenius_norm(transform) * object_speed;
}

// scale^time on each axis. Called for every ray that meets a moving instance, and pow costs
// some 600 instructions, so the usual scales skip it for the same result: 1^time is 1 (no
// scaling), and an axis scaled as another reuses its power (uniform scaling).
Vec3 scale_at(const Vec3& scale, double time) {
  const auto power = [time](double s) { return s == 1 ? 1.0 : tessera::pow(s, time); };
  const double x = power(scale.x);
  const double y = scale.y == scale.x ? x : power(scale.y);
  const double z = scale.z == scale.x ? x : scale.z == scale.y ? y : power(scale.z);
  return {x, y, z};
}

}  // namespace

Affine transform_at(const Affine& transform, const ObjectMotion& motion, double time) {
  const Vec3 scale = scale_at(motion.scale, time);
  const Affine rotation =
      Affine::rotation(motion.angle_degrees * time, motion.axis).value_or(Affine::identity());
  return Affine::translation(motion.translation * time) * transform * rotation *
         Affine::scaling(scale);
}

std::optional<Instance> instance_at(const Instance& instance, double time) {
  const Affine to_world = transform_at(instance.to_world, *instance.motion, time);
  if (!to_world.is_finite()) return std::nullopt;
  const std::optional<Affine> to_object = to_world.inverse();
  if (!to_object) return std::nullopt;
  Instance posed = instance;
  place_instance(posed, to_world, *to_object);
  posed.motion.reset();
  return posed;
}

std::optional<Instance> make_moving_instance(const ShapeGeometry& geometry, const Affine& transform,
                                             const ObjectMotion& motion, double shutter,
                                             const MeshAccel* mesh) {
  std::optional<Instance> instance = make_instance(geometry, transform, mesh);
  if (!instance) return std::nullopt;
  instance->motion = motion;
  const double half = shutter / 2;
  Bounds3 swept = instance->world_bounds;
  for (int k = 0; k < kPoses; ++k) {
    const double time = -half + shutter * k / (kPoses - 1);
    if (const auto posed = make_instance(geometry, transform_at(transform, motion, time), mesh))
      swept.extend(posed->world_bounds);
  }
  const double step = shutter / (kPoses - 1);
  const double pad = max_speed(transform, motion, object_bounds(geometry, mesh), half) * step / 2;
  instance->world_bounds = Bounds3{swept.lo - Vec3{pad, pad, pad}, swept.hi + Vec3{pad, pad, pad}};
  return instance;
}

}  // namespace tessera
