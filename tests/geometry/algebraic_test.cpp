// Ray / algebraic surface intersection (shapes.h): hits known in closed form for each surface
// of algebraic_surfaces.h, the world-space box extent, and finite results at singular points
// and for rays lying in a surface.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/geometry/algebraic_surfaces.h"
#include "common/geometry/instance.h"
#include "common/geometry/shapes.h"
#include "common/math/float_error.h"

namespace tessera {
namespace {

using K = AlgebraicKind;

AlgebraicSurface surface(K kind, double size = 100) { return {kind, {size, size, size}}; }

// A hit and a miss along axis-aligned rays, and the exit from a point inside, per surface.
struct Case {
  K kind;
  Ray hit_ray;
  double hit_t;
  Ray miss_ray;
  Ray inside_ray;
  double inside_t;
};

const double kFourLobesX = std::sqrt(1 + std::sqrt(1.2));
const double kSteinerZ = (0.5 - std::sqrt(0.125)) / 2;

const Case kCases[] = {
    {K::OneSheetHyperboloid,
     {{-5, 0, 0}, {1, 0, 0}},
     4,
     {{-5, 3, 0}, {1, 0, 0}},
     {{0, 0, 0}, {1, 0, 0}},
     1},
    {K::TwoSheetHyperboloid,
     {{0, 0, -5}, {0, 0, 1}},
     4,
     {{-5, 0, 0}, {1, 0, 0}},
     {{0, 0, 3}, {1, 0, 0}},
     std::sqrt(8.0)},
    {K::EllipticCylinder,
     {{-5, 0, 0}, {1, 0, 0}},
     4,
     {{-5, 2, 0}, {1, 0, 0}},
     {{0, 0, 0}, {0, 1, 0}},
     1},
    {K::EllipticCone,
     {{-5, 0, 0.5}, {1, 0, 0}},
     4.5,
     {{-5, 1, 0}, {1, 0, 0}},
     {{0, 0, 1}, {1, 0, 0}},
     1},
    {K::EllipticParaboloid,
     {{0.5, 0, 5}, {0, 0, -1}},
     4.75,
     {{-5, 0, -1}, {1, 0, 0}},
     {{0, 0, 1}, {1, 0, 0}},
     1},
    {K::HyperbolicParaboloid,
     {{0.5, 0.25, 5}, {0, 0, -1}},
     4.8125,
     {{0, -5, 1}, {0, 1, 0}},
     {{0, 0, 1}, {1, 0, 0}},
     1},
    {K::PinchedSurfaceWithHoles,
     {{-5, 0, 0}, {1, 0, 0}},
     4,
     {{0, 3, -5}, {0, 0, 1}},
     {{0, 0, 0}, {0, 1, 0}},
     1},
    {K::PinchedSurfaceWithLobe,
     {{0, 0, 5}, {0, 0, -1}},
     4,
     {{-5, 0, 2}, {1, 0, 0}},
     {{0, 0, 0.5}, {1, 0, 0}},
     std::sqrt(0.125)},
    {K::FourLobes,
     {{-5, 1, 0}, {1, 0, 0}},
     5 - kFourLobesX,
     {{-5, 0, 2}, {1, 0, 0}},
     {{1, 1, 0}, {0, 0, 1}},
     std::sqrt(1.2)},
    {K::SteinersRomanSurface,
     {{0.25, 0.25, -5}, {0, 0, 1}},
     5 + kSteinerZ,
     {{0.5, -0.5, -5}, {0, 0, 1}},
     {{0.25, 0.25, 0.25}, {0, 0, 1}},
     0.42677669529663687 - 0.25},
    {K::ToothCube,
     {{-5, 0, 0}, {1, 0, 0}},
     4,
     {{-5, 1.2, 1.2}, {1, 0, 0}},
     {{0.5, 0, 0}, {1, 0, 0}},
     0.5},
};

TEST(Algebraic, HitMissAndInsidePerSurface) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(static_cast<int>(c.kind));
    const AlgebraicSurface s = surface(c.kind);
    const ImplicitPolynomial f = algebraic_polynomial(c.kind);
    LocalHit hit;
    ASSERT_TRUE(intersect_algebraic(s, c.hit_ray, 0, 50, hit));
    EXPECT_NEAR(hit.t, c.hit_t, 1e-14);
    EXPECT_LT(std::fabs(evaluate(f, hit.point)), 1e-15);
    EXPECT_LT(max_component(hit.point_error), 1e-14);
    // The normal is the gradient: against the ray when it comes from where F > 0.
    const bool from_outside = evaluate(f, c.hit_ray.origin) > 0;
    EXPECT_EQ(dot(hit.normal, c.hit_ray.direction) < 0, from_outside);
    EXPECT_EQ(hit.shading_normal, hit.normal);
    EXPECT_FALSE(intersect_algebraic(s, c.miss_ray, 0, 50, hit));
    ASSERT_TRUE(intersect_algebraic(s, c.inside_ray, 0, 50, hit));
    EXPECT_NEAR(hit.t, c.inside_t, 1e-14);
    EXPECT_FALSE(intersect_algebraic(s, c.hit_ray, 0, c.hit_t * (1 - 1e-9), hit));  // t_max
  }
}

TEST(Algebraic, CrossingsAreSortedAndCountTouchingRootsTwice) {
  // The ding-dong surface along its axis: z^2 (z - 1), the lobe's top then the pinch.
  std::vector<LocalHit> hits =
      algebraic_crossings(surface(K::PinchedSurfaceWithLobe), {{0, 0, 5}, {0, 0, -1}}, 0, 50);
  ASSERT_EQ(hits.size(), 3u);
  EXPECT_NEAR(hits[0].t, 4, 1e-15);
  EXPECT_NEAR(hits[1].t, 5, 1e-7);
  EXPECT_EQ(hits[1].t, hits[2].t);
  EXPECT_TRUE(is_finite(hits[1].normal));
  // The tooth along x: x^2 (x^2 - 1), the isolated point at the centre touching.
  hits = algebraic_crossings(surface(K::ToothCube), {{-5, 0, 0}, {1, 0, 0}}, 0, 50);
  ASSERT_EQ(hits.size(), 4u);
  EXPECT_NEAR(hits[0].t, 4, 1e-15);
  EXPECT_NEAR(hits[1].t, 5, 1e-7);
  EXPECT_NEAR(hits[3].t, 6, 1e-15);
  // A one-sheet hyperboloid, through both walls.
  hits = algebraic_crossings(surface(K::OneSheetHyperboloid), {{-5, 0, 0}, {1, 0, 0}}, 0, 50);
  ASSERT_EQ(hits.size(), 2u);
  EXPECT_NEAR(hits[1].t, 6, 1e-15);
}

// The closed surfaces, inside their box: rays from outside cross them an even number of times.
TEST(Algebraic, CrossingsOfClosedSurfacesComeInPairs) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (K kind : {K::FourLobes, K::ToothCube, K::SteinersRomanSurface}) {
    SCOPED_TRACE(static_cast<int>(kind));
    for (int i = 0; i < 20000; ++i) {
      const Vec3 origin = normalize_or({unit(rng), unit(rng), unit(rng)}, {1, 0, 0}) * 6;
      const Vec3 target{unit(rng), unit(rng), unit(rng)};
      const std::vector<LocalHit> hits =
          algebraic_crossings(surface(kind, 8), {origin, target - origin}, 0, 10);
      ASSERT_EQ(hits.size() % 2, 0u) << i;
    }
  }
}

TEST(Algebraic, FarAwayRaysKeepTheirDigits) {
  LocalHit hit;
  for (double distance : {1e2, 1e4, 1e6}) {
    SCOPED_TRACE(distance);
    ASSERT_TRUE(intersect_algebraic(surface(K::EllipticParaboloid, 4 * distance),
                                    {{0.5, 0, distance}, {0, 0, -1}}, 0, 2 * distance, hit));
    EXPECT_NEAR(hit.point.z, 0.25, 1e-15);
    EXPECT_NEAR(hit.t, distance - 0.25, distance * 2e-16);
    ASSERT_TRUE(intersect_algebraic(surface(K::ToothCube, 4 * distance),
                                    {{-distance, 0.5, 0}, {1, 0, 0}}, 0, 2 * distance, hit));
    // x^4 - x^2 = y^2 - y^4 = 3/16.
    EXPECT_NEAR(hit.point.x, -std::sqrt((1 + std::sqrt(1.75)) / 2), 1e-15);
  }
}

// The box extent is a world-space box around the translated origin: the CT's scale and
// rotation do not apply to it.
TEST(Algebraic, ExtentClipsInWorldSpace) {
  IntersectionCounters counters;
  WorldHit hit;
  const AlgebraicSurface cylinder{K::EllipticCylinder, {4, 4, 4}};
  // Standing along y at x = 10.
  const Affine stood = Affine::translation({10, 0, 0}) * *Affine::rotation(90, {1, 0, 0});
  std::optional<Instance> inst = make_instance(cylinder, stood, nullptr);
  ASSERT_TRUE(inst);
  EXPECT_EQ(inst->world_bounds.lo, (Vec3{8, -2, -2}));
  EXPECT_EQ(inst->world_bounds.hi, (Vec3{12, 2, 2}));
  ASSERT_TRUE(intersect_instance(*inst, {{0, 1.9, 0}, {1, 0, 0}}, kInfinity, hit, counters));
  EXPECT_NEAR(hit.t, 9, 1e-14);
  EXPECT_NEAR(hit.normal.x, -1, 1e-15);
  EXPECT_FALSE(intersect_instance(*inst, {{0, 2.1, 0}, {1, 0, 0}}, kInfinity, hit, counters));
  // Scaled by 3 the cylinder's walls (x = 7 and 13) leave the unscaled box: nothing to hit.
  inst = make_instance(cylinder, stood * Affine::scaling({3, 3, 3}), nullptr);
  ASSERT_TRUE(inst);
  EXPECT_EQ(inst->world_bounds.hi, (Vec3{12, 2, 2}));
  EXPECT_FALSE(intersect_instance(*inst, {{0, 0, 0}, {1, 0, 0}}, kInfinity, hit, counters));
  // Scaled by 1.5, the walls at 8.5 and 11.5 are inside it.
  inst = make_instance(cylinder, stood * Affine::scaling({1.5, 1.5, 1.5}), nullptr);
  ASSERT_TRUE(intersect_instance(*inst, {{0, 0, 0}, {1, 0, 0}}, kInfinity, hit, counters));
  EXPECT_NEAR(hit.t, 8.5, 1e-14);
  // From inside the box, the box's faces are not surfaces.
  EXPECT_FALSE(intersect_instance(*inst, {{10, 0, 0}, {0, 1, 0}}, kInfinity, hit, counters));
}

TEST(Algebraic, TransformedSurfacesForEveryKind) {
  // A hit found through an instance equals the object-space hit of the transformed ray.
  const Affine to_world = Affine::translation({3, -2, 100}) *
                          *Affine::rotation(30, normalize_or(Vec3{1, 2, 3}, {})) *
                          Affine::scaling({0.5, 2, 1});
  for (const Case& c : kCases) {
    SCOPED_TRACE(static_cast<int>(c.kind));
    const std::optional<Instance> inst = make_instance(surface(c.kind), to_world, nullptr);
    ASSERT_TRUE(inst);
    const Ray world{to_world.apply_point(c.hit_ray.origin),
                    to_world.apply_vector(c.hit_ray.direction)};
    WorldHit hit;
    IntersectionCounters counters;
    ASSERT_TRUE(intersect_instance(*inst, world, kInfinity, hit, counters));
    EXPECT_NEAR(hit.t, c.hit_t, 1e-12);
    EXPECT_LT(
        length(hit.point - to_world.apply_point(c.hit_ray.origin + c.hit_ray.direction * c.hit_t)),
        1e-12);
    const bool from_outside = evaluate(algebraic_polynomial(c.kind), c.hit_ray.origin) > 0;
    EXPECT_EQ(dot(hit.normal, world.direction) < 0, from_outside);
  }
}

// Steiner's surface holds its three axes, where the gradient vanishes too: rays along them
// (restricting the polynomial to zero) and rays crossing them give finite results.
TEST(Algebraic, RaysInSteinersSurfaceAreNeverNaN) {
  const AlgebraicSurface steiner = surface(K::SteinersRomanSurface, 2);
  LocalHit hit;
  for (const Ray& ray : {Ray{{-5, 0, 0}, {1, 0, 0}}, Ray{{0, -5, 0}, {0, 1, 0}},
                         Ray{{0, 0, 5}, {0, 0, -1}}, Ray{{0, 0, 0}, {1, 0, 0}}}) {
    EXPECT_FALSE(intersect_algebraic(steiner, ray, 0, 20, hit));
    EXPECT_TRUE(algebraic_crossings(steiner, ray, 0, 20).empty());
  }
  // Lines in the coordinate planes cross the other axes at touching roots: F = x^2 y^2 at z = 0.
  ASSERT_TRUE(intersect_algebraic(steiner, {{-5, 0.3, 0}, {1, 0, 0}}, 0, 20, hit));
  EXPECT_NEAR(hit.t, 5, 1e-7);
  EXPECT_TRUE(is_finite(hit.point) && is_finite(hit.normal) && is_finite(hit.point_error));
  EXPECT_GT(length(hit.normal), 0);
  // Rotated so the axes are no longer exact in floating point: roots may come from rounding,
  // but whatever is found is finite.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int i = 0; i < 200; ++i) {
    const Affine to_world = *Affine::rotation(
        360 * unit(rng), normalize_or(Vec3{unit(rng), unit(rng), unit(rng)}, {1, 0, 0}));
    const std::optional<Instance> inst = make_instance(steiner, to_world, nullptr);
    ASSERT_TRUE(inst);
    for (const Vec3& axis : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}) {
      const Vec3 d = to_world.apply_vector(axis);
      WorldHit world_hit;
      IntersectionCounters counters;
      if (intersect_instance(*inst, {d * -3 + d * (0.1 * unit(rng)), d}, kInfinity, world_hit,
                             counters)) {
        ASSERT_TRUE(is_finite(world_hit.point) && is_finite(world_hit.normal) &&
                    is_finite(world_hit.point_error));
      }
    }
  }
}

TEST(Algebraic, RandomRaysAreNeverNaN) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-2, 2);
  for (const Case& c : kCases) {
    const AlgebraicSurface s = surface(c.kind, 4);
    for (int i = 0; i < 5000; ++i) {
      const Ray ray{{unit(rng), unit(rng), unit(rng)}, {unit(rng), unit(rng), unit(rng)}};
      for (const LocalHit& h : algebraic_crossings(s, ray, 0, 10)) {
        ASSERT_TRUE(std::isfinite(h.t) && is_finite(h.point) && is_finite(h.normal) &&
                    is_finite(h.point_error));
        ASSERT_GT(length(h.normal), 0);
      }
    }
  }
}

// A ray leaving a hit from offset_ray_origin() does not find the same point again.
TEST(Algebraic, SpawnedRaysDoNotFindTheirOwnHit) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(-1, 1);
  int tested = 0;
  for (const Case& c : kCases) {
    SCOPED_TRACE(static_cast<int>(c.kind));
    const Affine to_world = Affine::translation({unit(rng) * 1e3, 0, 5}) *
                            *Affine::rotation(77, normalize_or(Vec3{1, -1, 2}, {})) *
                            Affine::scaling({0.3, 1, 2});
    const std::optional<Instance> inst = make_instance(surface(c.kind, 6), to_world, nullptr);
    ASSERT_TRUE(inst);
    const Vec3 centre = to_world.apply_point({0, 0, 0});
    IntersectionCounters counters;
    for (int r = 0; r < 300; ++r) {
      const Vec3 target = centre + Vec3{unit(rng), unit(rng), unit(rng)} * 2;
      const Vec3 origin = target + normalize_or({unit(rng), unit(rng), unit(rng)}, {1, 0, 0}) * 20;
      WorldHit hit;
      if (!intersect_instance(*inst, {origin, target - origin}, kInfinity, hit, counters)) continue;
      for (int s = 0; s < 4; ++s) {
        const Vec3 w{unit(rng), unit(rng), unit(rng)};
        if (dot(w, hit.normal) == 0) continue;
        const Vec3 o = offset_ray_origin(hit.point, hit.point_error, hit.normal, w);
        WorldHit again;
        ++tested;
        if (!intersect_instance(*inst, {o, w}, kInfinity, again, counters)) continue;
        EXPECT_GT(length(again.point - hit.point), 16 * length(hit.point_error));
      }
    }
  }
  EXPECT_GT(tested, 2000);
}

}  // namespace
}  // namespace tessera
