// Shapes under affine transforms (instance.h).
//
// The world hit's error bound has three parts:
//  1. the object-space point's own bound (from the shape routine), carried through to_world;
//  2. the rounding of to_world itself (Affine::point_error);
//  3. the round trip: a ray spawned near the hit is taken back into object space by
//     to_object, which rounds its origin by up to gamma(3) (|M^-1| |o| + |t^-1|); and to_object
//     is only the rounded inverse of to_world, so the two disagree by a residual of the same
//     order. Both perturb the object-space origin; mapped into world space by |M| they become
//     the third term. Offsetting the spawned origin by the full bound therefore keeps it on
//     the intended side of the *object-space* surface, which is where the intersection is
//     decided. For translate * rotate * scale transforms |M| |M^-1| = |R| |R^T| (entries at
//     most 1), so the term stays ~1e-15 of the coordinates' magnitude even for non-uniform
//     scales of 1e-4 .. 1e4 and translations of 1e8; for sheared, badly conditioned
//     transforms it grows with the (Skeel) condition number, as the real error does.
#include "common/geometry/instance.h"

#include <bit>
#include <cmath>
#include <variant>

#include "common/accel/wide_box_kernel.h"
#include "common/geometry/csg.h"
#include "common/geometry/cube_packet.h"
#include "common/geometry/motion.h"
#include "common/geometry/shapes.h"
#include "common/geometry/torus_packet.h"
#include "common/geometry/world_hits_avx2.h"
#include "common/math/float_error.h"

namespace tessera {

namespace {

// |lin(a)| v: the linear part's absolute values applied to a non-negative vector. Forced
// inline: called twice for every hit, GCC kept it out of line (0.7 % of the demo's instructions).
// Each component is built whole, not written by index, so that reading the result two
// components at a time does not wait for separate stores (a store-forwarding stall).
[[gnu::always_inline]] inline Vec3 abs_linear(const Affine& a, const Vec3& v) {
  const auto row = [&](int r) {
    return std::fabs(a.m[r][0]) * v.x + std::fabs(a.m[r][1]) * v.y + std::fabs(a.m[r][2]) * v.z;
  };
  return {row(0), row(1), row(2)};
}

Vec3 abs_translation(const Affine& a) {
  return {std::fabs(a.m[0][3]), std::fabs(a.m[1][3]), std::fabs(a.m[2][3])};
}

// Part 3 above, for a world point of magnitude `magnitude` (componentwise |p| plus its error).
[[gnu::always_inline]] inline Vec3 round_trip_error(const Instance& instance,
                                                    const Vec3& magnitude) {
  // |M^-1| |p| + |t^-1|: the size of the terms to_object adds up for this point.
  const Vec3 object_terms =
      abs_linear(instance.to_object, magnitude) + abs_translation(instance.to_object);
  // gamma(3) for the rounding of to_object applied to the spawned origin, and a further
  // gamma(8) for the residual to_world * to_object - I of the computed inverse (whose terms
  // are of the same size); both are taken back to world space by |M|.
  return (abs_linear(instance.to_world, object_terms) + abs_translation(instance.to_world)) *
         gamma_bound(11);
}

// The same for a diagonal instance (diagonal_affine.h).
[[gnu::always_inline]] inline Vec3 diagonal_round_trip_error(const Instance::Diagonal& diagonal,
                                                             const Vec3& magnitude) {
  const Vec3 object_terms =
      diagonal.to_object.abs_linear(magnitude) + abs(diagonal.to_object.offset);
  return (diagonal.to_world.abs_linear(object_terms) + abs(diagonal.to_world.offset)) *
         gamma_bound(11);
}

// What a shape's routines are asked: the world ray, taken into the instance's object space,
// and the limit on t.
struct ShapeQuery {
  const Instance& instance;
  const Ray& world_ray;
  const Ray& ray;  // in object space
  double t_max;
  IntersectionCounters& counters;
};

struct LocalIntersect : ShapeQuery {
  LocalHit& hit;

  bool operator()(const Sphere&) const { return intersect_sphere(ray, t_max, hit); }
  bool operator()(const Cube&) const { return intersect_cube(ray, t_max, hit); }
  bool operator()(const TaperedCylinder& c) const {
    return intersect_tapered_cylinder(c, ray, t_max, hit);
  }
  bool operator()(const Torus& t) const { return intersect_torus(t, ray, t_max, hit); }
  bool operator()(const AlgebraicSurface& a) const {
    double t_min = 0, t_limit = t_max;
    if (!algebraic_extent_span(a, instance.to_world, world_ray, t_min, t_limit)) return false;
    return intersect_algebraic(a, ray, t_min, t_limit, hit);
  }
  bool operator()(const MeshShape& m) const {
    if (instance.mesh == nullptr) return false;
    return intersect_mesh(*instance.mesh, m.interpolate_normals, ray, t_max, hit, counters);
  }
  // Boolean objects have no object space of their own: intersect_instance hands them to
  // intersect_csg before this point.
  bool operator()(const CsgShape&) const { return false; }
};

// Whether the object-space ray meets the shape in (0, t_max), for occluded_instance: the shapes
// with an occlusion test of their own answer without building the hit (a sphere's and a cube's
// saves the stores of a LocalHit and its zeroing, a torus skips polishing its root, a mesh
// stops at its first triangle); the others stop at their nearest hit anyway.
struct LocalOcclusion : ShapeQuery {
  bool operator()(const Sphere&) const { return occluded_sphere(ray, t_max); }
  bool operator()(const Cube&) const { return occluded_cube(ray, t_max); }
  bool operator()(const Torus& t) const { return occluded_torus(t, ray, t_max); }
  bool operator()(const MeshShape&) const {
    return instance.mesh != nullptr && occluded_mesh(*instance.mesh, ray, t_max, counters);
  }
  template <typename Shape>
  bool operator()(const Shape& shape) const {
    LocalHit local;
    return LocalIntersect{*this, local}(shape);
  }
};

// The full products of an instance's transforms, which every instance may take.
struct FullTransforms {
  const Instance& instance;

  [[gnu::always_inline]] Ray object_ray(const Ray& world_ray) const {
    // The direction is not renormalized, so t means the same in both spaces.
    return {object_point(world_ray.origin), object_vector(world_ray.direction), world_ray.time};
  }
  [[gnu::always_inline]] Vec3 object_point(const Vec3& p) const {
    return instance.to_object.apply_point(p);
  }
  [[gnu::always_inline]] Vec3 object_vector(const Vec3& v) const {
    return instance.to_object.apply_vector(v);
  }
  // The hit's world point and its error bound.
  [[gnu::always_inline]] void world_point(const LocalHit& local, WorldHit& hit) const {
    hit.point = instance.to_world.apply_point(local.point);
    hit.point_error = instance.to_world.point_error(local.point, local.point_error);
    hit.point_error += round_trip_error(instance, abs(hit.point) + hit.point_error);
  }
  // A local normal in world space, not yet normalized: through the inverse transpose.
  [[gnu::always_inline]] Vec3 world_normal(const Vec3& normal) const {
    return instance.to_object.apply_transpose(normal);
  }
};

// The diagonal products (diagonal_affine.h) of a diagonal instance, which give the full ones
// unless a component comes out zero or non-finite: then the full products are taken.
struct DiagonalTransforms {
  const Instance& instance;
  const Instance::Diagonal& diagonal;

  [[gnu::always_inline]] Ray object_ray(const Ray& world_ray) const {
    const Ray ray{diagonal.to_object.apply_point(world_ray.origin),
                  diagonal.to_object.apply_vector(world_ray.direction), world_ray.time};
    if (same_as_full(ray.origin, ray.direction)) [[likely]]
      return ray;
    return FullTransforms{instance}.object_ray(world_ray);
  }
  // The parts of object_ray, each tested on its own: for a ray whose origin was taken once for
  // several rays (object_origin).
  [[gnu::always_inline]] Vec3 object_point(const Vec3& p) const {
    const Vec3 q = diagonal.to_object.apply_point(p);
    if (same_as_full(q)) [[likely]]
      return q;
    return FullTransforms{instance}.object_point(p);
  }
  [[gnu::always_inline]] Vec3 object_vector(const Vec3& v) const {
    const Vec3 w = diagonal.to_object.apply_vector(v);
    if (same_as_full(w)) [[likely]]
      return w;
    return FullTransforms{instance}.object_vector(v);
  }
  [[gnu::always_inline]] void world_point(const LocalHit& local, WorldHit& hit) const {
    hit.point = diagonal.to_world.apply_point(local.point);
    hit.point_error = diagonal.to_world.point_error(local.point, local.point_error);
    hit.point_error += diagonal_round_trip_error(diagonal, abs(hit.point) + hit.point_error);
    if (!same_as_full(hit.point, hit.point_error)) [[unlikely]]
      FullTransforms{instance}.world_point(local, hit);
  }
  [[gnu::always_inline]] Vec3 world_normal(const Vec3& normal) const {
    const Vec3 n = diagonal.to_object.apply_vector(normal);
    if (same_as_full(n)) return n;
    return FullTransforms{instance}.world_normal(normal);
  }
};

// The bodies of object_ray, to_world_hit and the intersection tests, for either kind of
// transforms, forced inline so that each test keeps them in its own body (as before CSG shared
// them: called out of line they cost a scene without boolean objects some 0.5 % more
// instructions, docs/PERFORMANCE.md, "Scenes that use none of the new effects"); the kind is
// chosen once a call.
// The hit's world normals, unit, from the local ones.
template <typename Transforms>
[[gnu::always_inline]] inline void world_normals(const Transforms& transforms,
                                                 const LocalHit& local, WorldHit& hit) {
  // A degenerate normal falls back to a finite unit vector rather than NaN.
  hit.normal = normalize_or(transforms.world_normal(local.normal), Vec3{});
  if (hit.normal == Vec3{}) hit.normal = Vec3{0, 0, 1};
  // Only smooth meshes interpolate a shading normal; every other shape reports its geometric
  // normal again, which would come out of the same transform and normalization bit for bit
  // (also when it falls back to hit.normal).
  hit.shading_normal =
      same_bits(local.shading_normal, local.normal)
          ? hit.normal
          : normalize_or(transforms.world_normal(local.shading_normal), hit.normal);
}

template <typename Transforms>
[[gnu::always_inline]] inline void to_world_hit_with(const Transforms& transforms,
                                                     const LocalHit& local, WorldHit& hit) {
  hit.t = local.t;
  transforms.world_point(local, hit);
  if (transforms.instance.face_normals) {
    hit.normal = (*transforms.instance.face_normals)[local.part];
    hit.shading_normal = hit.normal;
  } else {
    world_normals(transforms, local, hit);
  }
  hit.object_point = local.point;
  hit.part = local.part;
  hit.object = transforms.instance.object;
}

// `ray` is the world ray in the instance's object space, as transforms.object_ray gives it.
template <typename Transforms>
[[gnu::always_inline]] inline bool intersect_with(const Transforms& transforms,
                                                  const Ray& world_ray, const Ray& ray,
                                                  double t_max, WorldHit& hit,
                                                  IntersectionCounters& counters) {
  ++counters.shape_tests;
  UnzeroedLocalHits<1> storage;
  LocalHit& local = *storage.hits();
  if (!std::visit(LocalIntersect{{transforms.instance, world_ray, ray, t_max, counters}, local},
                  transforms.instance.geometry))
    return false;
  to_world_hit_with(transforms, local, hit);
  return true;
}

// intersect_with for the instance's kind of transforms, with the object ray that
// object_ray_of(transforms) makes.
template <typename ObjectRayOf>
[[gnu::always_inline]] inline bool intersect_placed(const Instance& instance, const Ray& world_ray,
                                                    double t_max, WorldHit& hit,
                                                    IntersectionCounters& counters,
                                                    const ObjectRayOf& object_ray_of) {
  if (instance.diagonal) {
    const DiagonalTransforms transforms{instance, *instance.diagonal};
    return intersect_with(transforms, world_ray, object_ray_of(transforms), t_max, hit, counters);
  }
  const FullTransforms transforms{instance};
  return intersect_with(transforms, world_ray, object_ray_of(transforms), t_max, hit, counters);
}

[[gnu::always_inline]] inline Ray object_ray_inline(const Instance& instance,
                                                    const Ray& world_ray) {
  if (instance.diagonal)
    return DiagonalTransforms{instance, *instance.diagonal}.object_ray(world_ray);
  return FullTransforms{instance}.object_ray(world_ray);
}

#if defined(__SSE2__)
// intersect_instance_packet's lanes through a shape's packet test (torus_packet.h,
// cube_packet.h): each lane's object direction as intersect_instance takes it, the shape's test
// packet_test(directions, locals) four lanes at once, the hits back to world space as
// intersect_instance takes them, four at a time (world_hits_avx2.h).
template <typename Transforms, typename PacketTest>
[[gnu::always_inline]] inline unsigned intersect_lanes(const Transforms& transforms,
                                                       const Ray rays[4], unsigned lanes,
                                                       WorldHit* const hits[4],
                                                       IntersectionCounters& counters,
                                                       const PacketTest& packet_test) {
  // Lanes outside `lanes` repeat the first one's ray (computed, not used). Built whole: an array
  // of Vec3 declared first is zeroed (a `rep stos`).
  const int first = std::countr_zero(lanes);
  const auto direction = [&](int l) {
    return transforms.object_vector(rays[(lanes >> l) & 1u ? l : first].direction);
  };
  const Vec3 directions[4] = {direction(0), direction(1), direction(2), direction(3)};
  counters.shape_tests += static_cast<std::uint64_t>(std::popcount(lanes));
  UnzeroedLocalHits<4> storage;
  LocalHit* locals = storage.hits();
  const unsigned hit_lanes = packet_test(directions, locals);
  if (hit_lanes != 0) to_world_hits_avx2(transforms.instance, locals, hit_lanes, hits);
  return hit_lanes;
}

// intersect_lanes for the instance's kind of transforms.
template <typename PacketTest>
unsigned intersect_placed_lanes(const Instance& instance, const Ray rays[4], unsigned lanes,
                                WorldHit* const hits[4], IntersectionCounters& counters,
                                const PacketTest& packet_test) {
  if (instance.diagonal)
    return intersect_lanes(DiagonalTransforms{instance, *instance.diagonal}, rays, lanes, hits,
                           counters, packet_test);
  return intersect_lanes(FullTransforms{instance}, rays, lanes, hits, counters, packet_test);
}
#endif

// A torus's world box, tighter than its object box's corners: the torus is its core circle
// (radius R in the xy plane) swept by a ball of radius r, so its image under the linear part L
// is an ellipse swept by an ellipsoid, and support functions add: along world axis i it reaches
// R |(L_i0, L_i1)| + r |L_i| either side of its centre (the translation). The corners' box reaches
// (R + r)(|L_i0| + |L_i1|) + r |L_i2|: for the tori of features/torus.sdl, tipped by 60 degrees,
// 0.37 r further on two axes, where shadow rays and camera rays that miss the object box went on
// into the instance's transform and the torus's setup. Padded as the corners' box is, by the
// rounding of to_world applied to a corner (twice Affine::point_error), with room for the hit
// points' own rounding (under 16 eps (R + r) off the axis, where the extremes lie; the bound a
// thin tube reports is wider, to cover its quartic's rounding band, but its points are as close)
// and for a grazing ray's touching root, which lies within rounding of the surface, not on it: the
// tube is widened by 1e-10 (R + r), some 10^5 times that rounding.
Bounds3 torus_world_bounds(const Torus& torus, const Affine& to_world) {
  const double big_r = torus.torus_radius, r = torus.tube_radius, e = big_r + r;
  const double tube = r + 1e-10 * e;
  const Vec3 centre{to_world.m[0][3], to_world.m[1][3], to_world.m[2][3]};
  const double hit_error = 16 * kMachineEpsilon * e;
  const Vec3 corner_error =
      to_world.point_error(Vec3{e, e, r}, Vec3{hit_error, hit_error, hit_error}) * 2;
  const auto reach = [&](int i) {
    const double a = to_world.m[i][0], b = to_world.m[i][1], c = to_world.m[i][2];
    const double in_plane = a * a + b * b;
    return big_r * std::sqrt(in_plane) + tube * std::sqrt(in_plane + c * c);
  };
  const Vec3 half = Vec3{reach(0), reach(1), reach(2)} + corner_error;
  return Bounds3{centre - half, centre + half};
}

}  // namespace

void place_instance(Instance& instance, const Affine& to_world, const Affine& to_object) {
  instance.to_world = to_world;
  instance.to_object = to_object;
  const std::optional<DiagonalAffine> world = DiagonalAffine::of(to_world);
  const std::optional<DiagonalAffine> object = DiagonalAffine::of(to_object);
  instance.diagonal.reset();
  if (world && object) instance.diagonal = Instance::Diagonal{*world, *object};
  instance.face_normals.reset();
  if (std::holds_alternative<Cube>(instance.geometry)) {
    std::array<Vec3, 6> normals;
    for (std::uint32_t face = 0; face < 6; ++face) {
      LocalHit local;
      local.normal = cube_face_normal(face);
      local.shading_normal = local.normal;
      WorldHit hit;
      if (instance.diagonal)
        world_normals(DiagonalTransforms{instance, *instance.diagonal}, local, hit);
      else
        world_normals(FullTransforms{instance}, local, hit);
      normals[face] = hit.normal;
    }
    instance.face_normals = normals;
  }
}

std::optional<Instance> make_instance(const ShapeGeometry& geometry, const Affine& to_world,
                                      const MeshAccel* mesh) {
  if (!to_world.is_finite()) return std::nullopt;
  const std::optional<Affine> to_object = to_world.inverse();
  if (!to_object) return std::nullopt;
  Instance instance;
  instance.geometry = geometry;
  place_instance(instance, to_world, *to_object);
  instance.mesh = mesh;
  if (const auto* algebraic = std::get_if<AlgebraicSurface>(&geometry)) {
    instance.world_bounds = algebraic_extent(*algebraic, to_world);
    return instance;
  }
  if (const auto* torus = std::get_if<Torus>(&geometry)) {
    instance.world_bounds = torus_world_bounds(*torus, to_world);
    return instance;
  }
  // The transformed corners, padded by their rounding so the box certainly holds the shape.
  const Bounds3 local = object_bounds(geometry, mesh);
  if (!local.empty()) {
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 p{(corner & 1) ? local.hi.x : local.lo.x, (corner & 2) ? local.hi.y : local.lo.y,
                   (corner & 4) ? local.hi.z : local.lo.z};
      const Vec3 w = to_world.apply_point(p);
      const Vec3 e = to_world.point_error(p, Vec3{}) * 2;
      instance.world_bounds.extend(w - e);
      instance.world_bounds.extend(w + e);
    }
  }
  return instance;
}

Ray object_ray(const Instance& instance, const Ray& world_ray) {
  return object_ray_inline(instance, world_ray);
}

void to_world_hit(const Instance& instance, const LocalHit& local, WorldHit& hit) {
  if (instance.diagonal)
    to_world_hit_with(DiagonalTransforms{instance, *instance.diagonal}, local, hit);
  else
    to_world_hit_with(FullTransforms{instance}, local, hit);
}

bool intersect_instance(const Instance& instance, const Ray& world_ray, double t_max, WorldHit& hit,
                        IntersectionCounters& counters) {
  if (std::holds_alternative<CsgShape>(instance.geometry))
    return intersect_csg(instance, world_ray, t_max, hit, counters);
  if (instance.motion && world_ray.time != 0) {
    const std::optional<Instance> posed = instance_at(instance, world_ray.time);
    return posed && intersect_instance(*posed, world_ray, t_max, hit, counters);
  }
  return intersect_placed(instance, world_ray, t_max, hit, counters,
                          [&](const auto& transforms) { return transforms.object_ray(world_ray); });
}

Vec3 object_origin(const Instance& instance, const Vec3& world_origin) {
  if (instance.diagonal)
    return DiagonalTransforms{instance, *instance.diagonal}.object_point(world_origin);
  return FullTransforms{instance}.object_point(world_origin);
}

bool intersect_instance(const Instance& instance, const Ray& world_ray, const Vec3& object_origin,
                        double t_max, WorldHit& hit, IntersectionCounters& counters) {
  // A boolean object's children and a moving instance's pose have object spaces of their own.
  if (std::holds_alternative<CsgShape>(instance.geometry) ||
      (instance.motion && world_ray.time != 0))
    return intersect_instance(instance, world_ray, t_max, hit, counters);
  // object_ray's origin and direction, each equal to the full product's (diagonal_affine.h).
  return intersect_placed(instance, world_ray, t_max, hit, counters, [&](const auto& transforms) {
    return Ray{object_origin, transforms.object_vector(world_ray.direction), world_ray.time};
  });
}

unsigned intersect_instance_packet(const Instance& instance, const Ray rays[4], unsigned lanes,
                                   const Vec3& object_origin, const double t_max[4],
                                   WorldHit* const hits[4], IntersectionCounters& counters) {
#if defined(__SSE2__)
  // A moving shape takes the lanes one at a time (posed at each ray's time).
  if (!instance.motion && !std::has_single_bit(lanes) && has_avx2(wide_box_kernel())) {
    if (const Torus* torus = std::get_if<Torus>(&instance.geometry))
      return intersect_placed_lanes(instance, rays, lanes, hits, counters,
                                    [&](const Vec3 directions[4], LocalHit* locals) {
                                      return intersect_torus_packet_avx2(
                                          *torus, object_origin, directions, lanes, t_max, locals);
                                    });
    if (std::holds_alternative<Cube>(instance.geometry))
      return intersect_placed_lanes(
          instance, rays, lanes, hits, counters, [&](const Vec3 directions[4], LocalHit* locals) {
            return intersect_cube_packet_avx2(object_origin, directions, lanes, t_max, locals);
          });
  }
#endif
  unsigned hit_lanes = 0;
  for (unsigned m = lanes; m != 0; m &= m - 1) {
    const int l = std::countr_zero(m);
    if (intersect_instance(instance, rays[l], object_origin, t_max[l], *hits[l], counters))
      hit_lanes |= 1u << l;
  }
  return hit_lanes;
}

bool occluded_instance(const Instance& instance, const Ray& world_ray, double t_max,
                       std::uint32_t& object, IntersectionCounters& counters) {
  if (std::holds_alternative<CsgShape>(instance.geometry)) {
    // Which child's surface blocks the ray depends on the crossings' order: the nearest hit.
    WorldHit hit;
    if (!intersect_csg(instance, world_ray, t_max, hit, counters)) return false;
    object = hit.object;
    return true;
  }
  if (instance.motion && world_ray.time != 0) {
    const std::optional<Instance> posed = instance_at(instance, world_ray.time);
    return posed && occluded_instance(*posed, world_ray, t_max, object, counters);
  }
  ++counters.shape_tests;
  object = instance.object;
  // Only the object ray depends on the kind: one visit of the shape for both (two cost the
  // instances that are not diagonal some 20 instructions a call).
  const Ray ray = object_ray_inline(instance, world_ray);
  return std::visit(LocalOcclusion{{instance, world_ray, ray, t_max, counters}}, instance.geometry);
}

}  // namespace tessera
