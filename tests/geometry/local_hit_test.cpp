// intersect_instance leaves its LocalHit unzeroed (instance.cpp), so every shape's nearest-hit
// routine must write every member of it on a hit: the same hit, whatever the bytes it was
// handed held before.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <random>
#include <vector>

#include "common/geometry/shapes.h"
#include "common/math/float_error.h"
#include "test_meshes.h"

namespace tessera {
namespace {

using Intersect = std::function<bool(const Ray&, LocalHit&)>;

LocalHit filled_with(unsigned char byte) {
  LocalHit hit;
  std::memset(static_cast<void*>(&hit), byte, sizeof hit);
  return hit;
}

template <typename T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Rays from a sphere of radius 4 towards points near the centre: most hit a shape of size 1.
// Returns how many hit.
int expect_every_member_written(const Intersect& intersect) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 from =
        normalize_or(Vec3{coordinate(rng), coordinate(rng), coordinate(rng)}, Vec3{0, 0, 1}) * 4;
    const Vec3 to{coordinate(rng) * 0.5, coordinate(rng) * 0.5, coordinate(rng) * 0.5};
    const Ray ray{from, to - from, 0};
    LocalHit zeros = filled_with(0x00), ones = filled_with(0xff);
    const bool hit = intersect(ray, zeros);
    EXPECT_EQ(intersect(ray, ones), hit) << i;
    if (!hit) continue;
    ++hits;
    EXPECT_TRUE(same_bits(zeros.t, ones.t)) << i;
    EXPECT_TRUE(same_bits(zeros.point, ones.point)) << i;
    EXPECT_TRUE(same_bits(zeros.point_error, ones.point_error)) << i;
    EXPECT_TRUE(same_bits(zeros.normal, ones.normal)) << i;
    EXPECT_TRUE(same_bits(zeros.shading_normal, ones.shading_normal)) << i;
    EXPECT_TRUE(same_bits(zeros.part, ones.part)) << i;
  }
  return hits;
}

TEST(LocalHit, EveryMemberIsWrittenOnAHit) {
  std::vector<Intersect> shapes = {
      [](const Ray& ray, LocalHit& hit) { return intersect_sphere(ray, kInfinity, hit); },
      [](const Ray& ray, LocalHit& hit) { return intersect_cube(ray, kInfinity, hit); },
      [](const Ray& ray, LocalHit& hit) {
        return intersect_tapered_cylinder(TaperedCylinder{0.5}, ray, kInfinity, hit);
      },
      [](const Ray& ray, LocalHit& hit) {
        return intersect_torus(Torus{0.3, 0.8}, ray, kInfinity, hit);
      },
      [](const Ray& ray, LocalHit& hit) {
        return intersect_algebraic(AlgebraicSurface{AlgebraicKind::FourLobes, {2, 2, 2}}, ray, 0,
                                   50, hit);
      },
  };
  const Mesh octahedron = testing::octahedron();  // the accelerator keeps a pointer to it
  const MeshAccel mesh = build_mesh_accel(octahedron, BvhMode::Sah);
  for (const bool smooth : {false, true})
    shapes.push_back([&mesh, smooth](const Ray& ray, LocalHit& hit) {
      IntersectionCounters counters;
      return intersect_mesh(mesh, smooth, ray, kInfinity, hit, counters);
    });
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    SCOPED_TRACE(s);
    EXPECT_GT(expect_every_member_written(shapes[s]), 100);
  }
}

}  // namespace
}  // namespace tessera
