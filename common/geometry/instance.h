// A shape placed in the world: generic geometry under an affine transform. The world ray is
// taken into object space with the inverse transform (its direction is not renormalized, so
// t is the same in both spaces), intersected there, and the hit is brought back with its
// error bound (pbrt-v3 §3.9.4), so that rays can leave it robustly (offset_ray_origin).
#pragma once

#include <array>
#include <bit>
#include <cstdint>

#include "common/accel/mesh_accel.h"
#include "common/geometry/local_hit.h"
#include "common/math/affine.h"
#include "common/math/diagonal_affine.h"
#include "common/math/ray.h"
#include "common/scene/motion.h"
#include "common/scene/shape.h"
#include "common/stats/intersection_counters.h"

namespace tessera {

// Whether two vectors are the same bit for bit (unlike ==, which equates 0 and -0).
inline bool same_bits(const Vec3& a, const Vec3& b) {
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  return ((bits(a.x) ^ bits(b.x)) | (bits(a.y) ^ bits(b.y)) | (bits(a.z) ^ bits(b.z))) == 0;
}

struct Instance {
  ShapeGeometry geometry;
  Affine to_world;
  Affine to_object;  // inverse of to_world
  // Both transforms again, when their linear parts are diagonal, to be applied as such
  // (math/diagonal_affine.h). Set with them by place_instance.
  struct Diagonal {
    DiagonalAffine to_world, to_object;
  };
  std::optional<Diagonal> diagonal;
  // A cube's normals in world space, by face (LocalHit::part), unit: its hits' normals depend on
  // their face alone, so they are taken through the transform once, as to_world_hit would take
  // them, not at every hit. Set by place_instance.
  std::optional<std::array<Vec3, 6>> face_normals;
  const MeshAccel* mesh = nullptr;  // for MeshShape geometry
  // For CsgShape geometry, the children's instances (make_csg_instance, csg.h).
  const Instance* left = nullptr;
  const Instance* right = nullptr;
  Bounds3 world_bounds;
  std::uint32_t object = 0;  // its index in Scene::objects, reported by its hits
  // Set when the object moves during the shutter (geometry/motion.h): to_world is then its
  // pose at time 0 and world_bounds cover its whole motion.
  std::optional<ObjectMotion> motion;
};

// Builds an instance; nullopt when `to_world` is singular or not finite.
std::optional<Instance> make_instance(const ShapeGeometry& geometry, const Affine& to_world,
                                      const MeshAccel* mesh);

// Sets the instance's transforms, `to_object` being the inverse of `to_world`.
void place_instance(Instance& instance, const Affine& to_world, const Affine& to_object);

struct WorldHit {
  double t = 0;
  Vec3 point;           // world space
  Vec3 point_error;     // per-component error bound of `point`
  Vec3 normal;          // unit outward geometric normal, world space
  Vec3 shading_normal;  // unit shading normal (interpolated for smooth meshes), world space
  Vec3 object_point;    // the hit in object space (solid textures, texture coordinates)
  std::uint32_t part = 0;
  // The scene object whose surface was hit (Instance::object): the instance itself, or for a
  // boolean object the child whose surface it is, which gives the hit its material.
  std::uint32_t object = 0;
};

// Nearest hit with t in (0, t_max), or false, leaving `hit` as it was (Tracer::closest_hit
// keeps its best hit so far there). A moving instance is posed at the ray's time.
bool intersect_instance(const Instance& instance, const Ray& world_ray, double t_max, WorldHit& hit,
                        IntersectionCounters& counters);

// A world point taken into the instance's object space as the origin of intersect_instance's
// object ray, bit for bit. Rays that share their origin (a pinhole camera's) need it once per
// instance: Tracer::find_packet_hits takes the eye so once, not at every shape test.
Vec3 object_origin(const Instance& instance, const Vec3& world_origin);

// intersect_instance, bit for bit, for a ray whose origin `object_origin` has already taken into
// the instance's object space.
bool intersect_instance(const Instance& instance, const Ray& world_ray, const Vec3& object_origin,
                        double t_max, WorldHit& hit, IntersectionCounters& counters);

// intersect_instance for up to four rays from one origin (a camera packet's lanes at one leaf):
// for each lane l in `lanes` (bit l), the ray rays[l] with limit t_max[l]; bit l of the answer is
// set when it hits, *hits[l] then written, as intersect_instance would, bit for bit. A torus
// forms the lanes' quartics together (torus_packet.h) when AVX2 is in use and two or more lanes
// ask; every other case takes intersect_instance a lane at a time.
unsigned intersect_instance_packet(const Instance& instance, const Ray rays[4], unsigned lanes,
                                   const Vec3& object_origin, const double t_max[4],
                                   WorldHit* const hits[4], IntersectionCounters& counters);

// Whether the ray meets the instance with t in (0, t_max): the answer of intersect_instance,
// for shadow feelers, without the world-space hit (point, error bound, normals) and through a
// mesh's any-hit traversal. `object` becomes the scene object whose surface blocks the ray: the
// instance's own, or for a boolean object the child of its nearest hit, whose material decides
// how much light passes (eq. 4.24).
bool occluded_instance(const Instance& instance, const Ray& world_ray, double t_max,
                       std::uint32_t& object, IntersectionCounters& counters);

// The world ray in the instance's object space (same t) and a local hit back in world space,
// for routines that find several hits at once (csg.cpp).
Ray object_ray(const Instance& instance, const Ray& world_ray);
void to_world_hit(const Instance& instance, const LocalHit& local, WorldHit& hit);

}  // namespace tessera
