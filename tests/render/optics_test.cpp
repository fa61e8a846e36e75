// Reflection and refraction directions (common/render/optics.h) at their edge cases: the
// critical angle and a rounding step either side of it, normal incidence with cosines an ulp
// outside [-1, 1], and eta = 1.
#include "common/render/optics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tessera {
namespace {

// Glass (speed 0.67) into air: sin(critical) = 0.67.
constexpr double kEta = 1 / 0.67;
const Vec3 kNormal{0, 0, 1};  // faces against rays travelling down -z

// The unit ray reaching the surface at `angle` from the normal.
Vec3 incident(double angle) { return {std::sin(angle), 0, -std::cos(angle)}; }

bool is_unit(const Vec3& v) { return std::fabs(length(v) - 1) < 1e-15; }

TEST(Optics, SnellsLawAwayFromTheEdges) {
  const double angle = 0.3;
  const std::optional<Vec3> t = refract(incident(angle), kNormal, 0.5);
  ASSERT_TRUE(t);
  EXPECT_TRUE(is_unit(*t));
  // sin(t) = eta sin(i), continuing downwards in the plane of incidence.
  EXPECT_NEAR(t->x, 0.5 * std::sin(angle), 1e-15);
  EXPECT_EQ(t->y, 0);
  EXPECT_LT(t->z, 0);
  // eta = 1 changes nothing.
  const std::optional<Vec3> same = refract(incident(angle), kNormal, 1);
  ASSERT_TRUE(same);
  EXPECT_NEAR(length(*same - incident(angle)), 0, 1e-15);
}

// Around the critical angle the transmitted ray turns continuously towards the surface and
// then vanishes: a defined unit direction or total internal reflection, never NaN.
TEST(Optics, CriticalAngleAndATinyStepEitherSide) {
  const double critical = std::asin(1 / kEta);
  for (double offset : {-1e-6, -1e-9, -1e-12, 0.0, 1e-12, 1e-9, 1e-6}) {
    SCOPED_TRACE(offset);
    const double angle = critical + offset;
    const std::optional<Vec3> t = refract(incident(angle), kNormal, kEta);
    if (offset > 0) {
      EXPECT_FALSE(t) << "beyond the critical angle the ray reflects";
      continue;
    }
    if (offset == 0 && !t) continue;  // which side of the edge depends on the rounding
    ASSERT_TRUE(t);
    EXPECT_TRUE(is_unit(*t));
    EXPECT_LE(t->z, 0) << "never back into the first medium";
    // Grazing: cos(t) = sqrt(1 - eta^2 sin^2 i) ~ sqrt(2 eta^2 sin(c) cos(c) |offset|).
    const double expected_cos =
        std::sqrt(std::max(0.0, 1 - kEta * kEta * std::sin(angle) * std::sin(angle)));
    EXPECT_NEAR(-t->z, expected_cos, 1e-7);
  }
  // Just below it by an ulp of the sine: still a unit direction along the surface.
  const double sine = std::nextafter(1 / kEta, 0.0);
  const std::optional<Vec3> t = refract({sine, 0, -std::sqrt(1 - sine * sine)}, kNormal, kEta);
  if (t) {
    EXPECT_TRUE(is_unit(*t));
    EXPECT_LE(t->z, 0);
    EXPECT_GT(t->z, -1e-6);
  }
}

// Unit vectors are unit only to rounding: N.r may be -1 - ulp at normal incidence, which
// unclamped puts a negative number under a square root in 1 - (N.r)^2.
TEST(Optics, CosinesARoundingStepOutsideTheirDomain) {
  const Vec3 r{0, 0, -std::nextafter(1.0, 2.0)};  // |r| = 1 + ulp
  for (double eta : {0.5, 1.0, kEta}) {
    const std::optional<Vec3> t = refract(r, kNormal, eta);
    ASSERT_TRUE(t) << eta;
    EXPECT_EQ(*t, (Vec3{0, 0, -1})) << eta;
  }
  const Vec3 tilted = normalize_or({1e-17, 0, -1}, {});
  const std::optional<Vec3> t = refract(tilted, kNormal, kEta);
  ASSERT_TRUE(t);
  EXPECT_TRUE(is_unit(*t));
}

TEST(Optics, ReflectionIsExactForAxisRays) {
  EXPECT_EQ(reflect({0, 0, -1}, kNormal), (Vec3{0, 0, 1}));
  const Vec3 r = reflect(incident(0.7), kNormal);
  EXPECT_TRUE(is_unit(r));
  EXPECT_NEAR(r.z, std::cos(0.7), 1e-15);
}

}  // namespace
}  // namespace tessera
