// The lane tests of mesh leaves, two triangles at a time (SSE2, where the build has it) and four
// (AVX2, where the CPU has it): each gives bit for bit the hits of the scalar path, which is the
// one-triangle test of triangle.h per lane, so that images do not depend on the CPU. Rays graze
// edges and vertices, start on or near the triangles' planes (where the t error bound decides),
// meet t_max at the hit's exact t, and lanes hold NaN corners (the padding of odd leaves) or huge
// coordinates.
#include "common/geometry/intersect_triangle_pair.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "common/math/float_error.h"

namespace tessera {
namespace {

struct Corners {
  Vec3 p[3];
};

TriangleQuad make_quad(const Corners* const corners[4]) {
  TriangleQuad quad;
  for (int lane = 0; lane < 4; ++lane)
    for (int c = 0; c < 3; ++c) set_quad_corner(quad, c, lane, corners[lane]->p[c]);
  return quad;
}

// Lane hits that match no test's: each entry a path reports must be its own.
TriangleLaneHits unset_hits() {
  TriangleLaneHits hits;
  for (double* entries : {hits.t, hits.b0, hits.b1, hits.b2})
    for (int lane = 0; lane < kTriangleLanesMax; ++lane)
      entries[lane] = std::numeric_limits<double>::quiet_NaN();
  return hits;
}

void expect_same_bits(double a, double b, const char* what) {
  EXPECT_EQ(std::bit_cast<std::uint64_t>(a), std::bit_cast<std::uint64_t>(b)) << what;
}

// The lanes of `fast` reported hit agree bit for bit with the one-triangle test on `corners`;
// its lanes, `lane_count` from `first`, are those bits of `fast_lanes` and entries of `fast`.
void expect_lanes_match(const Corners* const corners[4], int first, int lane_count,
                        unsigned fast_lanes, const TriangleLaneHits& fast,
                        const TriangleRay& triangle_ray, double t_max, const char* path) {
  for (int lane = first; lane < first + lane_count; ++lane) {
    const Corners& triangle = *corners[lane];
    TriangleHit single;
    const bool hit = intersect_triangle(triangle.p[0], triangle.p[1], triangle.p[2], triangle_ray,
                                        t_max, single);
    EXPECT_EQ(hit, (fast_lanes >> lane & 1) != 0) << path << " lane " << lane;
    if (!hit || (fast_lanes >> lane & 1) == 0) continue;
    expect_same_bits(fast.t[lane], single.t, "t");
    expect_same_bits(fast.b0[lane], single.b0, "b0");
    expect_same_bits(fast.b1[lane], single.b1, "b1");
    expect_same_bits(fast.b2[lane], single.b2, "b2");
  }
}

// Every path on the four triangles a, b, c, d (a quad, halves a b and c d) and one ray: each half
// alone, the quad at once with AVX2 where the CPU has it, and the scalar path, each checked lane by
// lane against the one-triangle test. Returns the lanes hit (a: bit 0 ... d: bit 3).
unsigned expect_paths_agree(const Corners& a, const Corners& b, const Corners& c, const Corners& d,
                            const Ray& ray, double t_max) {
  const Corners* const corners[4] = {&a, &b, &c, &d};
  const TriangleQuad quad = make_quad(corners);
  const TriangleLanesRay lanes_ray = prepare_triangle_lanes_ray(ray);
  const TriangleRay& triangle_ray = lanes_ray.ray;
  TriangleLaneHits scalar = unset_hits();
  const unsigned scalar_lanes =
      intersect_triangle_lanes_scalar(quad, 0, 4, triangle_ray, t_max, scalar);
  expect_lanes_match(corners, 0, 4, scalar_lanes, scalar, triangle_ray, t_max, "scalar");
  for (int half = 0; half < 2; ++half) {
    TriangleLaneHits half_hits = unset_hits();
    const unsigned half_lanes =
        intersect_triangle_lanes_scalar(quad, 2 * half, 2, triangle_ray, t_max, half_hits);
    expect_lanes_match(corners, 2 * half, 2, half_lanes, half_hits, triangle_ray, t_max,
                       "scalar half");
    TriangleLaneHits pair_hits = unset_hits();
    const unsigned pair_lanes = intersect_triangle_pair(quad, half, lanes_ray, t_max, pair_hits);
    expect_lanes_match(corners, 2 * half, 2, pair_lanes, pair_hits, triangle_ray, t_max, "pair");
    // A half reports its own lanes only, as the bits of the quad's.
    EXPECT_EQ(half_lanes & ~(3u << 2 * half), 0u);
    EXPECT_EQ(pair_lanes & ~(3u << 2 * half), 0u);
  }
#if defined(__SSE2__)
  if (__builtin_cpu_supports("avx2")) {
    TriangleLaneHits quad_hits = unset_hits();
    const unsigned quad_lanes = intersect_triangle_quad(quad, lanes_ray, t_max, quad_hits);
    expect_lanes_match(corners, 0, 4, quad_lanes, quad_hits, triangle_ray, t_max, "quad");
  }
#endif
  return scalar_lanes;
}

// Triangles a and b in both halves (a b, and b a), for the cases written for pairs.
unsigned expect_paths_agree(const Corners& a, const Corners& b, const Ray& ray, double t_max) {
  const unsigned lanes = expect_paths_agree(a, b, b, a, ray, t_max);
  EXPECT_EQ(lanes >> 2, (lanes & 1) << 1 | (lanes >> 1 & 1));
  return lanes & 3;
}

Vec3 random_point(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-1, 1);
  return Vec3{u(rng), u(rng), u(rng)} * scale;
}

TEST(TrianglePair, PathsAgreeOnRandomTrianglesAndRays) {
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> u(0, 1);
  int hits = 0, tight = 0;
  for (int i = 0; i < 20000; ++i) {
    const double scale = std::pow(10.0, 6 * u(rng) - 3);  // 1e-3 to 1e3
    const Vec3 centre = random_point(rng, std::pow(10.0, 5 * u(rng)));
    Corners triangles[4];
    for (Corners& triangle : triangles)
      for (Vec3& p : triangle.p) p = centre + random_point(rng, scale);
    // Aim at a random point of one lane's triangle, its edge or its vertex.
    const Corners& aimed = triangles[(i / 3) % 4];
    const double w0 = u(rng), w1 = (1 - w0) * u(rng);
    const int kind = i % 3;
    const double v0 = kind == 2 ? 1 : w0, v1 = kind == 2 ? 0 : kind == 1 ? 1 - w0 : w1;
    const Vec3 target = aimed.p[0] * v0 + aimed.p[1] * v1 + aimed.p[2] * (1 - v0 - v1);
    const Vec3 origin = centre + random_point(rng, 4 * scale);
    const Ray ray{origin, (target - origin) * std::pow(10.0, 4 * u(rng) - 2)};
    const auto agree = [&](double t_max) {
      return std::popcount(
          expect_paths_agree(triangles[0], triangles[1], triangles[2], triangles[3], ray, t_max));
    };
    hits += agree(kInfinity);
    // t_max at the hit's t and one step either side: the limit's comparisons.
    TriangleHit h;
    if (intersect_triangle(aimed.p[0], aimed.p[1], aimed.p[2], ray, kInfinity, h)) {
      for (const double limit : {h.t, next_up(h.t), next_down(h.t)}) tight += agree(limit);
    }
  }
  EXPECT_GT(hits, 10000);  // the cases above must hit often to show anything
  EXPECT_GT(tight, 5000);
}

TEST(TrianglePair, PathsAgreeForOriginsOnAndNearThePlane) {
  // Rays leaving a triangle's surface: t is within its error bound of zero, which decides.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  int hits = 0, misses = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 centre = random_point(rng, 1e4 * u(rng));
    Corners a, b;
    for (Vec3& p : a.p) p = centre + random_point(rng, 1);
    for (Vec3& p : b.p) p = centre + random_point(rng, 1);
    const double w0 = u(rng), w1 = (1 - w0) * u(rng);
    const Vec3 on = a.p[0] * w0 + a.p[1] * w1 + a.p[2] * (1 - w0 - w1);
    const Vec3 normal = cross(a.p[1] - a.p[0], a.p[2] - a.p[0]);
    const double offset = (u(rng) - 0.5) * std::pow(10.0, -16 * u(rng)) * (length(centre) + 1);
    const Ray ray{on + normal * offset, random_point(rng, 1)};
    const unsigned lanes = expect_paths_agree(a, b, ray, kInfinity);
    (lanes & 1) != 0 ? ++hits : ++misses;
  }
  EXPECT_GT(hits, 100);
  EXPECT_GT(misses, 100);
}

// The lanes' ray, built in place from prepare_triangle_ray's result (intersect_triangle_pair.h),
// holds that result, the origin permuted by its axes, bit for bit, and the byte offsets of those
// axes' coordinates in a quad's corner, for every largest axis.
TEST(TrianglePair, LanesRayIsTheTriangleRayAndItsPermutedOrigin) {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> coordinate(-3, 3);
  for (int i = 0; i < 1000; ++i) {
    const Ray ray{{coordinate(rng), coordinate(rng), coordinate(rng)},
                  {coordinate(rng), coordinate(rng), coordinate(rng)}};
    const TriangleRay expected = prepare_triangle_ray(ray);
    const TriangleLanesRay lanes_ray = prepare_triangle_lanes_ray(ray);
    const TriangleRay& got = lanes_ray.ray;
    EXPECT_EQ(got.kx, expected.kx);
    EXPECT_EQ(got.ky, expected.ky);
    EXPECT_EQ(got.kz, expected.kz);
    EXPECT_EQ(got.usable, expected.usable);
    expect_same_bits(got.sx, expected.sx, "sx");
    expect_same_bits(got.sy, expected.sy, "sy");
    expect_same_bits(got.sz, expected.sz, "sz");
    const Vec3 origin = permute_axes(ray.origin, expected.kx, expected.ky, expected.kz);
    expect_same_bits(got.origin.x, ray.origin.x, "origin.x");
    expect_same_bits(got.origin.y, ray.origin.y, "origin.y");
    expect_same_bits(got.origin.z, ray.origin.z, "origin.z");
    expect_same_bits(lanes_ray.origin[0], origin.x, "permuted x");
    expect_same_bits(lanes_ray.origin[1], origin.y, "permuted y");
    expect_same_bits(lanes_ray.origin[2], origin.z, "permuted z");
    const int axes[3] = {expected.kx, expected.ky, expected.kz};
    const TriangleQuad quad{};
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(reinterpret_cast<const char*>(quad.corner[1]) + lanes_ray.coordinate_offset[k],
                reinterpret_cast<const char*>(quad.corner[1][axes[k]]));
  }
}

TEST(TrianglePair, NaNLanesAndSpecialRaysAgree) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const Corners triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  const Corners padding{{{kNaN, kNaN, kNaN}, {kNaN, kNaN, kNaN}, {kNaN, kNaN, kNaN}}};
  const Corners huge{{{-1e300, -1e300, 0}, {1e300, -1e300, 0}, {0, 1e300, 0}}};
  const Corners flat{{{0, 0, 0}, {1, 1, 0}, {2, 2, 0}}};
  const Ray down{{0.25, 0.25, 1}, {0, 0, -1}};
  EXPECT_EQ(expect_paths_agree(triangle, padding, down, kInfinity), 1u);
  EXPECT_EQ(expect_paths_agree(padding, triangle, down, kInfinity), 2u);
  EXPECT_EQ(expect_paths_agree(padding, padding, down, kInfinity), 0u);
  expect_paths_agree(huge, triangle, down, kInfinity);
  EXPECT_EQ(expect_paths_agree(flat, triangle, down, kInfinity), 2u);
  EXPECT_EQ(expect_paths_agree(triangle, triangle, down, 1.0), 0u);  // t = 1 is not below 1
  // Padding in either half of a quad, as in leaves of three.
  EXPECT_EQ(expect_paths_agree(triangle, flat, triangle, padding, down, kInfinity), 5u);
  EXPECT_EQ(expect_paths_agree(padding, padding, padding, triangle, down, kInfinity), 8u);
  EXPECT_EQ(expect_paths_agree(padding, padding, padding, padding, down, kInfinity), 0u);
  for (const Ray& ray :
       {Ray{{0.25, 0.25, 1}, {0, 0, 0}}, Ray{{0.25, 0.25, 1}, {0, kNaN, -1}},
        Ray{{0.25, 0.25, 1}, {0, 0, -kInfinity}}, Ray{{0.25, 0.25, 0}, {0, 0, 1}},
        Ray{{-1, 0.25, 0}, {1, 0, 0}}, Ray{{0.5, 0.5, 1}, {0, 0, -1}}, Ray{{0, 0, 1}, {0, 0, -1}},
        Ray{{0.25, 0.25, 1e-300}, {1e-300, 1e-300, -1}}})
    expect_paths_agree(triangle, huge, ray, kInfinity);
}

}  // namespace
}  // namespace tessera
