// The eight-box float test of the mesh BVH traversal: conservative against the double slab test
// intersect_bounds (it never rejects a box that one accepts, and its entry distances never let
// a later, smaller t_max skip one), on random and adversarial rays and boxes (far from the
// origin, tiny boxes, axis-parallel rays, zero direction components, grazing rays, origins on
// box planes); and every kernel this build and CPU can select (SSE2, AVX2, AVX-512VL)
// bit-identical to the scalar one, so that images do not depend on which one runs.
#include "common/accel/float_child_boxes.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "common/accel/wide_box_kernel.h"
#include "tests/accel/edge_case_rays.h"

namespace tessera {
namespace {

struct Counts {
  int double_hits = 0;  // boxes the double test accepts
  int float_hits = 0;   // boxes the float test accepts
};

std::string describe(const Vec3& v) {
  std::ostringstream out;
  out.precision(17);
  out << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return out.str();
}

#if defined(__SSE2__)
// The AVX2 functions as the AVX-512VL kernel compiles them (wide_box_kernel.h): inlined into a
// function for its target, where the compiler may pick other instructions and registers.
[[gnu::target(TESSERA_AVX512VL_TARGET), gnu::flatten]] unsigned
intersect_float_child_boxes_avx512vl(const FloatChildBoxes& boxes, const FloatBoxRay& ray,
                                     const FloatBoxLimit& far_limit, float entry[kWideChildren]) {
  return intersect_float_child_boxes_avx2(boxes, ray, far_limit, entry);
}
[[gnu::target(TESSERA_AVX512VL_TARGET), gnu::flatten]] void set_float_box_ray_avx512vl(
    FloatBoxRay& r, const Ray& ray) {
  set_float_box_ray_avx2(r, ray);
}
#endif

// The scalar kernel's result, after checking that every SIMD kernel this build and CPU can
// select gives the same hits and the same entry distances, bit for bit.
unsigned intersect_with_every_kernel(const FloatChildBoxes& wide, const FloatBoxRay& box_ray,
                                     float far_limit, float entry[kWideChildren]) {
  const FloatBoxLimit limit(far_limit);
  const unsigned hits = intersect_float_child_boxes_scalar(wide, box_ray, limit, entry);
#if defined(__SSE2__)
  const auto expect_same = [&](const char* kernel, unsigned simd_hits,
                               const float simd_entry[kWideChildren]) {
    EXPECT_EQ(simd_hits, hits) << kernel;
    for (int c = 0; c < kWideChildren; ++c)
      EXPECT_EQ(std::bit_cast<std::uint32_t>(simd_entry[c]), std::bit_cast<std::uint32_t>(entry[c]))
          << kernel << " child " << c;
  };
  float simd_entry[kWideChildren];
  expect_same("sse2", intersect_float_child_boxes_sse2(wide, box_ray, limit, simd_entry),
              simd_entry);
  if (wide_box_kernel_supported(WideBoxKernel::Avx2))
    expect_same("avx2", intersect_float_child_boxes_avx2(wide, box_ray, limit, simd_entry),
                simd_entry);
  if (wide_box_kernel_supported(WideBoxKernel::Avx512Vl))
    expect_same("avx512vl", intersect_float_child_boxes_avx512vl(wide, box_ray, limit, simd_entry),
                simd_entry);
#endif
  return hits;
}

TEST(FloatChildBoxes, ThisMachineRunsTheAvx2Code) {
  // Where the CPU has AVX2, traversals use its code (alone, or compiled for AVX-512VL where the
  // CPU has that too), and the comparisons above cover it.
  if (!wide_box_kernel_supported(WideBoxKernel::Avx2)) GTEST_SKIP() << "no AVX2 on this CPU";
  EXPECT_EQ(wide_box_kernel(), wide_box_kernel_supported(WideBoxKernel::Avx512Vl)
                                   ? WideBoxKernel::Avx512Vl
                                   : WideBoxKernel::Avx2);
}

// Tests the eight boxes (fewer leave empty slots) against `ray` both ways.
void expect_conservative(const std::vector<Bounds3>& boxes, const Ray& ray, double t_max,
                         Counts& counts) {
  FloatChildBoxes wide = empty_float_child_boxes();
  for (int c = 0; c < static_cast<int>(boxes.size()); ++c) set_float_child_box(wide, c, boxes[c]);
  const FloatBoxRay box_ray(ray);
  const float far_limit = float_far_limit(t_max);
  float entry[kWideChildren];
  const unsigned hits = intersect_with_every_kernel(wide, box_ray, far_limit, entry);
  ASSERT_FALSE(::testing::Test::HasFailure());
  const Vec3 inv_dir{1 / ray.direction.x, 1 / ray.direction.y, 1 / ray.direction.z};
  for (int c = 0; c < kWideChildren; ++c) {
    const bool is_hit = ((hits >> c) & 1u) != 0;
    counts.float_hits += is_hit;
    if (c >= static_cast<int>(boxes.size())) {
      ASSERT_FALSE(is_hit) << "empty slot " << c;
      continue;
    }
    double double_entry = 0;
    if (!intersect_bounds(boxes[c], ray.origin, inv_dir, t_max, double_entry)) continue;
    ++counts.double_hits;
    ASSERT_TRUE(is_hit) << "child " << c << " box " << describe(boxes[c].lo) << " "
                        << describe(boxes[c].hi) << " ray " << describe(ray.origin) << " "
                        << describe(ray.direction) << " t_max " << t_max;
    // After a hit at the double entry, the double test still accepts the box: so must the
    // pop of the traversal, which compares the float entry with the float limit.
    ASSERT_LE(entry[c], float_far_limit(double_entry))
        << "child " << c << " double entry " << double_entry;
  }
}

Bounds3 box_around(const Vec3& center, const Vec3& half) { return {center - half, center + half}; }

TEST(FloatChildBoxes, ConservativeOnRandomRays) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Counts counts;
  for (int i = 0; i < 50000; ++i) {
    std::vector<Bounds3> boxes;
    const int n = 1 + i % kWideChildren;
    for (int c = 0; c < n; ++c) {
      Bounds3 b;
      b.extend(Vec3{u(rng), u(rng), u(rng)});
      b.extend(Vec3{u(rng), u(rng), u(rng)});
      boxes.push_back(b);
    }
    const Vec3 origin{3 * u(rng), 3 * u(rng), 3 * u(rng)};
    const Vec3 target{u(rng), u(rng), u(rng)};
    const Ray ray{origin, (target - origin) * (1 + u(rng))};
    const double t_max = u(rng) > 0 ? kInfinity : 0.6 + 0.5 * u(rng);
    expect_conservative(boxes, ray, t_max, counts);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(counts.double_hits, 10000);  // the cases are not all misses
  // Conservative, but not by much: the float test prunes nearly as well.
  EXPECT_LT(counts.float_hits, counts.double_hits + counts.double_hits / 1000)
      << counts.float_hits << " float hits, " << counts.double_hits << " double hits";
}

// Rays aimed exactly at corners, edges and faces of boxes (grazing), at every scale and far from
// the origin, along the axes and with zero, negative zero and tiny direction components.
TEST(FloatChildBoxes, ConservativeOnAdversarialRays) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-1, 1);
  const double offsets[] = {0, 1e5, -1e5, 3e7};
  const double sizes[] = {1e-6, 1e-3, 1, 1e3};
  Counts counts;
  for (int i = 0; i < 200000; ++i) {
    const double offset = offsets[i % 4];
    const double size = sizes[(i / 4) % 4];
    const Vec3 center = Vec3{offset, -offset, offset} + Vec3{u(rng), u(rng), u(rng)} * size;
    std::vector<Bounds3> boxes;
    for (int c = 0; c < kWideChildren; ++c)
      boxes.push_back(box_around(center + Vec3{u(rng), u(rng), u(rng)} * size,
                                 Vec3{u(rng) + 1, u(rng) + 1, u(rng) + 1} * (size / 2)));
    if (i % 7 == 0) boxes[1].lo.y = boxes[1].hi.y;  // flat
    const Bounds3& target_box = boxes[static_cast<std::size_t>(i) % boxes.size()];
    // A corner, an edge point or a face point of the target box, or a point inside it.
    Vec3 target;
    for (int a = 0; a < 3; ++a) {
      const int pick = static_cast<int>(rng() % 4);
      target[a] = pick == 0   ? target_box.lo[a]
                  : pick == 1 ? target_box.hi[a]
                              : target_box.lo[a] +
                                    (target_box.hi[a] - target_box.lo[a]) * (0.5 + 0.5 * u(rng));
    }
    Vec3 origin = target + Vec3{u(rng), u(rng), u(rng)} * (size * 4);
    Vec3 direction = target - origin;
    for (int a = 0; a < 3; ++a) {
      const auto kind = rng() % 10;
      if (kind == 0) {  // axis-parallel: the origin in the target's plane
        origin[a] = target[a];
        direction[a] = (rng() % 2) ? 0.0 : -0.0;
      } else if (kind == 1) {
        direction[a] *= 1e-30;
      }
    }
    if (i % 3 == 0) direction = direction * (1 / length(direction));
    if (i % 11 == 0) origin = target;                   // on the box's surface or inside it
    const double t_max = i % 5 == 0 ? 1.0 : kInfinity;  // the target at t = 1, or almost
    expect_conservative(boxes, {origin, direction}, t_max, counts);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(counts.double_hits, 200000);
}

TEST(FloatChildBoxes, EdgeCases) {
  const Bounds3 unit{{0, 0, 0}, {1, 1, 1}};
  const Bounds3 flat{{0, 0, 0.5}, {1, 1, 0.5}};
  const Bounds3 point{{0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}};
  const Bounds3 infinite{{-kInfinity, -kInfinity, -kInfinity}, {kInfinity, kInfinity, kInfinity}};
  const Bounds3 huge{{-1e300, -1e300, -1e300}, {1e300, 1e300, 1e300}};
  const Bounds3 tiny{{1e-40, 1e-40, 1e-40}, {2e-40, 2e-40, 2e-40}};
  std::vector<Ray> rays = edge_case_rays();
  rays.push_back({{0, 0, 0}, {1, 1, 1}});  // through the tiny box near the origin
  rays.push_back({{1e-40, 1e-40, 1e-40}, {1e-30, 1e-30, 1e-30}});
  rays.push_back({{-1e5, 0.5, 0.5}, {1, 0, 0}});
  const std::vector<Bounds3> all = {unit, flat, point, infinite, huge, tiny};
  Counts counts;
  for (const Ray& ray : rays)
    for (std::size_t first = 0; first < all.size(); ++first)
      for (std::size_t n = 0; n <= kWideChildren; ++n) {
        std::vector<Bounds3> boxes;
        for (std::size_t k = 0; k < n; ++k) boxes.push_back(all[(first + k) % all.size()]);
        for (const double t_max : {kInfinity, 0.25, 0.0, 1e-45}) {
          expect_conservative(boxes, ray, t_max, counts);
          if (HasFatalFailure()) return;
        }
      }
  EXPECT_GT(counts.double_hits, 100);
}

// Slab distances below FLT_MIN, where float rounds to a fixed grid (2^-149) and relative error
// bounds fail: tiny boxes near the origin, reached at t of 1e-42 (kFloatTinyMargin's domain).
TEST(FloatChildBoxes, ConservativeBelowFloatsNormalRange) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.1, 10);
  const double grid = std::ldexp(1.0, -149);
  Counts counts;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 direction{u(rng), u(rng), u(rng)};
    const double t = static_cast<double>(1 + rng() % 1000) * grid;
    std::vector<Bounds3> boxes;
    for (int c = 0; c < kWideChildren; ++c) {
      // A point near the ray (on the grid), or a box around it a grid step wide.
      Bounds3 b;
      for (int a = 0; a < 3; ++a) {
        const double p = std::round(t * direction[a] / grid) * grid;
        b.lo[a] = p - static_cast<double>(rng() % 2) * grid;
        b.hi[a] = p + static_cast<double>(rng() % 2) * grid;
      }
      boxes.push_back(b);
    }
    expect_conservative(boxes, {{0, 0, 0}, direction}, kInfinity, counts);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(counts.double_hits, 1000);
}

// A tie on float's subnormal grid (g = 2^-149), which the random cases above do not meet: from
// the origin along (6, 2, 1), the box's x slab starts at 3g / 6 = g / 2 and its y slab ends at
// g / 2, so the double test accepts it at t = g / 2. In float, 3g * fl(1 / 6) lies just above
// g / 2 and rounds up to g, while g * 0.5 is exactly g / 2, which rounds to even, 0: the far end
// comes a grid step before the entry, and only kFloatTinyMargin keeps the box.
TEST(FloatChildBoxes, TheTinyMarginCoversASubnormalTie) {
  const double g = std::ldexp(1.0, -149);
  Counts counts;
  expect_conservative({{{3 * g, -1, -1}, {1, g, 1}}}, {{0, 0, 0}, {6, 2, 1}}, kInfinity, counts);
  if (HasFatalFailure()) return;
  EXPECT_EQ(counts.double_hits, 1);
}

// Slots left empty are never entered, even by a ray of NaNs, which accepts every slab.
TEST(FloatChildBoxes, EmptySlotsAreNeverHit) {
  FloatChildBoxes wide = empty_float_child_boxes();
  set_float_child_box(wide, 0, {{0, 0, 0}, {1, 1, 1}});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Ray& ray : {Ray{{nan, nan, nan}, {1, 1, 1}}, Ray{{0, 0, 0}, {nan, nan, nan}},
                         Ray{{kInfinity, 0, 0}, {kInfinity, 0, 0}}}) {
    float entry[kWideChildren];
    EXPECT_EQ(intersect_with_every_kernel(wide, FloatBoxRay(ray), INFINITY, entry) & ~1u, 0u);
  }
}

TEST(FloatChildBoxes, RoundingToFloatIsOutward) {
  for (const double x : {0.1, -0.1, 1e5 + 1e-3, -3e7 - 0.5, 1e-45, 1e300, -1e300, 0.5}) {
    EXPECT_LE(round_down_to_float(x), x);
    EXPECT_GE(round_up_to_float(x), x);
    EXPECT_LE(round_up_to_float(x), std::nextafter(round_down_to_float(x), INFINITY));
  }
  for (const float f : {0.0f, -0.0f, 1.0f, -1.0f, FLT_TRUE_MIN, -FLT_TRUE_MIN, FLT_MAX, -FLT_MAX,
                        -INFINITY, 3e-39f}) {
    EXPECT_EQ(float_step_up(f), std::nextafter(f, INFINITY)) << f;
    EXPECT_EQ(float_step_down(-f), std::nextafter(-f, -INFINITY)) << f;
  }
  EXPECT_EQ(round_down_to_float(0.5), 0.5f);
  EXPECT_EQ(round_up_to_float(0.5), 0.5f);
}

// The ray's constants made three axes at once (the SSE2 and AVX2 kernels') are the reference's, bit
// for bit: random rays near and far from the origin, origins exactly on floats, between them,
// beyond float's range and subnormal in float, signed zeros, infinities and NaNs in both origin and
// direction.
TEST(FloatChildBoxes, RayConstantsMatchTheAxisByAxisReference) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> specials = {
      0.0,  -0.0,  0.1,   -0.1,      0.5,        1e-45, -1e-45,     3e-39,      1e-300,  -1e-300,
      1e39, -1e39, 1e300, kInfinity, -kInfinity, nan,   1e5 + 1e-3, -3e7 - 0.5, FLT_MAX, -FLT_MAX};
  std::vector<Ray> rays = edge_case_rays();
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::size_t> pick(0, specials.size() - 1);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 20000; ++i) {
    const double scale = std::pow(10.0, static_cast<double>(i % 9) * 5 - 20);
    const auto value = [&](int kind) { return kind == 0 ? specials[pick(rng)] : u(rng) * scale; };
    Vec3 origin, direction;
    for (int a = 0; a < 3; ++a) {
      origin[a] = value(i % 4 == 0 ? static_cast<int>(rng() % 2) : 1);
      direction[a] = i % 5 == 0 ? value(static_cast<int>(rng() % 2)) : direction_component(rng, u);
    }
    rays.push_back({origin, direction});
  }
  const auto bits = [](const float(&v)[3][kWideChildren], int a, int c) {
    return std::bit_cast<std::uint32_t>(v[a][c]);
  };
  const auto expect_same = [&](const char* kernel, const FloatBoxRay& made,
                               const FloatBoxRay& reference, const Ray& ray) {
    for (int a = 0; a < 3; ++a) {
      ASSERT_EQ(made.near_side[a], reference.near_side[a])
          << kernel << " " << describe(ray.origin) << " " << describe(ray.direction) << " axis "
          << a;
      for (int c = 0; c < kWideChildren; ++c) {
        ASSERT_EQ(bits(made.inv_dir, a, c), bits(reference.inv_dir, a, c))
            << kernel << " " << describe(ray.origin) << " " << describe(ray.direction) << " axis "
            << a;
        ASSERT_EQ(bits(made.origin_near, a, c), bits(reference.origin_near, a, c))
            << kernel << " " << describe(ray.origin) << " " << describe(ray.direction) << " axis "
            << a;
        ASSERT_EQ(bits(made.origin_far, a, c), bits(reference.origin_far, a, c))
            << kernel << " " << describe(ray.origin) << " " << describe(ray.direction) << " axis "
            << a;
      }
    }
  };
  for (const Ray& ray : rays) {
    const FloatBoxRay reference(ray);
#if defined(__SSE2__)
    FloatBoxRay made;
    set_float_box_ray_sse2(made, ray);
    expect_same("sse2", made, reference, ray);
    if (wide_box_kernel_supported(WideBoxKernel::Avx2)) {
      FloatBoxRay made_avx2;
      set_float_box_ray_avx2(made_avx2, ray);
      expect_same("avx2", made_avx2, reference, ray);
    }
    if (wide_box_kernel_supported(WideBoxKernel::Avx512Vl)) {
      FloatBoxRay made_avx512vl;
      set_float_box_ray_avx512vl(made_avx512vl, ray);
      expect_same("avx512vl", made_avx512vl, reference, ray);
    }
#endif
  }
}
}  // namespace
}  // namespace tessera
