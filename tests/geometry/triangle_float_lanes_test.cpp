// The float test of mesh leaves (triangle_float_lanes.h) decides only what the double watertight
// test would: a lane it reports missed the double test misses, a lane it reports hit the double
// test hits, on random rays and on those where float's error is largest (rays through edges and
// shared vertices nudged by a few of double's steps, fans around a shared vertex, rays leaving a
// triangle, t_max at a hit's t and a step either side), at 0, 1e5 and 3e7 from the origin and
// at float's extremes. The SSE path (four lanes) and the AVX2 path (eight) decide alike.
#include "common/geometry/triangle_float_lanes.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "common/geometry/triangle.h"
#include "common/math/float_error.h"

namespace tessera {
namespace {

#if defined(__SSE2__)

constexpr double kInfinity = std::numeric_limits<double>::infinity();

using Corners = std::array<Vec3, 3>;

template <bool kDecideHits>
FloatLaneDecisions decide_sse2(const FloatTriangleQuad* quads, const FloatLanesRay& ray,
                               double t_max) {
  const FloatLaneDecisions low =
      decide_triangle_float_lanes<Sse2FloatLanes, kDecideHits>(quads, ray, t_max, 15);
  const FloatLaneDecisions high =
      decide_triangle_float_lanes<Sse2FloatLanes, kDecideHits>(quads + 1, ray, t_max, 15);
  return {low.undecided | high.undecided << 4, low.hit | high.hit << 4};
}

template <bool kDecideHits>
[[gnu::target("avx2"), gnu::flatten]] FloatLaneDecisions decide_avx2(const FloatTriangleQuad* quads,
                                                                     const FloatLanesRay& ray,
                                                                     double t_max) {
  return decide_triangle_float_lanes<Avx2FloatLanes, kDecideHits>(quads, ray, t_max, 255);
}

struct Tally {
  long double_hits = 0;  // lanes the double test hits
  long missed = 0;       // lanes the float test decides missed
  long hit = 0;          // lanes the float test decides hit
  long lanes = 0;
};

// The eight triangles against one ray with t_max: the decisions hold for the double test, and
// every path makes the same ones.
void check_lanes(const std::array<Corners, 8>& triangles, const Ray& ray, double t_max,
                 Tally& tally) {
  FloatTriangleQuad quads[2];
  for (int lane = 0; lane < 8; ++lane) {
    const Corners& p = triangles[static_cast<std::size_t>(lane)];
    if (triangle_is_degenerate(p[0], p[1], p[2]))
      set_float_quad_lane_never_hit(quads[lane / 4], lane % 4);
    else
      set_float_quad_lane(quads[lane / 4], lane % 4, p.data());
  }
  const TriangleLanesRay lanes_ray = prepare_triangle_lanes_ray(ray);
  const FloatLanesRay float_ray = prepare_float_lanes_ray(lanes_ray);
  const FloatLaneDecisions decisions = decide_sse2<true>(quads, float_ray, t_max);
  const FloatLaneDecisions without_hits = decide_sse2<false>(quads, float_ray, t_max);
  ASSERT_EQ(without_hits.hit, 0u);
  ASSERT_EQ(without_hits.undecided, decisions.undecided | decisions.hit);
  if (__builtin_cpu_supports("avx2")) {
    const FloatLaneDecisions wide = decide_avx2<true>(quads, float_ray, t_max);
    ASSERT_EQ(wide.undecided, decisions.undecided);
    ASSERT_EQ(wide.hit, decisions.hit);
    ASSERT_EQ(decide_avx2<false>(quads, float_ray, t_max).undecided, without_hits.undecided);
  }
  for (int lane = 0; lane < 8; ++lane) {
    const Corners& p = triangles[static_cast<std::size_t>(lane)];
    TriangleHit h;
    const bool double_hit = !triangle_is_degenerate(p[0], p[1], p[2]) &&
                            intersect_triangle(p[0], p[1], p[2], lanes_ray.ray, t_max, h);
    const bool missed = ((decisions.undecided | decisions.hit) >> lane & 1) == 0;
    const bool hit = (decisions.hit >> lane & 1) != 0;
    ++tally.lanes;
    tally.double_hits += double_hit;
    tally.missed += missed;
    tally.hit += hit;
    ASSERT_FALSE(missed && double_hit)
        << "lane " << lane << " decided missed but hit at t " << h.t << "; t_max " << t_max;
    ASSERT_FALSE(hit && !double_hit)
        << "lane " << lane << " decided hit but missed; t_max " << t_max;
  }
}

// check_lanes with t_max infinite, then at each lane's double hit and a step either side.
void check_lanes_and_limits(const std::array<Corners, 8>& triangles, const Ray& ray, Tally& tally) {
  ASSERT_NO_FATAL_FAILURE(check_lanes(triangles, ray, kInfinity, tally));
  const TriangleRay triangle_ray = prepare_triangle_ray(ray);
  for (const Corners& p : triangles) {
    TriangleHit h;
    if (triangle_is_degenerate(p[0], p[1], p[2]) ||
        !intersect_triangle(p[0], p[1], p[2], triangle_ray, kInfinity, h))
      continue;
    for (const double t_max : {h.t, next_up(h.t), next_down(h.t)})
      ASSERT_NO_FATAL_FAILURE(check_lanes(triangles, ray, t_max, tally));
  }
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  for (;;) {
    const Vec3 v{normal(rng), normal(rng), normal(rng)};
    if (length(v) > 1e-3) return v / length(v);
  }
}

Corners random_triangle(std::mt19937_64& rng, const Vec3& center, double size) {
  std::uniform_real_distribution<double> unit(-1, 1);
  Corners p;
  for (Vec3& corner : p) corner = center + size * Vec3{unit(rng), unit(rng), unit(rng)};
  return p;
}

// A point on an edge (a third of them at a vertex), nudged off it by a few of double's steps,
// where an edge function is nearly zero.
Vec3 near_edge(std::mt19937_64& rng, const Corners& p) {
  std::uniform_int_distribution<int> pick(0, 2);
  std::uniform_real_distribution<double> along(0, 1);
  const int a = pick(rng), b = (a + 1) % 3;
  const double s = pick(rng) == 0 ? 0.0 : along(rng);
  const Vec3 point = p[a] + s * (p[b] - p[a]);
  std::uniform_int_distribution<int> steps(-4, 4);
  const double nudge = steps(rng) * 1e-16 * length(p[b] - p[a]);
  return point + nudge * random_unit(rng);
}

struct Scale {
  double offset;  // distance of the triangles from the world's origin
  double size;    // the triangles' size
  double reach;   // the rays' origins' distance from the triangles
};

class FloatLanesScales : public ::testing::TestWithParam<Scale> {};

TEST_P(FloatLanesScales, DecidesOnlyWhatTheDoubleTestDecides) {
  const Scale scale = GetParam();
  std::mt19937_64 rng(1234);
  Tally tally;
  for (int round = 0; round < 3000; ++round) {
    const Vec3 center = scale.offset * random_unit(rng);
    std::array<Corners, 8> triangles;
    for (Corners& t : triangles) t = random_triangle(rng, center, scale.size);
    // Every other round, a fan around a shared vertex.
    if (round % 2 == 1) {
      for (std::size_t i = 1; i < 8; ++i) triangles[i][0] = triangles[0][0];
      for (std::size_t i = 1; i < 8; ++i) triangles[i][1] = triangles[i - 1][2];
    }
    const Corners& target = triangles[static_cast<std::size_t>(round % 8)];
    Vec3 aim;
    switch (round % 3) {
      case 0:
        aim = near_edge(rng, target);
        break;
      case 1:
        aim = target[0];  // the shared vertex of the fans
        break;
      default:
        aim = center + scale.size * 2 * random_unit(rng);
    }
    const Vec3 origin = aim + scale.reach * random_unit(rng);
    const Ray ray{origin, (aim - origin) / length(aim - origin)};
    ASSERT_NO_FATAL_FAILURE(check_lanes_and_limits(triangles, ray, tally));
    // A ray leaving a triangle's surface, as shadow and secondary rays do.
    const Ray leaving{aim, random_unit(rng)};
    ASSERT_NO_FATAL_FAILURE(check_lanes_and_limits(triangles, leaving, tally));
  }
  std::printf("double hits %ld; decided missed %ld, hit %ld of %ld\n", tally.double_hits,
              tally.missed, tally.hit, tally.lanes);
  EXPECT_GT(tally.double_hits, 1000);
  // The test decides lanes at all (so that this checks something) where float can tell the
  // triangles apart: not where float's spacing (2^-24 of the offset) nears a thousandth of their
  // size, nor where the bound's floor or float's range take over. Rays leaving a triangle and
  // t_max at a hit leave many hits undecided.
  if (scale.size >= 1e-3 * scale.offset && scale.size > 1e-15 && scale.offset < 1e15) {
    EXPECT_GT(tally.missed, tally.lanes / 4);
    EXPECT_GT(tally.hit, tally.double_hits / 20);
  }
}

INSTANTIATE_TEST_SUITE_P(FloatLanes, FloatLanesScales,
                         ::testing::Values(Scale{0, 1, 10}, Scale{0, 1e-3, 1}, Scale{1, 1e-2, 3},
                                           Scale{1e5, 1, 10}, Scale{1e5, 1e-2, 1},
                                           Scale{1e5, 1e-3, 1e-3}, Scale{3e7, 1, 100},
                                           Scale{0, 1e-20, 1e-20}, Scale{1e-20, 1e-22, 1e-21},
                                           Scale{0, 1e-39, 1e-39}, Scale{1e3, 1e3, 1e4},
                                           Scale{1e36, 1e35, 1e36}));

// Lanes without a triangle are missed; coordinates beyond float's range are never decided.
TEST(FloatLanes, EmptyLanesAreMissedAndFloatsRangeIsNeverExceeded) {
  const Corners triangle{Vec3{-1, -1, 0}, Vec3{1, -1, 0}, Vec3{0, 1, 0}};
  FloatTriangleQuad quad;
  for (int lane = 0; lane < 4; ++lane) set_float_quad_lane_never_hit(quad, lane);
  set_float_quad_lane(quad, 2, triangle.data());
  const TriangleLanesRay down = prepare_triangle_lanes_ray(Ray{{0, 0, 1}, {0, 0, -1}});
  const FloatLaneDecisions decisions = decide_triangle_float_lanes<Sse2FloatLanes, true>(
      &quad, prepare_float_lanes_ray(down), kInfinity, 15);
  EXPECT_EQ(decisions.undecided, 0u);
  EXPECT_EQ(decisions.hit, 4u);
  const double big = 1e39;
  const Corners far{Vec3{big, 0, 0}, Vec3{big, 1, 0}, Vec3{big, 0, 1}};
  for (int lane = 0; lane < 4; ++lane) set_float_quad_lane(quad, lane, far.data());
  const TriangleLanesRay towards = prepare_triangle_lanes_ray(Ray{{0, 0.2, 0.2}, {1, 0, 0}});
  const FloatLaneDecisions beyond = decide_triangle_float_lanes<Sse2FloatLanes, true>(
      &quad, prepare_float_lanes_ray(towards), kInfinity, 15);
  EXPECT_EQ(beyond.undecided, 15u);
  EXPECT_EQ(beyond.hit, 0u);
}

#endif

}  // namespace
}  // namespace tessera
