// Four rays' cube tests together with AVX2 (cube_packet.h) must be intersect_cube's, bit for bit,
// and the instance's packet test (intersect_instance_packet) of a cube intersect_instance's, with
// every box kernel (the scalar path stays for machines without AVX2).
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "common/accel/wide_box_kernel.h"
#include "common/geometry/cube_packet.h"
#include "common/geometry/instance.h"
#include "common/geometry/shapes.h"
#include "tests/geometry/packet_checks.h"

namespace tessera {
namespace {

using test::component;
using test::same_value;

bool same_local_hit(const LocalHit& a, const LocalHit& b) {
  return same_value(a.t, b.t) && same_value(a.point, b.point) &&
         same_value(a.point_error, b.point_error) && same_value(a.normal, b.normal) &&
         same_value(a.shading_normal, b.shading_normal) && a.part == b.part;
}

// A coordinate for a camera-like origin: often on a face's plane or its edge (+-1), else outside
// or inside the cube.
double coordinate(std::mt19937_64& rng) {
  const int i = std::uniform_int_distribution<int>(0, 9)(rng);
  if (i == 0) return 1;
  if (i == 1) return -1;
  return std::uniform_real_distribution<double>(-3, 3)(rng);
}

TEST(CubePacket, HitsAreIntersectCubesBitForBit) {
  if (!wide_box_kernel_supported(WideBoxKernel::Avx2)) GTEST_SKIP() << "no AVX2";
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> unit(-1, 1);
  int hits = 0, parallel_hits = 0, tied_hits = 0;
  for (int i = 0; i < 200000; ++i) {
    // A quarter of special values everywhere; else rays from a camera-like origin towards points
    // near the cube, some parallel to a slab (a zero component of either sign).
    // Another quarter ties two slabs: an origin as far from the x faces as from the y faces
    // (|o.x| = |o.y|), directions whose x and y components are as far in proportion, so both
    // slabs give the same distances and the earlier axis must name the face.
    const bool special = i % 4 == 0, tied = i % 4 == 1;
    const double a = 1.5 + (unit(rng) + 1) * 0.75, sx = unit(rng) < 0 ? -1 : 1,
                 sy = unit(rng) < 0 ? -1 : 1;
    const Vec3 origin = special ? Vec3{component(rng, 3), component(rng, 3), component(rng, 3)}
                        : tied  ? Vec3{a * sx, a * sy, coordinate(rng)}
                                : Vec3{coordinate(rng), coordinate(rng), coordinate(rng)};
    Vec3 directions[4];
    double t_max[4];
    for (int l = 0; l < 4; ++l) {
      if (special) {
        directions[l] = Vec3{component(rng, 1), component(rng, 1), component(rng, 1)};
        t_max[l] = component(rng, 4);
        continue;
      }
      const double k = 0.2 + (unit(rng) + 1) * 0.4;
      Vec3 d = tied ? Vec3{-origin.x * k, -origin.y * k, unit(rng) * 0.3}
                    : Vec3{unit(rng) * 1.2, unit(rng) * 1.2, unit(rng) * 1.2} - origin;
      const int flat = std::uniform_int_distribution<int>(0, 7)(rng);
      if (flat == 0) d.x = 0;
      if (flat == 1) d.y = -0.0;
      if (flat == 2) d.z = 0;
      directions[l] = d;
      t_max[l] = l == 3 ? 0.5 + unit(rng) * 0.5 : kInfinity;
    }
    const unsigned lanes = 1 + static_cast<unsigned>(i % 15);
    LocalHit together[4], alone[4];
    const unsigned hit_lanes =
        intersect_cube_packet_avx2(origin, directions, lanes, t_max, together);
    for (int l = 0; l < 4; ++l) {
      const bool hit =
          ((lanes >> l) & 1u) && intersect_cube(Ray{origin, directions[l], 0}, t_max[l], alone[l]);
      ASSERT_EQ((hit_lanes >> l) & 1u, hit ? 1u : 0u) << i << " lane " << l;
      if (!hit) continue;
      ++hits;
      if (directions[l].x == 0 || directions[l].y == 0 || directions[l].z == 0) ++parallel_hits;
      if (tied) ++tied_hits;
      ASSERT_TRUE(same_local_hit(together[l], alone[l])) << i << " lane " << l;
    }
  }
  EXPECT_GT(hits, 100000);
  EXPECT_GT(parallel_hits, 10000);
  EXPECT_GT(tied_hits, 10000);
}

// Whole packet tests of cubes, diagonal (as features/torus.sdl's floor) and turned (full
// products), against each lane alone, with every box kernel; lanes left out of the mask are not
// written.
TEST(CubePacket, InstancePacketsAreEachRayAlone) {
  std::mt19937_64 rng(22);
  std::vector<Instance> instances;
  for (const Affine& m : {Affine::translation({0, -2, 0}) * Affine::scaling({8, 0.05, 4}),
                          Affine::translation({1, 0, -1}) * *Affine::rotation(-60, {1, 0, 0}) *
                              Affine::scaling({2, 0.5, 1})}) {
    std::optional<Instance> made = make_instance(Cube{}, m, nullptr);
    ASSERT_TRUE(made.has_value());
    instances.push_back(*made);
  }
  const int hits = test::compare_instance_packets(instances, {0, 3, 12}, {9, 1, 5}, 0.9, 3000, rng);
  EXPECT_GT(hits, 10000);
}

}  // namespace
}  // namespace tessera
