// Four hits back in world space at once with AVX2 (world_hits_avx2.h) must be to_world_hit's,
// bit for bit, for any full transforms and any local hit, special values included.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "common/accel/wide_box_kernel.h"
#include "common/geometry/world_hits_avx2.h"

namespace tessera {
namespace {

// The hit's doubles the same bits each, or NaN in both (a NaN's sign and payload depend on the
// compiler's operand order), and its integers the same.
bool same_hit(const WorldHit& a, const WorldHit& b) {
  constexpr int kDoubles = 16;  // t and five vectors
  static_assert(offsetof(WorldHit, part) == kDoubles * sizeof(double));
  double x[kDoubles], y[kDoubles];
  std::memcpy(x, &a, sizeof x);
  std::memcpy(y, &b, sizeof y);
  for (int i = 0; i < kDoubles; ++i)
    if (std::bit_cast<std::uint64_t>(x[i]) != std::bit_cast<std::uint64_t>(y[i]) &&
        !(std::isnan(x[i]) && std::isnan(y[i])))
      return false;
  return a.part == b.part && a.object == b.object;
}

// A value: often a special one (zeros of both signs, ones, the edges of normalize_or's usable
// lengths, subnormals, huge values, infinities, NaN), else uniform in [-spread, spread].
double component(std::mt19937_64& rng, double spread) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  static const double kSpecial[] = {
      0.0,     -0.0,   1.0,   -1.0,  1e-300, 1e-150, 1e-160,
      -1e-170, 1e-320, 1e300, 1e155, kInf,   -kInf,  std::numeric_limits<double>::quiet_NaN()};
  constexpr int kCount = sizeof kSpecial / sizeof kSpecial[0];
  const int i = std::uniform_int_distribution<int>(0, 8 * kCount)(rng);
  if (i < kCount) return kSpecial[i];
  return std::uniform_real_distribution<double>(-spread, spread)(rng);
}

Vec3 vector(std::mt19937_64& rng, double spread) {
  return {component(rng, spread), component(rng, spread), component(rng, spread)};
}

// Mostly a rotation, scale and translation with its inverse, as scenes make them; else any two
// matrices (the lanes need not know that one inverts the other).
Instance random_instance(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  Instance instance;
  instance.object = static_cast<std::uint32_t>(rng());
  for (;;) {
    Affine to_world, to_object;
    if (rng() % 4 != 0) {
      const Affine m = Affine::translation(vector(rng, 10)) *
                       *Affine::rotation(unit(rng) * 180, {unit(rng), unit(rng), 1}) *
                       Affine::scaling({1 + unit(rng) * 0.9, 1 + unit(rng) * 0.9, 1});
      const std::optional<Affine> inverse = m.inverse();
      if (!inverse) continue;
      to_world = m;
      to_object = *inverse;
    } else {
      for (Affine* a : {&to_world, &to_object})
        for (auto& row : a->m)
          for (double& entry : row) entry = component(rng, 3);
    }
    place_instance(instance, to_world, to_object);
    if (!instance.diagonal) return instance;
  }
}

LocalHit random_local_hit(std::mt19937_64& rng) {
  LocalHit local;
  local.t = component(rng, 10);
  local.point = vector(rng, 2);
  local.point_error = abs(vector(rng, 1e-15));
  local.normal = vector(rng, 1);
  // A smooth mesh's shading normal now and then; else the normal itself, as every other shape's.
  local.shading_normal = rng() % 8 == 0 ? vector(rng, 1) : local.normal;
  local.part = static_cast<std::uint32_t>(rng() % 7);
  return local;
}

TEST(WorldHitsAvx2, LanesAreToWorldHitBitForBit) {
  if (!wide_box_kernel_supported(WideBoxKernel::Avx2)) GTEST_SKIP() << "no AVX2";
  std::mt19937_64 rng(21);
  int compared = 0, unusable_normals = 0;
  for (int i = 0; i < 4000; ++i) {
    const Instance instance = random_instance(rng);
    for (int j = 0; j < 50; ++j) {
      LocalHit locals[4];
      for (LocalHit& local : locals) local = random_local_hit(rng);
      const unsigned lanes = 1 + static_cast<unsigned>(rng() % 15);
      WorldHit together[4], alone;
      WorldHit* const hits[4] = {&together[0], &together[1], &together[2], &together[3]};
      to_world_hits_avx2(instance, locals, lanes, hits);
      for (int l = 0; l < 4; ++l) {
        if (((lanes >> l) & 1u) == 0) {
          ASSERT_TRUE(same_hit(together[l], WorldHit{})) << i << " lane " << l;
          continue;
        }
        to_world_hit(instance, locals[l], alone);
        ASSERT_TRUE(same_hit(together[l], alone)) << i << " lane " << l;
        ++compared;
        if (alone.normal == Vec3{0, 0, 1} && !(locals[l].normal == Vec3{0, 0, 1}))
          ++unusable_normals;
      }
    }
  }
  EXPECT_GT(compared, 300000);
  // normalize_or's fallback is taken (a normal of zero, subnormal or non-finite length).
  EXPECT_GT(unusable_normals, 10000);
}

}  // namespace
}  // namespace tessera
