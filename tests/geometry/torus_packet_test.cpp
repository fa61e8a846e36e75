// Four rays' torus frames formed together with AVX2 (torus_packet.h) must be torus_frame's, bit
// for bit (their first-root brackets included), and the instance's packet test
// (intersect_instance_packet) intersect_instance's, with every box kernel (the scalar path stays
// for machines without AVX2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "common/accel/wide_box_kernel.h"
#include "common/geometry/instance.h"
#include "common/geometry/torus_packet.h"
#include "tests/geometry/packet_checks.h"

namespace tessera {
namespace {

using test::component;
using test::same_value;

bool same_frame(const TorusFrame& a, const TorusFrame& b) {
  const TorusLine &p = a.line, &q = b.line;
  bool same = same_value(p.u, q.u) && same_value(p.f, q.f) && same_value(p.len, q.len) &&
              same_value(p.t0, q.t0) && same_value(p.s_lo, q.s_lo) && same_value(p.s_hi, q.s_hi) &&
              same_value(p.P, q.P) && same_value(p.Q, q.Q) && a.quartic.degree == b.quartic.degree;
  for (int i = 0; i <= kMaxPolynomialDegree; ++i)
    same = same && same_value(a.quartic.c[i], b.quartic.c[i]);
  return same && a.first_root_end.has_value() == b.first_root_end.has_value() &&
         (!a.first_root_end || same_value(*a.first_root_end, *b.first_root_end));
}

// Ring, horn, spindle, a thin tube and a degenerate one (no tube).
const Torus kTori[] = {{0.4, 1.1}, {0.75, 0.75}, {0.9, 0.5}, {0.01, 1}, {0, 1}};

TEST(TorusPacket, FramesAreTorusFramesBitForBit) {
  if (!wide_box_kernel_supported(WideBoxKernel::Avx2)) GTEST_SKIP() << "no AVX2";
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  int formed = 0, compared = 0, bracketed = 0, halved = 0;
  for (const Torus& torus : kTori) {
    for (int i = 0; i < 40000; ++i) {
      // Mostly an eye outside the box with rays towards the torus, as a camera's; some of
      // everything else.
      const bool special = i % 4 == 0;
      const Vec3 origin = special ? Vec3{component(rng, 3), component(rng, 3), component(rng, 3)}
                                  : Vec3{unit(rng) * 4, unit(rng) * 4, unit(rng) * 4};
      Vec3 directions[kTorusPacketLanes];
      double t_max[kTorusPacketLanes];
      for (int l = 0; l < kTorusPacketLanes; ++l) {
        const Vec3 target{unit(rng) * 1.5, unit(rng) * 1.5, unit(rng) * 0.8};
        directions[l] = special ? Vec3{component(rng, 1), component(rng, 1), component(rng, 1)}
                                : (target - origin) * (1 + unit(rng) * 0.5);
        t_max[l] = special ? component(rng, 2) : (l == 3 ? 0.9 : kInfinity);
      }
      TorusFrame together[kTorusPacketLanes];
      const unsigned lanes = torus_frames_avx2(torus, origin, directions, t_max, together);
      for (int l = 0; l < kTorusPacketLanes; ++l) {
        TorusFrame alone;
        const bool alone_formed = torus_frame(torus, origin, directions[l], t_max[l], alone);
        ASSERT_EQ((lanes >> l) & 1u, alone_formed ? 1u : 0u) << i << " lane " << l;
        if (!alone_formed) continue;
        ++formed;
        ASSERT_TRUE(same_frame(together[l], alone)) << i << " lane " << l;
        ++compared;
        if (!alone.first_root_end) continue;
        ++bracketed;
        // Not the plane's crossing: the cylinder's, or a halving's end.
        const TorusLine& line = alone.line;
        if (*alone.first_root_end != -line.f.z / line.u.z) ++halved;
      }
    }
  }
  EXPECT_GT(formed, 100000);
  EXPECT_EQ(compared, formed);
  // The first-root brackets, both of first_root_bracket's points and the halvings among them.
  EXPECT_GT(bracketed, 100000);
  EXPECT_GT(halved, 50000);
}

bool same_local_hit(const LocalHit& a, const LocalHit& b) {
  return same_value(a.t, b.t) && same_value(a.point, b.point) &&
         same_value(a.point_error, b.point_error) && same_value(a.normal, b.normal) &&
         same_value(a.shading_normal, b.shading_normal) && a.part == b.part;
}

// The hits of roots re-projected four lanes at once must be torus_root_hit's, bit for bit: roots
// near the surface (the spindle's inner lemon among them, which re-projects onto the circle about
// -R), roots on the axis (surface_hit's other branch), and special values (hypot_inline's ranges,
// infinities, NaN); lanes left out of the mask are not written.
TEST(TorusPacket, RootHitsAreTorusRootHitsBitForBit) {
  if (!wide_box_kernel_supported(WideBoxKernel::Avx2)) GTEST_SKIP() << "no AVX2";
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> unit(-1, 1);
  const double two_pi = 2 * std::numbers::pi;
  int compared = 0, inner = 0, on_axis = 0;
  for (const Torus& torus : kTori) {
    const double big_r = torus.torus_radius, r = torus.tube_radius;
    for (int i = 0; i < 50000; ++i) {
      TorusFrame frames[kTorusPacketLanes];
      TorusRoot roots[kTorusPacketLanes];
      for (int l = 0; l < kTorusPacketLanes; ++l) {
        const int kind = std::uniform_int_distribution<int>(0, 9)(rng);
        const double s = unit(rng) * 3;
        Vec3 u{unit(rng), unit(rng), unit(rng)}, point;
        if (kind == 0) {  // special values
          u = {component(rng, 1), component(rng, 1), component(rng, 1)};
          point = {component(rng, 2), component(rng, 2), component(rng, 2)};
        } else if (kind == 1) {  // on the axis
          u = {0, 0, 1};
          point = {0, 0, unit(rng) * 2};
        } else {  // near the surface: a point of the tube, moved by up to 1e-6
          const double theta = unit(rng) * two_pi, phi = unit(rng) * two_pi;
          const double rho = big_r + r * std::cos(phi);
          point = Vec3{rho * std::cos(theta), rho * std::sin(theta), r * std::sin(phi)} +
                  Vec3{unit(rng), unit(rng), unit(rng)} * 1e-6;
        }
        frames[l].line = {u, point - u * s, 1, 0, -4, 4, 0, 0};
        roots[l] = {s, unit(rng) * 10};
      }
      const unsigned lanes = static_cast<unsigned>(i % 15 + 1);
      LocalHit together[kTorusPacketLanes], unwritten;
      unwritten.t = -7.25;
      unwritten.point = unwritten.normal = {7, 7, 7};
      unwritten.part = 77;
      for (LocalHit& hit : together) hit = unwritten;
      torus_root_hits_avx2(torus, frames, roots, lanes, together);
      for (int l = 0; l < kTorusPacketLanes; ++l) {
        if (!((lanes >> l) & 1u)) {
          ASSERT_TRUE(same_local_hit(together[l], unwritten)) << i << " lane " << l;
          continue;
        }
        const LocalHit alone = torus_root_hit(torus, frames[l].line, roots[l]);
        ASSERT_TRUE(same_local_hit(together[l], alone)) << i << " lane " << l;
        ++compared;
        const Vec3 p = frames[l].line.f + frames[l].line.u * roots[l].s;
        if (same_value(alone.point, p)) ++on_axis;
        // Re-projected onto the circle about -R: nearer the axis than R on its side.
        if (alone.point.x * p.x + alone.point.y * p.y < big_r * big_r * 0.999 &&
            std::hypot(alone.point.x, alone.point.y) < big_r && big_r < r)
          ++inner;
      }
    }
  }
  EXPECT_GT(compared, 500000);
  EXPECT_GT(on_axis, 50000);
  EXPECT_GT(inner, 1000);
}

// Whole packet tests of tori, turned (full products) and diagonal, against each lane alone, with
// every box kernel; lanes left out of the mask are not written.
TEST(TorusPacket, InstancePacketsAreEachRayAlone) {
  std::mt19937_64 rng(12);
  std::vector<Instance> instances;
  for (const Torus& torus : kTori)
    for (const Affine& m : {Affine::translation({-3.6, 0, 0}) * *Affine::rotation(-60, {1, 0, 0}),
                            Affine::translation({0, 0.5, -0.0}) * Affine::scaling({2, 0.5, 1})}) {
      std::optional<Instance> made = make_instance(torus, m, nullptr);
      ASSERT_TRUE(made.has_value());
      instances.push_back(*made);
    }
  const int hits =
      test::compare_instance_packets(instances, {0, 3, 12}, {2.5, 2.5, 2.5}, 0.7, 3000, rng);
  EXPECT_GT(hits, 10000);
}

}  // namespace
}  // namespace tessera
