#include "common/math/diagonal_affine.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace tessera {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSubnormal = std::numeric_limits<double>::denorm_min() * 3;

bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof(Vec3)) == 0; }

// Values that make products and sums zero, signed, tiny, huge or not finite.
const std::vector<double> kSpecial = {0.0,   -0.0,   1.0, -1.0, kSubnormal, -kSubnormal, 1e-300,
                                      1e300, -1e308, 0.5, kInf, -kInf,      kNaN};

// A diagonal transform from random or special scales and translations. Its off-diagonal zeros
// carry both signs, as those of a computed inverse do.
Affine random_diagonal(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(-4, 4);
  std::uniform_int_distribution<int> pick(0, 7);
  const auto scale = [&]() -> double {
    switch (pick(rng)) {
      case 0:
        return 1e-150;
      case 1:
        return -1e150;
      case 2:
        return kSubnormal;
      default:
        return uniform(rng);
    }
  };
  const auto offset = [&]() -> double {
    switch (pick(rng)) {
      case 0:
        return 0.0;
      case 1:
        return -0.0;
      case 2:
        return 1e200;
      default:
        return uniform(rng);
    }
  };
  Affine a;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a.m[r][c] = r == c ? scale() : (pick(rng) < 4 ? 0.0 : -0.0);
    a.m[r][3] = offset();
  }
  return a;
}

Vec3 random_vector(std::mt19937_64& rng, bool non_negative) {
  std::uniform_real_distribution<double> uniform(-3, 3);
  std::uniform_int_distribution<int> pick(0, 2 * static_cast<int>(kSpecial.size()));
  const auto component = [&] {
    const int i = pick(rng);
    const double v = i < static_cast<int>(kSpecial.size()) ? kSpecial[i] : uniform(rng);
    return non_negative ? std::fabs(v) : v;
  };
  return {component(), component(), component()};
}

TEST(DiagonalAffine, RecognizesDiagonalLinearParts) {
  const std::optional<DiagonalAffine> d =
      DiagonalAffine::of(Affine::translation({1, 2, 3}) * Affine::scaling({2, -3, 4}));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->scale, (Vec3{2, -3, 4}));
  EXPECT_EQ(d->offset, (Vec3{1, 2, 3}));
  EXPECT_TRUE(DiagonalAffine::of(*Affine::rotation(180, {0, 0, 1})).has_value());
  EXPECT_FALSE(DiagonalAffine::of(*Affine::rotation(90, {1, 0, 0})).has_value());
  EXPECT_FALSE(DiagonalAffine::of(*Affine::rotation(-60, {0, 1, 0})).has_value());
  // The inverse of a diagonal transform is diagonal too (the cross products of its columns
  // give exact zeros), so an instance's two transforms classify alike.
  const Affine a = Affine::translation({0, -1, 0}) * Affine::scaling({8, 0.05, 8});
  EXPECT_TRUE(DiagonalAffine::of(*a.inverse()).has_value());
}

TEST(DiagonalAffine, SameAsFullRefusesZerosAndNonFiniteComponents) {
  EXPECT_TRUE(same_as_full({1, -kSubnormal, 1e308}));
  for (const double bad : {0.0, -0.0, kInf, -kInf, kNaN}) {
    EXPECT_FALSE(same_as_full({bad, 1, 1}));
    EXPECT_FALSE(same_as_full({1, bad, 1}));
    EXPECT_FALSE(same_as_full({1, 1, bad}));
  }
}

// Wherever same_as_full accepts a result, it is Affine's bit for bit; and both outcomes occur,
// so that the comparison is not vacuous.
TEST(DiagonalAffine, AcceptedResultsEqualTheFullProducts) {
  std::mt19937_64 rng(18);
  int accepted = 0, refused = 0;
  const auto check = [&](const Vec3& sparse, const Vec3& full) {
    if (!same_as_full(sparse)) {
      ++refused;
      return;
    }
    ++accepted;
    EXPECT_TRUE(same_bits(sparse, full)) << sparse.x << ' ' << sparse.y << ' ' << sparse.z << " vs "
                                         << full.x << ' ' << full.y << ' ' << full.z;
  };
  for (int i = 0; i < 200000; ++i) {
    const Affine a = random_diagonal(rng);
    const DiagonalAffine d = *DiagonalAffine::of(a);
    const Vec3 v = random_vector(rng, false);
    const Vec3 e = random_vector(rng, true);
    check(d.apply_point(v), a.apply_point(v));
    check(d.apply_vector(v), a.apply_vector(v));
    check(d.apply_vector(v), a.apply_transpose(v));
    check(d.point_error(v, e), a.point_error(v, e));
    const Vec3 full_abs{
        std::fabs(a.m[0][0]) * e.x + std::fabs(a.m[0][1]) * e.y + std::fabs(a.m[0][2]) * e.z,
        std::fabs(a.m[1][0]) * e.x + std::fabs(a.m[1][1]) * e.y + std::fabs(a.m[1][2]) * e.z,
        std::fabs(a.m[2][0]) * e.x + std::fabs(a.m[2][1]) * e.y + std::fabs(a.m[2][2]) * e.z};
    check(d.abs_linear(e), full_abs);
  }
  EXPECT_GT(accepted, 100000);
  EXPECT_GT(refused, 100000);
}

// The cases the test above must catch if same_as_full let them through: a zero result whose
// sign the full product decides otherwise, and a NaN the full product makes of 0 * inf.
TEST(DiagonalAffine, RefusedResultsCanDifferFromTheFullProducts) {
  Affine a = Affine::scaling({2, 2, 2});
  a.m[0][1] = -0.0;  // as a computed inverse's zeros can be
  const DiagonalAffine d = *DiagonalAffine::of(a);
  const Vec3 signed_zero = d.apply_vector({-0.0, 1, 1});
  EXPECT_FALSE(same_bits(signed_zero, a.apply_vector({-0.0, 1, 1})));
  EXPECT_FALSE(same_as_full(signed_zero));
  const Vec3 not_finite = d.apply_vector({1, kInf, 1});
  EXPECT_FALSE(same_bits(not_finite, a.apply_vector({1, kInf, 1})));
  EXPECT_FALSE(same_as_full(not_finite));
}

}  // namespace
}  // namespace tessera
