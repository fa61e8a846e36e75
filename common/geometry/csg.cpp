// Boolean objects (csg.h).
#include "common/geometry/csg.h"

#include <cmath>
#include <variant>

#include "common/geometry/motion.h"
#include "common/geometry/shapes.h"
#include "common/math/float_error.h"

namespace tessera {

namespace {

bool combine(CsgOperation operation, bool in_left, bool in_right) {
  switch (operation) {
    case CsgOperation::Union:
      return in_left || in_right;
    case CsgOperation::Intersection:
      return in_left && in_right;
    case CsgOperation::Difference:
      return in_left && !in_right;
  }
  return false;
}

// Every crossing with t > 0 of a shape, in its object space.
struct ShapeCrossings {
  const Instance& instance;
  const Ray& ray;  // in object space
  IntersectionCounters& counters;

  std::vector<LocalHit> operator()(const Sphere&) const { return sphere_crossings(ray, kInfinity); }
  std::vector<LocalHit> operator()(const Cube&) const { return cube_crossings(ray, kInfinity); }
  std::vector<LocalHit> operator()(const TaperedCylinder& c) const {
    return tapered_cylinder_crossings(c, ray, kInfinity);
  }
  std::vector<LocalHit> operator()(const Torus& t) const {
    return torus_crossings(t, ray, kInfinity);
  }
  std::vector<LocalHit> operator()(const MeshShape& m) const {
    if (instance.mesh == nullptr) return {};
    return mesh_crossings(*instance.mesh, m.interpolate_normals, ray, kInfinity, counters);
  }
  // An algebraic surface is clipped to a world-space box, not a closed solid: the loader
  // refuses it as a child, and a scene built otherwise gets nothing from it.
  std::vector<LocalHit> operator()(const AlgebraicSurface&) const { return {}; }
  std::vector<LocalHit> operator()(const CsgShape&) const { return {}; }  // solid_crossings
};

// The crossings of a shape: its surface's, each one toggling inside and outside; the origin is
// inside when the number ahead of it is odd.
SolidCrossings shape_crossings(const Instance& instance, const Ray& world_ray,
                               IntersectionCounters& counters) {
  if (instance.motion && world_ray.time != 0) {
    const std::optional<Instance> posed = instance_at(instance, world_ray.time);
    return posed ? shape_crossings(*posed, world_ray, counters) : SolidCrossings{};
  }
  ++counters.shape_tests;
  SolidCrossings out;
  const double direction_length = length(world_ray.direction);
  if (!(direction_length > 0)) return out;
  const Ray ray = object_ray(instance, world_ray);
  const std::vector<LocalHit> local =
      std::visit(ShapeCrossings{instance, ray, counters}, instance.geometry);
  out.inside_at_origin = local.size() % 2 == 1;
  bool inside = out.inside_at_origin;
  out.crossings.reserve(local.size());
  for (const LocalHit& l : local) {
    inside = !inside;
    SolidCrossing crossing;
    to_world_hit(instance, l, crossing.hit);
    // How far along the ray the point may be from the exact crossing: its distance from the
    // surface, plus the rounding of t itself.
    crossing.t_error =
        length(crossing.hit.point_error) / direction_length + gamma_bound(4) * std::fabs(l.t);
    crossing.entering = inside;
    out.crossings.push_back(crossing);
  }
  return out;
}

// The crossings of `operation` applied to two solids' crossings (see csg.h for the rule).
SolidCrossings combine_crossings(CsgOperation operation, const SolidCrossings& left,
                                 const SolidCrossings& right) {
  const std::vector<SolidCrossing>* lists[2] = {&left.crossings, &right.crossings};
  std::size_t next[2] = {0, 0};
  bool in[2] = {left.inside_at_origin, right.inside_at_origin};
  bool inside = combine(operation, in[0], in[1]);
  SolidCrossings out;
  out.inside_at_origin = inside;

  // The side whose next crossing comes first (the left one on a tie), or -1 when both are done.
  const auto earliest = [&]() {
    const bool has_left = next[0] < lists[0]->size(), has_right = next[1] < lists[1]->size();
    if (!has_left) return has_right ? 1 : -1;
    if (!has_right) return 0;
    return (*lists[1])[next[1]].hit.t < (*lists[0])[next[0]].hit.t ? 1 : 0;
  };
  std::vector<const SolidCrossing*> event;
  for (int side = earliest(); side >= 0;) {
    // One event: this crossing and every following one within the error bounds of the one
    // before it. Both children take their state after the event.
    const bool before[2] = {in[0], in[1]};
    const SolidCrossing* last[2] = {nullptr, nullptr};
    event.clear();
    for (; side >= 0; side = earliest()) {
      const SolidCrossing& c = (*lists[side])[next[side]];
      if (!event.empty() && c.hit.t - event.back()->hit.t > event.back()->t_error + c.t_error)
        break;
      ++next[side];
      in[side] = c.entering;
      last[side] = &c;
      event.push_back(&c);
    }
    const bool now = combine(operation, in[0], in[1]);
    if (now == inside) continue;
    inside = now;

    // The surface: a child whose own change agrees with the node's, the left one first. (One
    // does: each operation is monotone in its children, the subtracted one reversed.)
    int chosen = -1;
    for (int s = 0; s < 2 && chosen < 0; ++s) {
      if (last[s] == nullptr || in[s] == before[s]) continue;
      const bool reversed = operation == CsgOperation::Difference && s == 1;
      if ((in[s] != reversed) == now) chosen = s;
    }
    if (chosen < 0) chosen = last[0] != nullptr ? 0 : 1;
    SolidCrossing crossing = *last[chosen];
    if (operation == CsgOperation::Difference && chosen == 1) {
      crossing.hit.normal = -crossing.hit.normal;
      crossing.hit.shading_normal = -crossing.hit.shading_normal;
    }
    crossing.entering = now;
    // Its error bound covers every surface of the event, so that rays leaving it start beyond
    // all of them.
    const SolidCrossing reported = crossing;
    for (const SolidCrossing* c : event) {
      crossing.hit.point_error = max(crossing.hit.point_error,
                                     c->hit.point_error + abs(c->hit.point - reported.hit.point));
      crossing.t_error =
          std::max(crossing.t_error, c->t_error + std::fabs(c->hit.t - reported.hit.t));
    }
    out.crossings.push_back(crossing);
  }
  return out;
}

}  // namespace

Instance make_csg_instance(const CsgShape& shape, const Instance& left, const Instance& right) {
  Instance instance;
  instance.geometry = shape;
  instance.to_world = Affine::identity();
  instance.to_object = Affine::identity();
  instance.left = &left;
  instance.right = &right;
  switch (shape.operation) {
    case CsgOperation::Union:
      instance.world_bounds = left.world_bounds;
      instance.world_bounds.extend(right.world_bounds);
      break;
    case CsgOperation::Intersection:
      instance.world_bounds.lo = max(left.world_bounds.lo, right.world_bounds.lo);
      instance.world_bounds.hi = min(left.world_bounds.hi, right.world_bounds.hi);
      break;
    case CsgOperation::Difference:
      instance.world_bounds = left.world_bounds;
      break;
  }
  return instance;
}

SolidCrossings solid_crossings(const Instance& instance, const Ray& world_ray,
                               IntersectionCounters& counters) {
  const auto* shape = std::get_if<CsgShape>(&instance.geometry);
  if (shape == nullptr) return shape_crossings(instance, world_ray, counters);
  if (instance.left == nullptr || instance.right == nullptr) return {};
  const SolidCrossings left = solid_crossings(*instance.left, world_ray, counters);
  // Nothing of the left solid on this line: an intersection or difference has nothing either.
  if (shape->operation != CsgOperation::Union && left.crossings.empty() && !left.inside_at_origin)
    return {};
  return combine_crossings(shape->operation, left,
                           solid_crossings(*instance.right, world_ray, counters));
}

bool intersect_csg(const Instance& instance, const Ray& world_ray, double t_max, WorldHit& hit,
                   IntersectionCounters& counters) {
  const SolidCrossings solid = solid_crossings(instance, world_ray, counters);
  if (solid.crossings.empty() || !(solid.crossings.front().hit.t < t_max)) return false;
  hit = solid.crossings.front().hit;
  return true;
}

}  // namespace tessera
