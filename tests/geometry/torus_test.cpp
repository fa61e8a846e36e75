// Ray / torus intersection (shapes.h) against roots constructed analytically, in long double
// where the construction itself could round.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>

#include "common/geometry/instance.h"
#include "common/geometry/shapes.h"
#include "common/geometry/torus.h"
#include "common/math/float_error.h"
#include "tests/geometry/test_meshes.h"

namespace tessera {
namespace {

constexpr Torus kRing{0.25, 1};
constexpr Torus kHorn{1, 1};
constexpr Torus kSpindle{1, 0.5};

// The torus function, in long double: zero on the surface.
long double torus_function(const Torus& t, const Vec3& p) {
  const long double x = p.x, y = p.y, z = p.z, big_r = t.torus_radius, r = t.tube_radius;
  const long double k = x * x + y * y + z * z + big_r * big_r - r * r;
  return k * k - 4 * big_r * big_r * (x * x + y * y);
}

// Distance from p to the surface, to first order.
double surface_distance(const Torus& t, const Vec3& p) {
  const long double x = p.x, y = p.y, z = p.z, big_r = t.torus_radius, r = t.tube_radius;
  const long double k = x * x + y * y + z * z + big_r * big_r - r * r;
  const long double gx = 4 * k * x - 8 * big_r * big_r * x, gy = 4 * k * y - 8 * big_r * big_r * y,
                    gz = 4 * k * z;
  return static_cast<double>(std::fabs(torus_function(t, p)) /
                             std::sqrt(gx * gx + gy * gy + gz * gz));
}

std::vector<double> crossing_ts(const Torus& t, const Ray& ray) {
  std::vector<double> ts;
  for (const LocalHit& h : torus_crossings(t, ray, kInfinity)) ts.push_back(h.t);
  return ts;
}

TEST(Torus, AxisAlignedRayThroughTheTubes) {
  LocalHit hit;
  ASSERT_TRUE(intersect_torus(kRing, {{-5, 0, 0}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 3.75);
  EXPECT_EQ(hit.point, (Vec3{-1.25, 0, 0}));
  EXPECT_NEAR(hit.normal.x / length(hit.normal), -1, 1e-15);
  EXPECT_EQ(hit.shading_normal, hit.normal);
  const std::vector<double> ts = crossing_ts(kRing, {{-5, 0, 0}, {1, 0, 0}});
  ASSERT_EQ(ts.size(), 4u);
  const double expected[] = {3.75, 4.25, 5.75, 6.25};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(ts[i], expected[i], 1e-15) << i;
  // t is in units of the direction.
  ASSERT_TRUE(intersect_torus(kRing, {{-5, 0, 0}, {4, 0, 0}}, kInfinity, hit));
  EXPECT_NEAR(hit.t, 3.75 / 4, 1e-16);
}

TEST(Torus, MissesRespectsTMaxAndFindsTheExitFromInside) {
  LocalHit hit;
  EXPECT_FALSE(intersect_torus(kRing, {{-5, 0, 0.26}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_FALSE(intersect_torus(kRing, {{5, 0, 0}, {1, 0, 0}}, kInfinity, hit));  // behind
  EXPECT_FALSE(intersect_torus(kRing, {{-5, 0, 0}, {1, 0, 0}}, 3.75, hit));
  EXPECT_FALSE(intersect_torus(kRing, {{-5, 0, 0}, {0, 0, 0}}, kInfinity, hit));
  EXPECT_FALSE(intersect_torus(kRing, {{-5, NAN, 0}, {1, 0, 0}}, kInfinity, hit));
  // Inside the tube, the exit: the normal still points out of the tube.
  ASSERT_TRUE(intersect_torus(kRing, {{1, 0, 0}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 0.25);
  EXPECT_EQ(hit.point, (Vec3{1, 0, 0.25}));
  EXPECT_GT(hit.normal.z, 0);
}

TEST(Torus, RaysAlongTheAxis) {
  LocalHit hit;
  // Through the hole of a ring torus: nothing.
  EXPECT_FALSE(intersect_torus(kRing, {{0, 0, -5}, {0, 0, 1}}, kInfinity, hit));
  // Parallel to the axis through the tube's centre circle: z = -r, then z = +r.
  ASSERT_TRUE(intersect_torus(kRing, {{0, 1, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 4.75);
  EXPECT_EQ(hit.point, (Vec3{0, 1, -0.25}));
  EXPECT_EQ(crossing_ts(kRing, {{0, 1, -5}, {0, 0, 1}}), (std::vector<double>{4.75, 5.25}));
  // The seen-along-the-axis silhouette is the annulus of radii R - r and R + r, of area
  // 4 pi R r: sampled on a grid of parallel rays.
  const int n = 400;
  const double half = 1.3;
  int hits = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -half + (i + 0.5) * (2 * half / n), y = -half + (j + 0.5) * (2 * half / n);
      hits += intersect_torus(kRing, {{x, y, 10}, {0, 0, -1}}, kInfinity, hit);
    }
  const double area = hits * (2 * half / n) * (2 * half / n);
  EXPECT_NEAR(area, 4 * M_PI * 1 * 0.25, 0.01 * 4 * M_PI * 0.25);
}

// Rays tangent to the outer equator (x = R + r - delta, z = 0, along y): the two roots are
// y = +-sqrt((R + r)^2 - x^2), a near-double root when delta is small.
TEST(Torus, GrazingTheOuterEquator) {
  LocalHit hit;
  for (double delta : {1e-3, 1e-6, 1e-9, 1e-12}) {
    SCOPED_TRACE(delta);
    const double x = 1.25 - delta;
    const long double lx = x;
    const double half_chord = static_cast<double>(std::sqrt(1.5625L - lx * lx));
    const Ray ray{{x, -10, 0}, {0, 1, 0}};
    ASSERT_TRUE(intersect_torus(kRing, ray, kInfinity, hit));
    // The attainable accuracy of a pair 2w apart is about eps * |F| / (w |F''|).
    const double tolerance = 1e-15 / half_chord + 1e-14;
    EXPECT_NEAR(hit.t, 10 - half_chord, std::max(tolerance, 2e-8));
    EXPECT_LT(surface_distance(kRing, hit.point), 1e-15);
    const std::vector<double> ts = crossing_ts(kRing, ray);
    ASSERT_EQ(ts.size(), 2u);  // two crossings, or one touching root counted twice
    EXPECT_NEAR(ts[1], 10 + half_chord, std::max(tolerance, 2e-8));
  }
  // Exactly tangent: one touching hit.
  ASSERT_TRUE(intersect_torus(kRing, {{1.25, -10, 0}, {0, 1, 0}}, kInfinity, hit));
  EXPECT_NEAR(hit.t, 10, 1e-7);
  EXPECT_NEAR(hit.point.x, 1.25, 1e-15);
  EXPECT_GT(hit.normal.x, 0);
  EXPECT_FALSE(intersect_torus(kRing, {{1.25 + 1e-12, -10, 0}, {0, 1, 0}}, kInfinity, hit));
}

// Rays grazing the top of the tube (z = r - delta, along x): near-double roots at
// x = +-R +- sqrt(r^2 - z^2), compared with the construction in long double.
TEST(Torus, GrazingTheTopOfTheTube) {
  for (double delta : {1e-4, 1e-8, 1e-12}) {
    SCOPED_TRACE(delta);
    const double z = 0.25 - delta;
    const long double lz = z;
    const long double w = std::sqrt(0.0625L - lz * lz);
    const double expected[4] = {static_cast<double>(-1 - w), static_cast<double>(-1 + w),
                                static_cast<double>(1 - w), static_cast<double>(1 + w)};
    const std::vector<LocalHit> hits = torus_crossings(kRing, {{-5, 0, z}, {1, 0, 0}}, kInfinity);
    ASSERT_EQ(hits.size(), 4u);
    for (int i = 0; i < 4; ++i) {
      EXPECT_NEAR(hits[i].t - 5, expected[i], std::max(4e-16 / static_cast<double>(w), 1e-7)) << i;
      EXPECT_LT(surface_distance(kRing, hits[i].point), 1e-15) << i;
      EXPECT_TRUE(is_finite(hits[i].normal));
    }
  }
}

// From 10 to 10^6 units away the digits survive: the quartic is formed near the torus.
TEST(Torus, RaysFromFarAway) {
  LocalHit hit;
  for (double distance : {1e1, 1e2, 1e4, 1e6}) {
    SCOPED_TRACE(distance);
    // Along x at y = 0.1: the first root is x = -sqrt((R + r)^2 - 0.01).
    ASSERT_TRUE(intersect_torus(kRing, {{-distance, 0.1, 0}, {1, 0, 0}}, kInfinity, hit));
    const double x = static_cast<double>(-std::sqrt(1.5625L - 0.01L));
    EXPECT_NEAR(hit.point.x, x, 1e-15);
    EXPECT_NEAR(hit.t, distance + x, distance * 4e-16);
    EXPECT_LT(surface_distance(kRing, hit.point), 1e-15);
    // Obliquely, through the known point (1, 0, 0.25) on top of the tube.
    const Vec3 target{1, 0, 0.25};
    const Vec3 dir = normalize_or(Vec3{0.3, -0.2, -1}, {});
    const Ray ray{target - dir * distance, dir};
    ASSERT_TRUE(intersect_torus(kRing, ray, kInfinity, hit));
    EXPECT_LT(surface_distance(kRing, hit.point), 1e-15);
    EXPECT_NEAR(hit.point.z, 0.25, 1e-6);  // the tube's top, reached at a shallow angle
    EXPECT_NEAR(hit.t, distance, distance * 1e-15 + 1e-6);
  }
}

// The horn torus (r = R) pinches at the origin: along x, F = x^2 (x^2 - 4 R^2), a double root
// at 0 between simple ones at +-2R.
TEST(Torus, HornTorusPinchPoint) {
  LocalHit hit;
  for (double degrees : {90.0, 60.0, 20.0}) {
    SCOPED_TRACE(degrees);
    const double a = degrees * M_PI / 180;
    const Vec3 dir{std::sin(a), 0, std::cos(a)};
    const Ray ray{dir * -5, dir};
    // Along this meridian, F = s^2 (s^2 - 4 R^2 sin^2 a).
    const double w = 2 * std::sin(a);
    const std::vector<double> ts = crossing_ts(kHorn, ray);
    ASSERT_EQ(ts.size(), 4u);
    EXPECT_NEAR(ts[0], 5 - w, 1e-14);
    EXPECT_NEAR(ts[1], 5, 1e-7);  // the pinch: touching, counted twice
    EXPECT_NEAR(ts[2], 5, 1e-7);
    EXPECT_NEAR(ts[3], 5 + w, 1e-14);
    ASSERT_TRUE(intersect_torus(kHorn, ray, kInfinity, hit));
    EXPECT_NEAR(hit.t, 5 - w, 1e-14);
    // From inside the tube, aimed at the pinch: the pinch itself, with finite values.
    const Ray inside{dir * -0.5, dir};
    ASSERT_TRUE(intersect_torus(kHorn, inside, kInfinity, hit));
    EXPECT_NEAR(hit.t, 0.5, 1e-7);
    EXPECT_TRUE(is_finite(hit.point) && is_finite(hit.normal) && is_finite(hit.point_error));
    EXPECT_GT(length(hit.normal), 0);
  }
  // Along the axis, F = z^4: a quadruple root at the pinch.
  ASSERT_TRUE(intersect_torus(kHorn, {{0, 0, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 5);
  EXPECT_EQ(hit.point, Vec3{});
  EXPECT_EQ(hit.normal, (Vec3{0, 0, -1}));  // facing the ray: the gradient vanishes
  EXPECT_GT(max_component(hit.point_error), 0);
}

// The spindle torus (r > R): along x, roots at +-R +- r; the inner "lemon" is part of the
// surface. Along the axis, the cusps at z = +-sqrt(r^2 - R^2).
TEST(Torus, SpindleTorus) {
  LocalHit hit;
  const std::vector<LocalHit> hits = torus_crossings(kSpindle, {{-5, 0, 0}, {1, 0, 0}}, kInfinity);
  ASSERT_EQ(hits.size(), 4u);
  const double expected[] = {-1.5, -0.5, 0.5, 1.5};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(hits[i].point.x, expected[i], 1e-15) << i;
    EXPECT_LT(surface_distance(kSpindle, hits[i].point), 1e-15);
  }
  // The gradient's direction: out of the apple, into the lemon (the solid is between them).
  EXPECT_LT(hits[0].normal.x, 0);
  EXPECT_GT(hits[1].normal.x, 0);
  EXPECT_LT(hits[2].normal.x, 0);
  EXPECT_GT(hits[3].normal.x, 0);
  const double cusp = std::sqrt(0.75);
  ASSERT_TRUE(intersect_torus(kSpindle, {{0, 0, 5}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_NEAR(hit.t, 5 - cusp, 1e-7);
  EXPECT_EQ(hit.normal, (Vec3{0, 0, 1}));
  // Off the axis, through the apple only above the lemon's tip.
  ASSERT_TRUE(intersect_torus(kSpindle, {{0.05, 0, 5}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_LT(surface_distance(kSpindle, hit.point), 1e-15);
  EXPECT_GT(hit.normal.z, 0);
}

TEST(Torus, TransformedInstance) {
  // Stood up in the XZ-plane, scaled by 2 and moved 10^4 away.
  const Affine to_world = Affine::translation({1e4, -3, 2}) * *Affine::rotation(90, {1, 0, 0}) *
                          Affine::scaling({2, 2, 2});
  const std::optional<Instance> inst = make_instance(kRing, to_world, nullptr);
  ASSERT_TRUE(inst);
  EXPECT_NEAR(inst->world_bounds.hi.x, 1e4 + 2.5, 1e-9);
  EXPECT_NEAR(inst->world_bounds.hi.y, -3 + 0.5, 1e-9);
  WorldHit hit;
  IntersectionCounters counters;
  // Along -y onto the tube at world (1e4 + 2, -3, 2): first hit at y = -3 + 0.5.
  ASSERT_TRUE(intersect_instance(*inst, {{1e4 + 2, 10, 2}, {0, -1, 0}}, kInfinity, hit, counters));
  EXPECT_NEAR(hit.t, 12.5, 1e-11);
  EXPECT_NEAR(hit.point.y, -2.5, 1e-11);
  EXPECT_NEAR(hit.normal.y, 1, 1e-12);
  EXPECT_EQ(counters.shape_tests, 1u);
}

// A hit of the instance of `torus` by a ray aimed at a random point of its box, from a random
// direction and 1 to 5 times the box's diagonal away; nullopt when the ray misses. The distance
// is the object box's own, mapped to world space, so that the rays drawn do not change with the
// padding of the instance's world box.
std::optional<WorldHit> random_hit(const Torus& torus, const Affine& to_world, const Instance& inst,
                                   std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  const Bounds3 local = object_bounds(torus, nullptr);
  const double size = length(to_world.apply_vector(local.diagonal()));
  const Vec3 aim{unit(rng), unit(rng), unit(rng)};
  const Vec3 target = to_world.apply_point(local.lo + mul(local.diagonal(), aim));
  const Vec3 origin = target + testing::random_unit(rng) * (size * (1 + 4 * unit(rng)));
  WorldHit hit;
  IntersectionCounters counters;
  if (!intersect_instance(inst, {origin, target - origin}, kInfinity, hit, counters))
    return std::nullopt;
  return hit;
}

// A ray leaving a hit from offset_ray_origin() never finds the same point again: outward rays
// and inward ones alike, on all three kinds of torus and on thin ones, untransformed and under
// random transforms. Judged in object space, where the search runs: a hit of the spawned ray
// within 64 of its own error bounds of the ray's origin is its own surface found again (a real
// crossing lies at least about sqrt(offset * r) away, the tube's far side or, from its inner
// half, the surface curving back into the ray). A distance in world units would not tell: under
// a transform whose rounding is a fair part of a thin tube's width, the tube's far side lies
// within a few world error bounds of the hit. Main before branch thintorus failed it on both
// thin tori (the quartic's rounding band wider than the offset).
TEST(Torus, SpawnedRaysDoNotFindTheirOwnHit) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> unit(0, 1);
  int tested = 0;
  for (const Torus& torus : {kRing, kHorn, kSpindle, Torus{0.01, 1}, Torus{0.001, 1}}) {
    for (int i = 0; i < 120; ++i) {
      const Affine to_world =
          i % 4 == 0 ? Affine::scaling({1, 1, 1}) : testing::random_transform(rng);
      const std::optional<Instance> inst = make_instance(torus, to_world, nullptr);
      ASSERT_TRUE(inst);
      for (int r = 0; r < 20; ++r) {
        const std::optional<WorldHit> found = random_hit(torus, to_world, *inst, rng);
        if (!found) continue;
        const WorldHit& hit = *found;
        ASSERT_TRUE(is_finite(hit.point) && is_finite(hit.normal));
        for (int s = 0; s < 8; ++s) {
          const Vec3 w = testing::random_unit(rng);
          if (dot(w, hit.normal) == 0) continue;
          const Ray ray =
              object_ray(*inst, {offset_ray_origin(hit.point, hit.point_error, hit.normal, w), w});
          LocalHit again;
          ++tested;
          if (!intersect_torus(torus, ray, kInfinity, again)) continue;
          EXPECT_GT(again.t * length(ray.direction), 64 * length(again.point_error))
              << "torus " << torus.tube_radius << " " << torus.torus_radius << " transform " << i;
        }
      }
    }
  }
  EXPECT_GT(tested, 20000);
}

// The ray of Torus.SpawnedRaysDoNotFindTheirOwnHit's kind that main before branch thintorus got
// wrong, on a thin torus, untransformed: the ray leaving the hit found it again at t = 1.2e-14,
// five of the hit's error bounds (then 12 eps (R + r)) from its origin. The quartic the search
// forms is rounded by some eps (R + r)^4, which near a tube of radius r is a band of width about
// eps (R + r)^4 / (R r rho) about the surface (r = 0.01 R: ten times that bound), and the origin
// lay inside it. The hit's bound now covers the band, so the ray starts beyond it.
TEST(Torus, ThinTubeSpawnedRayStartsBeyondTheQuarticsRounding) {
  const Torus thin{0.01, 1};
  const Ray ray{{0x1.3e7f2c050b8fp+1, -0x1.9b33d60fede9bp+0, 0x1.8369d3069a116p-2},
                {-0x1.8df52f9398fe4p+0, 0x1.f2eada713c33ap+0, -0x1.7dd8718af7755p-2}};
  const Vec3 w{0x1.6b90661257819p-1, 0x1.631a0c900167ap-1, 0x1.f18a7526ce11fp-4};
  LocalHit hit;
  ASSERT_TRUE(intersect_torus(thin, ray, kInfinity, hit));
  const Vec3 n = hit.normal / length(hit.normal);
  ASSERT_GT(dot(w, n), 0);
  const Ray spawned{offset_ray_origin(hit.point, hit.point_error, n, w), w};
  LocalHit again;
  EXPECT_FALSE(intersect_torus(thin, spawned, kInfinity, again)) << "t " << again.t;
  EXPECT_FALSE(occluded_torus(thin, spawned, kInfinity));
}

// A hit's error bound covers the band about the surface where the quartic the search forms, in
// rounded arithmetic, may vanish, on tubes down to 0.0001 R thin: rays from the hit moved along
// the normal by just its bound (not the more that offset_ray_origin() adds), to either side and
// leaving to that side, a third of them grazing, never find that surface again near their
// origin. Fails with the band's factor 4 instead of 16, and with main's bound before branch
// thintorus (the point's own rounding only).
TEST(Torus, HitBoundCoversTheQuarticsRounding) {
  std::mt19937_64 rng(67);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const Torus& torus : {Torus{0.0001, 1}, Torus{0.001, 1}, Torus{0.01, 1}, kRing, kSpindle}) {
    const double big_r = torus.torus_radius, r = torus.tube_radius;
    int tested = 0;
    for (int i = 0; i < 15000; ++i) {
      // Aimed at a random point of the surface (the ray may hit another first).
      const double theta = 2 * M_PI * unit(rng), phi = 2 * M_PI * unit(rng);
      const double rho = big_r + r * std::cos(phi);
      const Vec3 target{rho * std::cos(theta), rho * std::sin(theta), r * std::sin(phi)};
      const Vec3 from = target + testing::random_unit(rng) * (1 + 3 * unit(rng));
      LocalHit hit;
      if (!intersect_torus(torus, {from, target - from}, kInfinity, hit)) continue;
      // Near a spindle's cusps its two sheets meet, and a real crossing may lie that near.
      if (std::hypot(hit.point.x, hit.point.y) < 0.01 * (big_r + r)) continue;
      const Vec3 n = hit.normal / length(hit.normal);
      for (int s = 0; s < 8; ++s) {
        const double side = s % 2 == 0 ? 1 : -1;
        Vec3 w = testing::random_unit(rng);
        if (s % 3 == 0) w = w - n * (dot(w, n) * (1 - 1e-3 * unit(rng)));
        if (dot(w, n) * side <= 0) w = -w;
        const Ray ray{hit.point + n * (side * hit.point_error.x), w};
        ++tested;
        LocalHit again;
        if (!intersect_torus(torus, ray, kInfinity, again)) continue;
        ASSERT_GT(again.t, 64 * length(hit.point_error))
            << "torus " << torus.tube_radius << " " << torus.torus_radius << " side " << side;
      }
    }
    EXPECT_GT(tested, 100000) << torus.tube_radius;
  }
}

// occluded_torus answers "is there a hit with t in (0, t_max)" mostly from a sign change of the
// quartic, without the hit, or from a proof that there is none (quartic_miss_proof.h, which the
// grazing rays here test at its margins): always what intersect_torus answers, on rays from far
// away and from near, grazing the tube, leaving the surface (offset as spawned rays are, not
// offset, and from just behind it), and with t_max just before, at and just after the nearest hit,
// where the answer turns.
TEST(Torus, OcclusionAnswersAsTheNearestHit) {
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> unit(0, 1);
  int compared = 0, occluded = 0;
  for (const Torus& torus : {kRing, kHorn, kSpindle, Torus{0.01, 1}}) {
    const double big_r = torus.torus_radius, r = torus.tube_radius;
    const auto expect_same_answer = [&](const Ray& ray, double t_max) {
      LocalHit hit;
      const bool blocked = intersect_torus(torus, ray, t_max, hit);
      ASSERT_EQ(occluded_torus(torus, ray, t_max), blocked)
          << "torus " << r << " " << big_r << " origin " << ray.origin.x << " " << ray.origin.y
          << " " << ray.origin.z << " t_max " << t_max;
      ++compared;
      occluded += blocked;
    };
    // Every ray with t_max unbounded, and around its nearest hit; from each hit, rays leave.
    const auto expect_same_answers = [&](const Ray& ray, bool from_hits) {
      expect_same_answer(ray, kInfinity);
      LocalHit hit;
      if (!intersect_torus(torus, ray, kInfinity, hit)) return;
      for (double t_max : {hit.t, std::nextafter(hit.t, 0.0), std::nextafter(hit.t, kInfinity),
                           hit.t * (1 - 1e-9), hit.t * (1 + 1e-9)})
        expect_same_answer(ray, t_max);
      if (!from_hits) return;
      for (int k = 0; k < 4; ++k) {
        // Not of unit length, so that t's rounding differs from s's.
        const Vec3 w = testing::random_unit(rng) * (0.1 + 10 * unit(rng));
        expect_same_answer({hit.point, w}, kInfinity);
        // Just behind the surface, within the distance at which its own hit is not reported.
        const Vec3 behind = hit.point - w * (4 * length(hit.point_error) * unit(rng));
        expect_same_answer({behind, w}, kInfinity);
        if (dot(w, hit.normal) == 0) continue;
        expect_same_answer({offset_ray_origin(hit.point, hit.point_error, hit.normal, w), w},
                           kInfinity);
      }
    };
    const Bounds3 box = object_bounds(torus, nullptr);
    for (int i = 0; i < 3000; ++i) {
      // Aimed into the box (every tenth ray through the centre, for the pinch and cusps), from
      // near, from far and from very far.
      const Vec3 target = i % 10 == 0
                              ? Vec3{}
                              : box.lo + mul(box.diagonal(), Vec3{unit(rng), unit(rng), unit(rng)});
      const double distance = std::array{1.0, 5.0, 1e4}[i % 3] * (big_r + r);
      const Vec3 origin = target + testing::random_unit(rng) * (distance * (0.5 + unit(rng)));
      expect_same_answers({origin, (target - origin) * (0.1 + 10 * unit(rng))}, true);
      // Grazing: tangent to the outer equator, or to the top of the tube, from a random angle,
      // within delta.
      const double delta = std::pow(10.0, -15 * unit(rng)) * r;
      const double angle = 2 * M_PI * unit(rng), c = std::cos(angle), s = std::sin(angle);
      const double rho = big_r + r - delta;
      expect_same_answers({{rho * c - 3 * s, rho * s + 3 * c, 0}, {s, -c, 0}}, false);
      expect_same_answers({{big_r * c - 3 * s, big_r * s + 3 * c, r - delta}, {s, -c, 0}}, false);
    }
  }
  EXPECT_GT(compared, 100000);
  EXPECT_GT(occluded, compared / 4);
  EXPECT_LT(occluded, compared * 3 / 4);
}

// leaves_the_torus_for_good settles a shadow ray without the quartic only where intersect_torus
// finds nothing: on rays leaving the surface of tori thin and fat under random transforms, offset
// as spawned rays are, not offset, from just behind, and from a few error bounds either side of
// the surface, half of them grazing (down to 10^-6 from the tangent plane), where the search's
// rounding can put a root just past the distance at which it counts as a hit; from both halves
// of the tube. A rounding margin of 0.5 instead of 8 in either half's proof fails it.
TEST(Torus, ExitProofNeverContradictsTheSearch) {
  std::mt19937_64 rng(53);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const Torus& torus : {kRing, kHorn, kSpindle, Torus{0.01, 1}, Torus{0.4, 1.1}}) {
    int offset_exits = 0, proven = 0, proven_offset = 0, proven_inner = 0;
    for (int i = 0; i < 200; ++i) {
      const Affine to_world =
          i % 4 == 0 ? Affine::scaling({1, 1, 1}) : testing::random_transform(rng);
      const std::optional<Instance> inst = make_instance(torus, to_world, nullptr);
      ASSERT_TRUE(inst);
      for (int k = 0; k < 20; ++k) {
        const std::optional<WorldHit> found = random_hit(torus, to_world, *inst, rng);
        if (!found) continue;
        const WorldHit& hit = *found;
        const double error = length(hit.point_error);
        for (int s = 0; s < 8; ++s) {
          Vec3 w = testing::random_unit(rng);
          if (dot(w, hit.normal) < 0) w = -w;
          if (s % 2 == 1) {
            const Vec3 along = w - hit.normal * dot(w, hit.normal);
            w = along / length(along) + hit.normal * std::pow(10.0, -6 * unit(rng));
          }
          w = w * (0.1 + 10 * unit(rng));
          const Vec3 origins[4] = {offset_ray_origin(hit.point, hit.point_error, hit.normal, w),
                                   hit.point, hit.point - w * (4 * error * unit(rng) / length(w)),
                                   hit.point + hit.normal * (error * (16 * unit(rng) - 8))};
          for (int kind = 0; kind < 4; ++kind) {
            const Ray ray = object_ray(*inst, {origins[kind], w});
            if (!leaves_the_torus_for_good(torus, ray)) continue;
            ++proven;
            if (kind == 0) ++proven_offset;
            if (std::hypot(ray.origin.x, ray.origin.y) < torus.torus_radius) ++proven_inner;
            LocalHit again;
            ASSERT_FALSE(intersect_torus(torus, ray, kInfinity, again))
                << "torus " << torus.tube_radius << " " << torus.torus_radius << " origin kind "
                << kind << " t " << again.t;
          }
          ++offset_exits;
        }
      }
    }
    // It settles most rays leaving the surface, and not only offset ones: the other three kinds
    // together about as often (0.99 to 1.16 times on these tori).
    EXPECT_GT(proven_offset, offset_exits / 2) << torus.tube_radius << " " << torus.torus_radius;
    EXPECT_GT(proven - proven_offset, proven_offset * 9 / 10);
    // Rays leaving the inner half too, away from the plane (2.5 to 13 % of those settled).
    EXPECT_GT(proven_inner, proven / 50) << torus.tube_radius << " " << torus.torus_radius;
  }
}

// crosses_into_the_tube settles a shadow ray as blocked without the quartic only where
// intersect_torus finds a hit before t_max: on rays from near, far and very far outside the box,
// of any length, through points of the torus's plane, of its core cylinder rho = R and of the rest
// of the tube just inside it (down to 10^-15 r from its surface, where the search's rounding
// decides) or deep in it, on tori thin and fat, with t_max unbounded and around the nearest hit.
// A rounding margin of 0.25 instead of 2^15 fails it, and so does dropping the margin at the
// second candidate point only.
TEST(Torus, EntryProofNeverContradictsTheSearch) {
  std::mt19937_64 rng(59);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const Torus& torus :
       {kRing, kHorn, kSpindle, Torus{0.01, 1}, Torus{0.001, 1}, Torus{0.4, 1.1}}) {
    const double big_r = torus.torus_radius, r = torus.tube_radius;
    int proven = 0, rays = 0, clipping_rays = 0, clipping_proven = 0;
    const auto expect_no_contradiction = [&](const Ray& ray, double t_max) {
      if (!crosses_into_the_tube(torus, ray, t_max)) return;
      ++proven;
      LocalHit hit;
      ASSERT_TRUE(intersect_torus(torus, ray, t_max, hit))
          << "torus " << r << " " << big_r << " origin " << ray.origin.x << " " << ray.origin.y
          << " " << ray.origin.z << " direction " << ray.direction.x << " " << ray.direction.y
          << " " << ray.direction.z << " t_max " << t_max;
    };
    for (int i = 0; i < 40000; ++i) {
      // Inside the tube by delta, in the plane at its inner or outer edge, or on the core cylinder
      // below its top or above its bottom.
      const double delta = (i % 4 == 3 ? unit(rng) : std::pow(10.0, -15 * unit(rng))) * r;
      const double angle = 2 * M_PI * unit(rng), c = std::cos(angle), s = std::sin(angle);
      // Every other ray tangent to the surface there (within delta of touching it), in its
      // tangent plane: vertical and along the tube in the plane, horizontal on the cylinder.
      Vec3 inside{big_r * c, big_r * s, (r - delta) * (unit(rng) < 0.5 ? 1 : -1)};
      Vec3 tangents[2] = {{c, s, 0}, {-s, c, 0}};
      const bool clipping = i % 2 == 1 && i % 7 == 1;
      if (i % 2 == 0) {
        const double rho = unit(rng) < 0.5 ? big_r + r - delta : std::fabs(big_r - r) + delta;
        inside = {rho * c, rho * s, 0};
        tangents[0] = {0, 0, 1};
      } else if (clipping) {
        // Or anywhere on the tube, off the plane and the core cylinder: rays clipping the tube's
        // top or sides, whose plane crossing is outside it.
        const double phi = 2 * M_PI * unit(rng), cp = std::cos(phi), sp = std::sin(phi);
        const double rho = big_r + (r - delta) * cp;
        inside = {rho * c, rho * s, (r - delta) * sp};
        tangents[0] = {-sp * c, -sp * s, cp};
      }
      const double distance = std::array{1.5, 5.0, 1e4}[i % 3] * (big_r + r);
      const double turn = 2 * M_PI * unit(rng);
      const Vec3 direction = (i / 2) % 2 == 0
                                 ? testing::random_unit(rng)
                                 : tangents[0] * std::cos(turn) + tangents[1] * std::sin(turn);
      Vec3 w = direction * (0.1 + 10 * unit(rng));
      Ray ray{inside - w * (distance * (1 + unit(rng)) / length(w)), w};
      if (i % 5 == 4) {
        // Into the box through its top or bottom face just off the top or bottom of the tube
        // (down to 10^-12 r), where the box entry is closest to the surface, then down or up
        // through the plane well inside the tube.
        const double side = unit(rng) < 0.5 ? 1 : -1;
        const double off = big_r + r * (2 * unit(rng) - 1) * std::pow(10.0, -12 * unit(rng));
        const Vec3 entry{off * c, off * s, side * r * (1 + 1e-9)};
        const double rho = big_r + r * (unit(rng) - 0.5);
        const double turn_in_plane = angle + (unit(rng) - 0.5) * r / big_r;
        w = (Vec3{rho * std::cos(turn_in_plane), rho * std::sin(turn_in_plane), 0} - entry) *
            (0.1 + 10 * unit(rng));
        ray = {entry - w * (distance * unit(rng) / length(w)), w};
      }
      ++rays;
      const int proven_before = proven;
      expect_no_contradiction(ray, kInfinity);
      if (clipping && i % 5 != 4) {
        ++clipping_rays;
        clipping_proven += proven - proven_before;
      }
      LocalHit hit;
      if (!intersect_torus(torus, ray, kInfinity, hit)) continue;
      for (double t_max : {hit.t, std::nextafter(hit.t, 0.0), std::nextafter(hit.t, kInfinity),
                           hit.t * (1 - 1e-9), hit.t * (1 + 1e-9), hit.t * 1.5})
        expect_no_contradiction(ray, t_max);
    }
    // It settles most of these rays (those whose crossing point is not too close to the surface).
    EXPECT_GT(proven, rays / 4) << r << " " << big_r;
    // And most of those clipping the tube off its plane, through the second candidate point (80
    // to 97 % of them on these tori; 40 to 61 % from the plane alone).
    EXPECT_GT(clipping_proven, clipping_rays * 7 / 10) << r << " " << big_r;
  }
}

// Hits against the exact hit (Newton's method on the torus function along the ray, in quadruple
// precision), on rays from outside: the nearest hit is mostly polished in a bracket of its own
// (quartic_first_root.h), no less accurately than the search polishes it (measured when only the
// nearest hit took that path: 46,685 hits, 516 of them differing from the search's, mean errors
// 0.4368 and 0.4364 ulps of t, 250 nearer the exact hit and 266 farther).
TEST(Torus, HitsAreWithinAnUlpOrSoOfTheExactHit) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> unit(0, 1);
  int hits = 0;
  double total_error = 0, largest_error = 0;  // in ulps of t
  for (const Torus& torus : {kRing, kHorn, kSpindle}) {
    const double big_r = torus.torus_radius, r = torus.tube_radius;
    for (int i = 0; i < 20000; ++i) {
      const Vec3 target{(2 * unit(rng) - 1) * (big_r + r), (2 * unit(rng) - 1) * (big_r + r),
                        (2 * unit(rng) - 1) * r};
      const Vec3 origin = target + testing::random_unit(rng) * ((big_r + r) * (2 + 10 * unit(rng)));
      const Ray ray{origin, (target - origin) * (0.1 + 10 * unit(rng))};
      LocalHit hit;
      if (!intersect_torus(torus, ray, kInfinity, hit)) continue;
      // The torus function cancels some 15 bits from this far away.
      __extension__ using Quad = __float128;
      Quad t = hit.t;
      for (int k = 0; k < 5; ++k) {
        const Quad x = Quad(ray.origin.x) + t * ray.direction.x,
                   y = Quad(ray.origin.y) + t * ray.direction.y,
                   z = Quad(ray.origin.z) + t * ray.direction.z;
        const Quad rho2 = x * x + y * y, q = rho2 + z * z + Quad(big_r) * big_r - Quad(r) * r;
        const Quad dq = 2 * (x * ray.direction.x + y * ray.direction.y + z * ray.direction.z),
                   drho2 = 2 * (x * ray.direction.x + y * ray.direction.y);
        const Quad value = q * q - 4 * Quad(big_r) * big_r * rho2,
                   slope = 2 * q * dq - 4 * Quad(big_r) * big_r * drho2;
        t -= value / slope;
      }
      const double ulp = std::nextafter(hit.t, kInfinity) - hit.t;
      const double error = std::fabs(static_cast<double>((hit.t - t) / ulp));
      ++hits;
      total_error += error;
      largest_error = std::max(largest_error, error);
    }
  }
  std::printf("%d hits, error in ulps of t: mean %.4f, largest %.1f\n", hits, total_error / hits,
              largest_error);
  EXPECT_GT(hits, 20000);
  EXPECT_LT(total_error / hits, 0.45);
}

// For CSG: a ray from outside crosses a closed surface an even number of times (touching roots
// count twice), alternately entering and leaving.
TEST(Torus, CrossingsFromOutsideComeInPairs) {
  std::mt19937_64 rng(23);
  int touching = 0;
  for (const Torus& torus : {kRing, kHorn, kSpindle}) {
    for (int i = 0; i < 20000; ++i) {
      const Vec3 origin = testing::random_unit(rng) * 5;
      // Aimed near the centre; every tenth ray through it exactly, for the pinch and cusps.
      std::uniform_real_distribution<double> aim(-1.5, 1.5);
      const Vec3 target = i % 10 == 0 ? Vec3{} : Vec3{aim(rng), aim(rng), aim(rng) / 3};
      const std::vector<LocalHit> hits =
          torus_crossings(torus, {origin, target - origin}, kInfinity);
      ASSERT_EQ(hits.size() % 2, 0u) << i;
      for (std::size_t k = 1; k < hits.size(); ++k) {
        ASSERT_LE(hits[k - 1].t, hits[k].t);
        touching += hits[k - 1].t == hits[k].t;
      }
    }
  }
  EXPECT_GT(touching, 0);  // the rays through the pinch
}

// Random rays, finite results whatever they hit.
TEST(Torus, NeverNaN) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-3, 3);
  for (const Torus& torus : {kRing, kHorn, kSpindle}) {
    for (int i = 0; i < 20000; ++i) {
      const Ray ray{{unit(rng), unit(rng), unit(rng)}, {unit(rng), unit(rng), unit(rng)}};
      for (const LocalHit& h : torus_crossings(torus, ray, kInfinity)) {
        ASSERT_TRUE(std::isfinite(h.t) && is_finite(h.point) && is_finite(h.normal) &&
                    is_finite(h.point_error));
        ASSERT_GT(length(h.normal), 0);
      }
    }
  }
}

}  // namespace
}  // namespace tessera
