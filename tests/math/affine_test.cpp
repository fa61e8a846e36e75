#include "common/math/affine.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tessera {
namespace {

void expect_near(const Vec3& a, const Vec3& b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

Affine rotation(double degrees, const Vec3& axis) {
  const std::optional<Affine> r = Affine::rotation(degrees, axis);
  EXPECT_TRUE(r.has_value());
  return r.value_or(Affine{});
}

TEST(Affine, TranslationMovesPointsNotVectors) {
  const Affine t = Affine::translation({1, 2, 3});
  EXPECT_EQ(t.apply_point({1, 1, 1}), (Vec3{2, 3, 4}));
  EXPECT_EQ(t.apply_vector({1, 1, 1}), (Vec3{1, 1, 1}));
}

TEST(Affine, ScalingScalesPerAxis) {
  const Affine s = Affine::scaling({2, 3, -4});
  EXPECT_EQ(s.apply_point({1, 1, 1}), (Vec3{2, 3, -4}));
  EXPECT_EQ(s.determinant(), -24);
}

TEST(Affine, ProductAppliesRightOperandFirst) {
  const Affine t = Affine::translation({10, 0, 0});
  const Affine s = Affine::scaling({2, 2, 2});
  // (t * s)(p) = t(s(p)): scale, then translate.
  EXPECT_EQ((t * s).apply_point({1, 1, 1}), (Vec3{12, 2, 2}));
  // (s * t)(p) = s(t(p)): translate, then scale.
  EXPECT_EQ((s * t).apply_point({1, 1, 1}), (Vec3{22, 2, 2}));
  // SDL's CT = CT * M order: rotating after translating (as written) turns the translation.
  const Affine ct = rotation(90, {0, 0, 1}) * Affine::translation({1, 0, 0});
  EXPECT_EQ(ct.apply_point({0, 0, 0}), (Vec3{0, 1, 0}));
}

TEST(Affine, RotationOfKnownVectors) {
  // Multiples of 90 degrees are exact.
  EXPECT_EQ(rotation(90, {0, 0, 1}).apply_vector({1, 0, 0}), (Vec3{0, 1, 0}));
  EXPECT_EQ(rotation(90, {1, 0, 0}).apply_vector({0, 1, 0}), (Vec3{0, 0, 1}));
  EXPECT_EQ(rotation(90, {0, 1, 0}).apply_vector({0, 0, 1}), (Vec3{1, 0, 0}));
  EXPECT_EQ(rotation(-90, {0, 0, 1}).apply_vector({1, 0, 0}), (Vec3{0, -1, 0}));
  EXPECT_EQ(rotation(180, {0, 0, 1}).apply_vector({1, 2, 3}), (Vec3{-1, -2, 3}));
  EXPECT_EQ(rotation(450, {0, 0, 1}).apply_vector({1, 0, 0}), (Vec3{0, 1, 0}));
  // The axis need not be unit length; the sense is right-handed.
  EXPECT_EQ(rotation(90, {0, 0, 7}).apply_vector({1, 0, 0}), (Vec3{0, 1, 0}));
  EXPECT_EQ(rotation(90, {0, 0, -7}).apply_vector({1, 0, 0}), (Vec3{0, -1, 0}));
  // 120 degrees about the diagonal cycles the axes.
  expect_near(rotation(120, {1, 1, 1}).apply_vector({1, 0, 0}), {0, 1, 0}, 1e-15);
  expect_near(rotation(120, {2, 2, 2}).apply_vector({0, 1, 0}), {0, 0, 1}, 1e-15);
  const double h = std::sqrt(0.5);
  expect_near(rotation(45, {0, 0, 1}).apply_vector({1, 0, 0}), {h, h, 0}, 1e-15);
  // Tiny and huge axes work as well as unit ones.
  expect_near(rotation(30, {0, 1e-200, 0}).apply_vector({0, 0, 1}),
              rotation(30, {0, 1, 0}).apply_vector({0, 0, 1}), 1e-16);
  expect_near(rotation(30, {0, 1e200, 0}).apply_vector({0, 0, 1}),
              rotation(30, {0, 1, 0}).apply_vector({0, 0, 1}), 1e-16);
}

TEST(Affine, RotationRejectsDegenerateAxes) {
  EXPECT_FALSE(Affine::rotation(30, {0, 0, 0}).has_value());
  EXPECT_FALSE(Affine::rotation(30, {NAN, 0, 1}).has_value());
  EXPECT_FALSE(Affine::rotation(30, {INFINITY, 0, 1}).has_value());
  EXPECT_FALSE(Affine::rotation(NAN, {0, 0, 1}).has_value());
}

TEST(Affine, RotationIsOrthonormal) {
  const Affine r = rotation(37.5, {1, -2, 0.5});
  EXPECT_NEAR(r.determinant(), 1, 1e-15);
  const Vec3 a = r.apply_vector({1, 0, 0}), b = r.apply_vector({0, 1, 0});
  EXPECT_NEAR(length(a), 1, 1e-15);
  EXPECT_NEAR(dot(a, b), 0, 1e-15);
  // The axis is fixed.
  expect_near(r.apply_vector({1, -2, 0.5}), {1, -2, 0.5}, 1e-15);
}

TEST(Affine, FromColumns) {
  const Affine a = Affine::from_columns({1, 2, 3}, {4, 5, 6}, {7, 8, 10});
  EXPECT_EQ(a.apply_vector({1, 0, 0}), (Vec3{1, 2, 3}));
  EXPECT_EQ(a.apply_vector({0, 1, 0}), (Vec3{4, 5, 6}));
  EXPECT_EQ(a.apply_vector({0, 0, 1}), (Vec3{7, 8, 10}));
  EXPECT_DOUBLE_EQ(a.determinant(), -3);
}

TEST(Affine, InverseTimesTransformIsIdentity) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> unit(-1, 1), exponent(-4, 4);
  for (int i = 0; i < 200; ++i) {
    const Vec3 s{std::pow(10, exponent(rng)), std::pow(10, exponent(rng)),
                 std::pow(10, exponent(rng))};
    const Affine m = Affine::translation({unit(rng) * 1e3, unit(rng) * 1e3, unit(rng) * 1e3}) *
                     rotation(unit(rng) * 180, {unit(rng), unit(rng), 1}) * Affine::scaling(s);
    const std::optional<Affine> inv = m.inverse();
    ASSERT_TRUE(inv.has_value());
    const Vec3 p{unit(rng), unit(rng), unit(rng)};
    // The world point keeps the translation's ~1e3 magnitude: its rounding, seen back in
    // object space, is amplified by 1 / (smallest scale).
    const Vec3 back = inv->apply_point(m.apply_point(p));
    expect_near(back, p, 1e-14 * (1 + 1e3 / std::min({s.x, s.y, s.z})));
    const Affine id = m * *inv;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(id.m[r][c], r == c ? 1 : 0, 1e-12);
  }
}

TEST(Affine, InverseOfKnownTransform) {
  const Affine m = Affine::translation({1, 2, 3}) * Affine::scaling({2, 4, 8});
  const std::optional<Affine> inv = m.inverse();
  ASSERT_TRUE(inv.has_value());
  EXPECT_EQ(inv->apply_point({3, 6, 11}), (Vec3{1, 1, 1}));
  EXPECT_EQ(inv->apply_vector({2, 4, 8}), (Vec3{1, 1, 1}));
}

TEST(Affine, SingularOrNonFiniteHasNoInverse) {
  EXPECT_FALSE(Affine::scaling({1, 0, 1}).inverse().has_value());
  EXPECT_FALSE(Affine::from_columns({1, 2, 3}, {2, 4, 6}, {0, 0, 1}).inverse().has_value());
  // Nearly dependent columns: |det| is tiny relative to the matrix's scale.
  EXPECT_FALSE(Affine::from_columns({1, 0, 0}, {1, 1e-14, 0}, {0, 0, 1}).inverse().has_value());
  Affine bad;
  bad.m[1][3] = NAN;
  EXPECT_FALSE(bad.is_finite());
  EXPECT_FALSE(bad.inverse().has_value());
  bad.m[1][3] = INFINITY;
  EXPECT_FALSE(bad.inverse().has_value());
  // Small or large but regular scales are fine: the test is relative.
  EXPECT_TRUE(Affine::scaling({1e-4, 1e-4, 1e-4}).inverse().has_value());
  EXPECT_TRUE(Affine::scaling({1e-4, 1e4, 1}).inverse().has_value());
  EXPECT_TRUE(Affine::scaling({1e-30, 1e-30, 1e-30}).inverse().has_value());
}

TEST(Affine, NormalsStayPerpendicularUnderNonUniformScale) {
  const Affine m = rotation(30, {1, 1, 0}) * Affine::scaling({1, 5, 0.2});
  const Affine inv = *m.inverse();
  // A surface with normal n contains the tangents t1 and t2.
  const Vec3 n = Vec3{1, 1, 1} / std::sqrt(3.0);
  const Vec3 t1{1, -1, 0}, t2{1, 1, -2};
  const Vec3 world_n = inv.apply_transpose(n);
  EXPECT_NEAR(dot(world_n, m.apply_vector(t1)), 0, 1e-14);
  EXPECT_NEAR(dot(world_n, m.apply_vector(t2)), 0, 1e-14);
  // Transforming the normal like a vector would not be perpendicular.
  EXPECT_GT(std::fabs(dot(m.apply_vector(n), m.apply_vector(t1))), 0.1);
}

TEST(Affine, PointErrorBoundsTheRounding) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int i = 0; i < 1000; ++i) {
    const Affine m = Affine::translation({unit(rng) * 1e8, unit(rng) * 1e8, unit(rng)}) *
                     rotation(unit(rng) * 180, {unit(rng), unit(rng), unit(rng) + 2}) *
                     Affine::scaling({1e-3, 1, 1e3});
    const Vec3 p{unit(rng), unit(rng) * 1e3, unit(rng) * 1e-2};
    const Vec3 computed = m.apply_point(p);
    const Vec3 bound = m.point_error(p, {});
    for (int r = 0; r < 3; ++r) {
      long double exact = m.m[r][3];
      for (int c = 0; c < 3; ++c)
        exact += static_cast<long double>(m.m[r][c]) * static_cast<long double>(p[c]);
      EXPECT_LE(std::fabs(static_cast<double>(computed[r] - exact)), bound[r]);
      // And the bound is not absurdly loose: within ~10 ulps of the magnitude.
      EXPECT_LT(bound[r], 1e-14 * (std::fabs(m.m[r][3]) + 1e3 * 1e3));
    }
  }
  // The carried error goes through the linear part.
  const Affine s = Affine::scaling({2, 3, 4});
  const Vec3 e = s.point_error({0, 0, 0}, {1, 1, 1});
  EXPECT_GE(e.x, 2);
  EXPECT_GE(e.y, 3);
  EXPECT_GE(e.z, 4);
  EXPECT_LT(e.z, 4.000001);
}

}  // namespace
}  // namespace tessera
