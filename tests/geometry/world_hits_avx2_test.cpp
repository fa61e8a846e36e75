// Four hits back in world space at once with AVX2 (world_hits_avx2.h) must be to_world_hit's,
// bit for bit, for any full or diagonal transforms, with face normals (a cube's) or without, and
// any local hit, special values included.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "common/accel/wide_box_kernel.h"
#include "common/geometry/shapes.h"
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

// The kinds of instance to_world_hit tells apart: full or diagonal transforms, a cube (face
// normals) or another shape.
struct Kind {
  bool diagonal, cube;
};

// Mostly a rotation (none when diagonal), scale and translation with its inverse, as scenes make
// them; else any two matrices (the lanes need not know that one inverts the other), diagonal ones
// with special values on the diagonal.
Instance random_instance(std::mt19937_64& rng, Kind kind) {
  std::uniform_real_distribution<double> unit(-1, 1);
  Instance instance;
  if (kind.cube) instance.geometry = Cube{};
  instance.object = static_cast<std::uint32_t>(rng());
  for (;;) {
    Affine to_world, to_object;
    if (rng() % 4 != 0) {
      const Affine turn = kind.diagonal
                              ? Affine::identity()
                              : *Affine::rotation(unit(rng) * 180, {unit(rng), unit(rng), 1});
      const Affine m = Affine::translation(vector(rng, 10)) * turn *
                       Affine::scaling({1 + unit(rng) * 0.9, 1 + unit(rng) * 0.9, 10 * unit(rng)});
      const std::optional<Affine> inverse = m.inverse();
      if (!inverse) continue;
      to_world = m;
      to_object = *inverse;
    } else if (kind.diagonal) {
      to_world = Affine::translation(vector(rng, 10)) * Affine::scaling(vector(rng, 3));
      to_object = Affine::translation(vector(rng, 10)) * Affine::scaling(vector(rng, 3));
    } else {
      for (Affine* a : {&to_world, &to_object})
        for (auto& row : a->m)
          for (double& entry : row) entry = component(rng, 3);
    }
    place_instance(instance, to_world, to_object);
    if (instance.diagonal.has_value() == kind.diagonal) return instance;
  }
}

LocalHit random_local_hit(std::mt19937_64& rng, Kind kind) {
  LocalHit local;
  local.t = component(rng, 10);
  local.point = vector(rng, 2);
  local.point_error = abs(vector(rng, 1e-15));
  local.normal = vector(rng, 1);
  // A smooth mesh's shading normal now and then; else the normal itself, as every other shape's.
  local.shading_normal = rng() % 8 == 0 ? vector(rng, 1) : local.normal;
  // A cube's part names one of its six faces.
  local.part = static_cast<std::uint32_t>(rng() % (kind.cube ? 6 : 7));
  return local;
}

// Each kind's lanes against to_world_hit; how many lanes were compared, how many fell back to
// normalize_or's {0, 0, 1} and how many had a local point whose diagonal products cannot be the
// full ones (a zero or non-finite component: those lanes take to_world_hit alone).
struct Compared {
  int lanes = 0, unusable_normals = 0, not_same_as_full = 0;
};

Compared compare_lanes(Kind kind, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Compared compared;
  for (int i = 0; i < 4000; ++i) {
    const Instance instance = random_instance(rng, kind);
    for (int j = 0; j < 50; ++j) {
      LocalHit locals[4];
      for (LocalHit& local : locals) local = random_local_hit(rng, kind);
      const unsigned lanes = 1 + static_cast<unsigned>(rng() % 15);
      WorldHit together[4], alone;
      WorldHit* const hits[4] = {&together[0], &together[1], &together[2], &together[3]};
      to_world_hits_avx2(instance, locals, lanes, hits);
      for (int l = 0; l < 4; ++l) {
        if (((lanes >> l) & 1u) == 0) {
          EXPECT_TRUE(same_hit(together[l], WorldHit{})) << i << " lane " << l;
          continue;
        }
        to_world_hit(instance, locals[l], alone);
        if (!same_hit(together[l], alone)) {
          ADD_FAILURE() << i << " lane " << l;
          return compared;
        }
        ++compared.lanes;
        if (alone.normal == Vec3{0, 0, 1} && !(locals[l].normal == Vec3{0, 0, 1}))
          ++compared.unusable_normals;
        if (!same_as_full(locals[l].point)) ++compared.not_same_as_full;
      }
    }
  }
  return compared;
}

TEST(WorldHitsAvx2, LanesAreToWorldHitBitForBit) {
  if (!wide_box_kernel_supported(WideBoxKernel::Avx2)) GTEST_SKIP() << "no AVX2";
  const Compared compared = compare_lanes({.diagonal = false, .cube = false}, 21);
  EXPECT_GT(compared.lanes, 300000);
  // normalize_or's fallback is taken (a normal of zero, subnormal or non-finite length).
  EXPECT_GT(compared.unusable_normals, 10000);
}

TEST(WorldHitsAvx2, DiagonalLanesAreToWorldHitBitForBit) {
  if (!wide_box_kernel_supported(WideBoxKernel::Avx2)) GTEST_SKIP() << "no AVX2";
  const Compared compared = compare_lanes({.diagonal = true, .cube = false}, 22);
  EXPECT_GT(compared.lanes, 300000);
  EXPECT_GT(compared.unusable_normals, 10000);
  EXPECT_GT(compared.not_same_as_full, 10000);
}

TEST(WorldHitsAvx2, FaceNormalLanesAreToWorldHitBitForBit) {
  if (!wide_box_kernel_supported(WideBoxKernel::Avx2)) GTEST_SKIP() << "no AVX2";
  for (const bool diagonal : {false, true}) {
    const Compared compared = compare_lanes({.diagonal = diagonal, .cube = true}, 23);
    EXPECT_GT(compared.lanes, 300000) << diagonal;
    EXPECT_GT(compared.not_same_as_full, 10000) << diagonal;
  }
}

}  // namespace
}  // namespace tessera
