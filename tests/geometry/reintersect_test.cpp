// The robustness property of shapes.h (pbrt's "reintersect" tests): a ray spawned at a hit with
// offset_ray_origin() and the hit's error bound never hits the same convex surface again
// outward, and inward only hits its far side, for random transforms with scales 1e-4..1e4
// (non-uniform), any rotation and translations up to 1e8. Tori: torus_test.cpp,
// Torus.SpawnedRaysDoNotFindTheirOwnHit (the same transforms).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "common/geometry/instance.h"
#include "common/geometry/shapes.h"
#include "common/math/float_error.h"
#include "tests/geometry/test_meshes.h"

namespace tessera {
namespace {

using testing::random_transform;
using testing::random_unit;

std::string describe(const Vec3& v) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "(%.17g, %.17g, %.17g)", v.x, v.y, v.z);
  return buffer;
}

struct Stats {
  int primary_hits = 0;
  int outward = 0;
  int inward = 0;
  int no_exit = 0;
  int failures = 0;
};

// A random transform as random_transform() makes, followed (applied before it) by a second
// rotation and a non-uniform scale: a sheared, possibly badly conditioned matrix, as a chain of
// SDL transforms can produce.
Affine random_sheared_transform(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  const Affine a = random_transform(rng);
  return a * *Affine::rotation(360 * unit(rng), random_unit(rng)) *
         Affine::scaling({std::pow(10, 2 * unit(rng) - 1), 1, 1});
}

// Fires `rays` random rays at random transforms of `geometry` and spawns `spawns` rays at each
// hit; reports the first few violations.
Stats check_reintersect(const ShapeGeometry& geometry, const MeshAccel* mesh, std::uint64_t seed,
                        int transforms, int rays, int spawns, bool sheared = false) {
  SCOPED_TRACE(::testing::Message() << "seed " << seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  Stats stats;
  auto fail = [&](const std::string& what) {
    if (++stats.failures <= 5) ADD_FAILURE() << what;
  };
  for (int i = 0; i < transforms; ++i) {
    const Affine to_world = sheared ? random_sheared_transform(rng) : random_transform(rng);
    const std::optional<Instance> inst = make_instance(geometry, to_world, mesh);
    if (!inst) {
      // Sheared products may be numerically singular (|det| < 1e-12 of Hadamard's bound).
      if (!sheared) fail("make_instance refused transform " + std::to_string(i));
      continue;
    }
    const Bounds3& wb = inst->world_bounds;
    const double size = length(wb.diagonal());
    IntersectionCounters counters;
    for (int r = 0; r < rays; ++r) {
      // Aim at a random point of the object's bounds from a random point around it; scale the
      // direction arbitrarily (t does not care).
      const Vec3 aim{unit(rng), unit(rng), unit(rng)};
      const Bounds3 local = object_bounds(geometry, mesh);
      const Vec3 target = to_world.apply_point(local.lo + mul(local.diagonal(), aim));
      const Vec3 origin = target + random_unit(rng) * (size * (1 + 4 * unit(rng)));
      const Vec3 dir = (target - origin) * std::pow(10, 4 * unit(rng) - 2);
      WorldHit hit;
      if (!intersect_instance(*inst, {origin, dir}, kInfinity, hit, counters)) continue;
      ++stats.primary_hits;
      const double error = length(hit.point_error);
      // The bound is relative to the coordinates, and small.
      if (!sheared && !(max_component(hit.point_error) < 1e-13 * max_component(abs(hit.point))))
        fail("error bound " + describe(hit.point_error) + " too large for " + describe(hit.point));
      for (int s = 0; s < spawns; ++s) {
        const Vec3 w = random_unit(rng) * std::pow(10, 4 * unit(rng) - 2);
        const double cosine = dot(w, hit.normal);
        if (cosine == 0) continue;
        const Vec3 o = offset_ray_origin(hit.point, hit.point_error, hit.normal, w);
        WorldHit again;
        const bool found = intersect_instance(*inst, {o, w}, kInfinity, again, counters);
        const std::string where = "transform " + std::to_string(i) + " ray " + std::to_string(r) +
                                  ": hit " + describe(hit.point) + " error " +
                                  describe(hit.point_error) + " normal " + describe(hit.normal) +
                                  " part " + std::to_string(hit.part) + ", spawned from " +
                                  describe(o) + " along " + describe(w);
        if (cosine > 0) {
          ++stats.outward;
          if (found)
            fail("outward ray hit again at t " + std::to_string(again.t) + " point " +
                 describe(again.point) + "; " + where);
        } else {
          ++stats.inward;
          if (!found) {
            // Legitimate only within the error bound of an edge or rim: the offset, along the
            // world normal, may carry the origin past the edge and out of the shape (with a
            // 1e-4 non-uniform scale that is a good part of the shape's thin side). Counted.
            ++stats.no_exit;
            continue;
          }
          // The far side: away from the first hit by much more than its error, or on another
          // face (an adjacent cube face or triangle near an edge may legitimately be close).
          const bool far = length(again.point - hit.point) > 64 * error;
          const bool other_face = dot(again.normal, hit.normal) < 1 - 1e-9;
          if (!far && !other_face)
            fail("inward ray hit again at t ~ 0: t " + std::to_string(again.t) + " point " +
                 describe(again.point) + "; " + where);
        }
      }
    }
  }
  return stats;
}

constexpr int kTransforms = 200;
constexpr int kRays = 25;
constexpr int kSpawns = 4;

void run(const char* name, const ShapeGeometry& geometry, const MeshAccel* mesh,
         std::uint64_t seed) {
  SCOPED_TRACE(name);
  const Stats s = check_reintersect(geometry, mesh, seed, kTransforms, kRays, kSpawns);
  EXPECT_EQ(s.failures, 0);
  // Enough rays of both kinds were actually tested.
  EXPECT_GT(s.primary_hits, kTransforms * kRays / 4);
  EXPECT_GT(s.outward, 1000);
  EXPECT_GT(s.inward, 1000);
  // Rays that started inside a convex shape found its far side, nearly always.
  EXPECT_LE(s.no_exit, s.inward / 200) << "inward rays without an exit";
  ::testing::Test::RecordProperty(std::string(name) + "_no_exit", s.no_exit);
}

TEST(Reintersect, Sphere) { run("sphere", Sphere{}, nullptr, 101); }
TEST(Reintersect, Cube) { run("cube", Cube{}, nullptr, 102); }
TEST(Reintersect, Cone) { run("cone", TaperedCylinder{0, false}, nullptr, 103); }
TEST(Reintersect, Cylinder) { run("cylinder", TaperedCylinder{1, false}, nullptr, 104); }
TEST(Reintersect, TaperedCylinder) {
  run("tapered 0.3", TaperedCylinder{0.3, false}, nullptr, 105);
  run("widening 1.7", TaperedCylinder{1.7, false}, nullptr, 106);
}
TEST(Reintersect, Octahedron) {
  const Mesh mesh = testing::octahedron();
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  run("octahedron", MeshShape{0, false}, &accel, 107);
}
// Sheared transforms (condition numbers up to ~1e9): the origin of an inward ray may leave a
// shape that thin through its far side, but outward rays must still never hit it again and
// inward ones never at t ~ 0.
TEST(Reintersect, ShearedTransforms) {
  const Mesh mesh = testing::octahedron();
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  const std::pair<const char*, ShapeGeometry> shapes[] = {{"sphere", Sphere{}},
                                                          {"cube", Cube{}},
                                                          {"cone", TaperedCylinder{0, false}},
                                                          {"octahedron", MeshShape{0, false}}};
  std::uint64_t seed = 201;
  for (const auto& [name, geometry] : shapes) {
    SCOPED_TRACE(name);
    const Stats s = check_reintersect(geometry, &accel, seed++, 60, kRays, kSpawns, true);
    EXPECT_EQ(s.failures, 0);
    EXPECT_GT(s.outward, 500);
    EXPECT_LE(s.no_exit, s.inward / 10);
  }
}

TEST(Reintersect, SubdividedCube) {
  const Mesh mesh = testing::subdivided_cube(3);
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  run("subdivided cube", MeshShape{0, true}, &accel, 108);
}

// The algebraic surfaces are not convex: a spawned ray may meet the surface again elsewhere,
// but never at its own hit (within 16 error bounds of it). Uniform scales 1e-4..1e4 with the
// box extent scaled alike (it is in world units), any rotation, translations up to 1e8.
TEST(Reintersect, AlgebraicSurfacesAtEveryScale) {
  std::mt19937_64 rng(301);
  std::uniform_real_distribution<double> unit(0, 1);
  int tested = 0, failures = 0;
  for (int kind = 0; kind <= static_cast<int>(AlgebraicKind::ToothCube); ++kind) {
    SCOPED_TRACE(kind);
    for (int i = 0; i < 40; ++i) {
      const double scale = std::pow(10, 8 * unit(rng) - 4);
      const Vec3 offset = random_unit(rng) * std::pow(10, 8 * unit(rng));
      const Affine to_world = Affine::translation(offset) *
                              *Affine::rotation(360 * unit(rng), random_unit(rng)) *
                              Affine::scaling({scale, scale, scale});
      const AlgebraicSurface surface{static_cast<AlgebraicKind>(kind), Vec3{4, 4, 4} * scale};
      const std::optional<Instance> inst = make_instance(surface, to_world, nullptr);
      ASSERT_TRUE(inst);
      IntersectionCounters counters;
      for (int r = 0; r < 25; ++r) {
        const Vec3 target =
            offset + Vec3{unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5} * (3 * scale);
        const Vec3 origin = target + random_unit(rng) * (20 * scale);
        WorldHit hit;
        if (!intersect_instance(*inst, {origin, target - origin}, kInfinity, hit, counters))
          continue;
        ASSERT_TRUE(is_finite(hit.point) && is_finite(hit.normal) && is_finite(hit.point_error));
        for (int k = 0; k < kSpawns; ++k) {
          const Vec3 w = random_unit(rng);
          if (dot(w, hit.normal) == 0) continue;
          const Vec3 o = offset_ray_origin(hit.point, hit.point_error, hit.normal, w);
          WorldHit again;
          ++tested;
          if (!intersect_instance(*inst, {o, w}, kInfinity, again, counters)) continue;
          if (!(length(again.point - hit.point) > 16 * length(hit.point_error)) && ++failures <= 5)
            ADD_FAILURE() << "transform " << i << " ray " << r << ": hit " << describe(hit.point)
                          << " error " << describe(hit.point_error) << " found again at "
                          << describe(again.point) << " along " << describe(w);
        }
      }
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(tested, 4000);
}

}  // namespace
}  // namespace tessera
