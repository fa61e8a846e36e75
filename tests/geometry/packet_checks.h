// Bit-for-bit comparisons of values and hits, random components with special values, and whole
// instance packet tests against each ray alone, for the tests of the packet paths
// (torus_packet_test.cpp, cube_packet_test.cpp), which must give what the scalar paths give.
#pragma once

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "common/accel/wide_box_kernel.h"

#include "common/geometry/instance.h"

namespace tessera::test {

// The same bits, or NaN in both (a NaN's sign depends on the compiler's operand order).
inline bool same_value(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
}
inline bool same_value(const Vec3& a, const Vec3& b) {
  return same_value(a.x, b.x) && same_value(a.y, b.y) && same_value(a.z, b.z);
}

inline bool same_hit(const WorldHit& a, const WorldHit& b) {
  return same_value(a.t, b.t) && same_value(a.point, b.point) &&
         same_value(a.point_error, b.point_error) && same_value(a.normal, b.normal) &&
         same_value(a.shading_normal, b.shading_normal) &&
         same_value(a.object_point, b.object_point) && a.part == b.part && a.object == b.object;
}

// A component: often a special value (zeros of both signs, +-1, values beyond hypot_inline's
// ranges, infinity, NaN), else uniform in [-spread, spread].
inline double component(std::mt19937_64& rng, double spread) {
  static const double kSpecial[] = {0.0,
                                    -0.0,
                                    1.0,
                                    -1.0,
                                    1e-300,
                                    1e300,
                                    1e-160,
                                    1e-170,
                                    1e-320,
                                    std::numeric_limits<double>::infinity(),
                                    std::numeric_limits<double>::quiet_NaN()};
  const int i = std::uniform_int_distribution<int>(0, 40)(rng);
  if (i < 11) return kSpecial[i];
  return std::uniform_real_distribution<double>(-spread, spread)(rng);
}

// Whole packet tests (intersect_instance_packet) of each instance against each lane alone
// (intersect_instance), with every box kernel: `packets` packets of four rays from `eye` towards
// the instance's centre plus up to `spread` along each axis, lane 2 limited to t_max = cut +- 0.1,
// the lane masks 1 to 15 in turn; lanes left out of the mask or missing are not written, and the
// shape tests are counted alike. Returns the hits compared.
inline int compare_instance_packets(const std::vector<Instance>& instances, const Vec3& eye,
                                    const Vec3& spread, double cut, int packets,
                                    std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  int hits = 0;
  for (const WideBoxKernel kernel : kWideBoxKernels) {
    if (!wide_box_kernel_supported(kernel)) continue;
    force_wide_box_kernel(kernel);
    for (const Instance& instance : instances) {
      const Vec3 origin = object_origin(instance, eye);
      const Vec3 centre{instance.to_world.m[0][3], instance.to_world.m[1][3],
                        instance.to_world.m[2][3]};
      for (int i = 0; i < packets; ++i) {
        Ray rays[4];
        double t_max[4];
        for (int l = 0; l < 4; ++l) {
          const Vec3 target =
              centre + Vec3{unit(rng) * spread.x, unit(rng) * spread.y, unit(rng) * spread.z};
          rays[l] = Ray{eye, target - eye, 0};
          t_max[l] = l == 2 ? cut + unit(rng) * 0.1 : kInfinity;
        }
        const unsigned lanes = 1 + static_cast<unsigned>(i % 15);
        WorldHit together[4], alone[4];
        WorldHit* const together_hits[4] = {&together[0], &together[1], &together[2], &together[3]};
        IntersectionCounters together_counts, alone_counts;
        const unsigned hit_lanes = intersect_instance_packet(instance, rays, lanes, origin, t_max,
                                                             together_hits, together_counts);
        for (int l = 0; l < 4; ++l) {
          const bool in = (lanes >> l) & 1u;
          const bool hit =
              in && intersect_instance(instance, rays[l], t_max[l], alone[l], alone_counts);
          EXPECT_EQ((hit_lanes >> l) & 1u, hit ? 1u : 0u) << i << " lane " << l;
          if (hit) {
            ++hits;
            EXPECT_TRUE(same_hit(together[l], alone[l])) << i << " lane " << l;
          } else {
            EXPECT_TRUE(same_hit(together[l], WorldHit{})) << i << " lane " << l;
          }
        }
        EXPECT_EQ(together_counts.shape_tests, alone_counts.shape_tests);
      }
    }
  }
  force_wide_box_kernel(std::nullopt);
  return hits;
}

}  // namespace tessera::test
