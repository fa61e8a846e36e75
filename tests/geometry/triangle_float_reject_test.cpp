// The float pre-test of mesh leaves (triangle_float_reject.h) only rejects: no lane that the
// double watertight test hits is ever rejected, on random rays and on the adversarial ones where
// float's error is largest against the edge functions (rays through edges and shared vertices,
// triangles far from the origin, tiny and huge triangles, coordinates below float's normal
// range and beyond its range). The SSE path gives bit for bit the scalar path's lanes.
#include "common/geometry/triangle_float_reject.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cmath>
#include <limits>
#include <random>

#include "common/geometry/triangle.h"

namespace tessera {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

using Corners = std::array<Vec3, 3>;

struct Tally {
  long double_hits = 0;  // lanes the double test hits
  long rejected = 0;     // lanes the float test rejects
  long lanes = 0;
};

// The four triangles against one ray: every lane the double test hits survives the float test,
// and the SIMD path agrees with the scalar one.
void check_quad(const std::array<Corners, 4>& triangles, const Ray& ray, double t_max,
                Tally& tally) {
  FloatTriangleQuad quad;
  const TriangleRay triangle_ray = prepare_triangle_ray(ray);
  const FloatTriangleRay float_ray = prepare_float_triangle_ray(triangle_ray);
  for (int lane = 0; lane < 4; ++lane) {
    const Corners& p = triangles[static_cast<std::size_t>(lane)];
    if (triangle_is_degenerate(p[0], p[1], p[2]))
      set_float_quad_lane_never_hit(quad, lane);
    else
      set_float_quad_lane(quad, lane, p.data());
  }
  const unsigned survivors = float_triangle_survivors_scalar(quad, triangle_ray, float_ray);
#if defined(__SSE2__)
  ASSERT_EQ(float_triangle_survivors_sse(quad, triangle_ray, float_ray), survivors);
#endif
  for (int lane = 0; lane < 4; ++lane) {
    const Corners& p = triangles[static_cast<std::size_t>(lane)];
    TriangleHit hit;
    const bool double_hit = !triangle_is_degenerate(p[0], p[1], p[2]) &&
                            intersect_triangle(p[0], p[1], p[2], triangle_ray, t_max, hit);
    const bool survived = (survivors >> lane & 1) != 0;
    ++tally.lanes;
    tally.double_hits += double_hit;
    tally.rejected += !survived;
    ASSERT_TRUE(survived || !double_hit)
        << "lane " << lane << " rejected but hit; origin " << ray.origin.x << " "
        << ray.origin.y << " " << ray.origin.z << " direction " << ray.direction.x << " "
        << ray.direction.y << " " << ray.direction.z;
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
  for (Vec3& corner : p)
    corner = center + size * Vec3{unit(rng), unit(rng), unit(rng)};
  return p;
}

// A point of the triangle's boundary or near it: on an edge (or at a vertex), nudged off it by
// a few of double's steps, where the edge function is nearly zero.
Vec3 near_edge(std::mt19937_64& rng, const Corners& p) {
  std::uniform_int_distribution<int> pick(0, 2);
  std::uniform_real_distribution<double> along(0, 1);
  const int a = pick(rng), b = (a + 1) % 3;
  const double s = pick(rng) == 0 ? 0.0 : along(rng);  // a third of them at a vertex
  Vec3 point = p[a] + s * (p[b] - p[a]);
  std::uniform_int_distribution<int> steps(-4, 4);
  const double nudge = steps(rng) * 1e-16 * length(p[b] - p[a]);
  return point + nudge * random_unit(rng);
}

struct Scale {
  double offset;  // distance of the triangles from the world's origin
  double size;    // the triangles' size
  double reach;   // the rays' origins' distance from the triangles
};

class FloatRejectScales : public ::testing::TestWithParam<Scale> {};

TEST_P(FloatRejectScales, NeverRejectsALaneTheDoubleTestHits) {
  const Scale scale = GetParam();
  std::mt19937_64 rng(1234);
  Tally tally;
  for (int round = 0; round < 4000; ++round) {
    const Vec3 center = scale.offset * random_unit(rng);
    std::array<Corners, 4> triangles;
    for (Corners& t : triangles) t = random_triangle(rng, center, scale.size);
    // Every other round, a fan around a shared vertex: rays aimed at it hit at least one of
    // them, and the float test must keep each one the double test hits.
    if (round % 2 == 1) {
      for (std::size_t i = 1; i < 4; ++i) triangles[i][0] = triangles[0][0];
      for (std::size_t i = 1; i < 4; ++i) triangles[i][1] = triangles[i - 1][2];
    }
    const Corners& target = triangles[static_cast<std::size_t>(round % 4)];
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
    // Unit directions: the double test misses with directions as tiny as the tiniest triangles.
    const Ray ray{origin, (aim - origin) / length(aim - origin)};
    ASSERT_NO_FATAL_FAILURE(check_quad(triangles, ray, kInfinity, tally));
    // A ray leaving a triangle's surface, as shadow and secondary rays do.
    const Ray leaving{aim, random_unit(rng)};
    ASSERT_NO_FATAL_FAILURE(check_quad(triangles, leaving, kInfinity, tally));
  }
  std::printf("hits %ld rejected %ld of %ld\n", tally.double_hits, tally.rejected, tally.lanes);
  EXPECT_GT(tally.double_hits, 1000);
  // The test rejects lanes at all (so that this checks something) where float can tell the
  // triangles apart: not where float's spacing nears their size, nor where the bound's floor or
  // float's range take over.
  if (scale.size >= 1e-5 * scale.offset && scale.size > 1e-15 && scale.offset < 1e15) {
    EXPECT_GT(tally.rejected, tally.lanes / 8);
  }
}

INSTANTIATE_TEST_SUITE_P(
    FloatReject, FloatRejectScales,
    ::testing::Values(Scale{0, 1, 10}, Scale{0, 1e-3, 1}, Scale{1, 1e-2, 3},
                      Scale{1e5, 1, 10}, Scale{1e5, 1e-2, 1}, Scale{1e5, 1e-3, 1e-3},
                      Scale{3e7, 1, 100}, Scale{0, 1e-20, 1e-20}, Scale{1e-20, 1e-22, 1e-21},
                      Scale{0, 1e-39, 1e-39}, Scale{1e3, 1e3, 1e4}, Scale{1e36, 1e35, 1e36}));

// Lanes that the double test never hits (NaN corners: gaps and degenerate triangles) are
// rejected, and a ray the double test cannot use hits nothing.
TEST(FloatReject, NeverHitLanesAndUnusableRays) {
  const Corners triangle{Vec3{-1, -1, 0}, Vec3{1, -1, 0}, Vec3{0, 1, 0}};
  FloatTriangleQuad quad;
  for (int lane = 0; lane < 4; ++lane) {
    if (lane == 2)
      set_float_quad_lane(quad, lane, triangle.data());
    else
      set_float_quad_lane_never_hit(quad, lane);
  }
  const TriangleRay down = prepare_triangle_ray(Ray{{0, 0, 1}, {0, 0, -1}});
  EXPECT_EQ(float_triangle_survivors_scalar(quad, down, prepare_float_triangle_ray(down)), 4u);
  const TriangleRay still = prepare_triangle_ray(Ray{{0, 0, 1}, {0, 0, 0}});
  EXPECT_EQ(float_triangle_survivors_scalar(quad, still, prepare_float_triangle_ray(still)), 0u);
#if defined(__SSE2__)
  EXPECT_EQ(float_triangle_survivors_sse(quad, down, prepare_float_triangle_ray(down)), 4u);
  EXPECT_EQ(float_triangle_survivors_sse(quad, still, prepare_float_triangle_ray(still)), 0u);
#endif
}

// Coordinates beyond float's range: nothing is rejected (the bound is infinite or NaN).
TEST(FloatReject, CoordinatesBeyondFloatsRangeAreNeverRejected) {
  const double big = 1e39;
  const Corners triangle{Vec3{big, 0, 0}, Vec3{big, 1, 0}, Vec3{big, 0, 1}};
  FloatTriangleQuad quad;
  for (int lane = 0; lane < 4; ++lane) set_float_quad_lane(quad, lane, triangle.data());
  const TriangleRay ray = prepare_triangle_ray(Ray{{0, 5, 5}, {1, 0, 0}});
  EXPECT_EQ(float_triangle_survivors_scalar(quad, ray, prepare_float_triangle_ray(ray)), 15u);
#if defined(__SSE2__)
  EXPECT_EQ(float_triangle_survivors_sse(quad, ray, prepare_float_triangle_ray(ray)), 15u);
#endif
}

}  // namespace
}  // namespace tessera
