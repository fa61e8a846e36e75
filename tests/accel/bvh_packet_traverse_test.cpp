// The packet walk of the scene BVH against each ray's own walk: the packet's box test gives every
// lane the hits and bit-identical entries of intersect_child_boxes, and every ray visits the same
// leaves in the same order with the same t_max, and counts the same box tests, as
// traverse_bvh_leaves, also when the rays of a packet disagree on which child comes first.
#include "common/accel/bvh_packet_traverse.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <tuple>
#include <vector>

#include "common/accel/bvh_traverse.h"
#include "common/accel/wide_box_kernel.h"
#include "tests/accel/edge_case_rays.h"
#include "tests/accel/random_boxes.h"

namespace tessera {
namespace {

// The box kernels this machine runs: the SSE2 (and scalar) packet test, and AVX2's (which the
// AVX-512VL kernel runs too).
std::vector<WideBoxKernel> packet_kernels() {
  std::vector<WideBoxKernel> kernels = {WideBoxKernel::Sse2};
  for (const WideBoxKernel kernel : {WideBoxKernel::Avx2, WideBoxKernel::Avx512Vl})
    if (wide_box_kernel_supported(kernel)) kernels.push_back(kernel);
  return kernels;
}

void expect_lanes_as_alone(const ChildBoxes& boxes, const Ray* rays, const double* t_max,
                           WideBoxKernel kernel) {
  SCOPED_TRACE(wide_box_kernel_name(kernel));
  const PacketRays packet(rays, kPacketLanes);
  double entry[2][kPacketLanes];
  unsigned hits[2];
  if (has_avx2(kernel))
    intersect_child_boxes_packet_avx2(boxes, packet, t_max, entry, hits);
  else
    intersect_child_boxes_packet(boxes, packet, t_max, entry, hits);
  for (int l = 0; l < kPacketLanes; ++l) {
    double alone[2] = {-1, -1};
    const unsigned alone_hits = intersect_child_boxes(boxes, BoxRay(rays[l]), t_max[l], alone);
    for (int c = 0; c < 2; ++c) {
      ASSERT_EQ((hits[c] >> l) & 1u, (alone_hits >> c) & 1u) << "lane " << l << " child " << c;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(entry[c][l]), std::bit_cast<std::uint64_t>(alone[c]))
          << "lane " << l << " child " << c << ": " << entry[c][l] << " vs " << alone[c];
    }
  }
}

void expect_lanes_as_alone(const ChildBoxes& boxes, const Ray* rays,
                           const double* t_max) {  // with each kernel
  for (const WideBoxKernel kernel : packet_kernels())
    expect_lanes_as_alone(boxes, rays, t_max, kernel);
}

// Each lane of a packet holds its ray's box constants as the scalar definition gives them (the
// SSE2 set-up computes two lanes at once), lanes past `count` the first ray's; the edge cases'
// zero, negative-zero and infinite components among them.
TEST(BvhPacket, PacketRaysHoldEachLanesConstants) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-2, 2);
  std::vector<Ray> pool = edge_case_rays();
  for (int i = 0; i < 40; ++i)
    pool.push_back(
        {{u(rng), u(rng), u(rng)},
         {direction_component(rng, u), direction_component(rng, u), direction_component(rng, u)}});
  int uniform_packets = 0;
  for (std::size_t first = 0; first + kPacketLanes <= pool.size(); ++first)
    for (int count = 1; count <= kPacketLanes; ++count) {
      const Ray* rays = &pool[first];
      const PacketRays packet(rays, count);
      EXPECT_EQ(packet.lanes, (1u << count) - 1);
      bool same_sides = true;
      for (int a = 0; a < 3; ++a)
        for (int l = 0; l < kPacketLanes; ++l) {
          const Ray& ray = rays[l < count ? l : 0];
          const double inv = 1 / ray.direction[a];
          EXPECT_EQ(std::bit_cast<std::uint64_t>(packet.origin[a][l]),
                    std::bit_cast<std::uint64_t>(ray.origin[a]));
          EXPECT_EQ(std::bit_cast<std::uint64_t>(packet.inv_dir[a][l]),
                    std::bit_cast<std::uint64_t>(inv));
          EXPECT_EQ(packet.backward[a][l], !(inv >= 0)) << "axis " << a << " lane " << l;
          same_sides = same_sides && packet.backward[a][l] == packet.backward[a][0];
        }
      EXPECT_EQ(packet.same_sides, same_sides) << "rays from " << first << ", count " << count;
      uniform_packets += same_sides;
      if (HasFailure()) return;
    }
  EXPECT_GT(uniform_packets, 10);  // both answers of same_sides occur
  EXPECT_LT(uniform_packets, 150);
}

TEST(BvhPacket, BoxTestMatchesEachRayAloneOnRandomRays) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-2, 2);
  const auto component = [&] { return direction_component(rng, u); };
  int same_sides = 0;
  for (int i = 0; i < 5000; ++i) {
    Bounds3 a, b;
    for (Bounds3* box : {&a, &b}) {
      box->extend(Vec3{u(rng), u(rng), u(rng)});
      box->extend(Vec3{u(rng), u(rng), u(rng)});
    }
    const ChildBoxes boxes = make_child_boxes(a, b);
    Ray rays[kPacketLanes];
    double t_max[kPacketLanes];
    for (int l = 0; l < kPacketLanes; ++l) {
      // Origins on box planes now and then (NaN slabs), directions of either sign per lane.
      rays[l] = {{u(rng) > 1.6 ? a.lo.x : u(rng), u(rng), u(rng) > 1.6 ? b.hi.z : u(rng)},
                 {component(), component(), component()}};
      t_max[l] = u(rng) > 0 ? kInfinity : 2 + u(rng);
      // Every other packet's directions take the signs of its first ray's (as neighbouring
      // camera rays' mostly do): the test's path for lanes that share their near sides.
      if (i % 2 == 0)
        for (int axis = 0; axis < 3; ++axis)
          rays[l].direction[axis] = std::copysign(rays[l].direction[axis], rays[0].direction[axis]);
    }
    same_sides += PacketRays(rays, kPacketLanes).same_sides;
    expect_lanes_as_alone(boxes, rays, t_max);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(same_sides, 2000);  // both paths of the test ran
  EXPECT_LT(same_sides, 4000);
}

TEST(BvhPacket, BoxTestMatchesEachRayAloneOnEdgeCases) {
  const Bounds3 unit{{0, 0, 0}, {1, 1, 1}};
  const Bounds3 flat{{0, 0, 0.5}, {1, 1, 0.5}};
  const Bounds3 infinite{{-kInfinity, -kInfinity, -kInfinity}, {kInfinity, kInfinity, kInfinity}};
  const std::vector<Ray> edge = edge_case_rays();
  for (const Bounds3& a : {unit, flat, Bounds3{}, infinite})
    for (const Bounds3& b : {unit, flat, Bounds3{}, infinite})
      for (std::size_t first = 0; first < edge.size(); ++first) {
        Ray rays[kPacketLanes];
        const double t_max[kPacketLanes] = {kInfinity, 0.25, 0.0, kInfinity};
        for (int l = 0; l < kPacketLanes; ++l) rays[l] = edge[(first + l) % edge.size()];
        expect_lanes_as_alone(make_child_boxes(a, b), rays, t_max);
        if (HasFatalFailure()) return;
      }
}

// A leaf visit, as it reached a ray: its range and the t_max it was given.
using Visit = std::tuple<std::uint32_t, std::uint32_t, double>;

// A closest-hit stand-in: t_max shrinks to the entry of the nearest primitive box in the leaf.
double nearest_entry(const std::vector<Bounds3>& boxes, const Bvh& bvh, const Ray& ray,
                     std::uint32_t first, std::uint32_t count, double t_max) {
  const Vec3 inv{1 / ray.direction.x, 1 / ray.direction.y, 1 / ray.direction.z};
  for (std::uint32_t i = first; i < first + count; ++i) {
    double entry = 0;
    if (intersect_bounds(boxes[bvh.primitive_order[i]], ray.origin, inv, t_max, entry) && entry > 0)
      t_max = entry;
  }
  return t_max;
}

void expect_packet_walks_as_alone_now(const std::vector<Bounds3>& boxes, const Bvh& bvh,
                                      const Ray* rays, int count) {
  std::vector<Visit> alone[kPacketLanes], together[kPacketLanes];
  std::uint64_t alone_nodes = 0, together_nodes = 0;
  double alone_t[kPacketLanes], together_t[kPacketLanes];
  for (int l = 0; l < count; ++l) {
    double last = kInfinity;
    traverse_bvh_leaves(bvh, rays[l], kInfinity, alone_nodes,
                        [&](std::uint32_t first, std::uint32_t size, double t_max) {
                          alone[l].emplace_back(first, size, t_max);
                          return last = nearest_entry(boxes, bvh, rays[l], first, size, t_max);
                        });
    alone_t[l] = last;
    together_t[l] = kInfinity;
  }
  traverse_bvh_packet_leaves(bvh, PacketRays(rays, count), together_t, together_nodes,
                             [&](unsigned lanes, std::uint32_t first, std::uint32_t size) {
                               for (int l = 0; l < kPacketLanes; ++l) {
                                 if (!(lanes & (1u << l))) continue;
                                 together[l].emplace_back(first, size, together_t[l]);
                                 together_t[l] =
                                     nearest_entry(boxes, bvh, rays[l], first, size, together_t[l]);
                               }
                             });
  EXPECT_EQ(together_nodes, alone_nodes);
  for (int l = 0; l < count; ++l) {
    EXPECT_EQ(together[l], alone[l]) << "lane " << l;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(together_t[l]), std::bit_cast<std::uint64_t>(alone_t[l]))
        << "lane " << l;
  }
  for (int l = count; l < kPacketLanes; ++l) EXPECT_TRUE(together[l].empty()) << "lane " << l;
}

void expect_packet_walks_as_alone(const std::vector<Bounds3>& boxes, const Bvh& bvh,
                                  const Ray* rays, int count) {
  for (const WideBoxKernel kernel : packet_kernels()) {
    SCOPED_TRACE(wide_box_kernel_name(kernel));
    force_wide_box_kernel(kernel);
    expect_packet_walks_as_alone_now(boxes, bvh, rays, count);
    force_wide_box_kernel(std::nullopt);
  }
}

TEST(BvhPacket, EachRayWalksAsAlone) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const std::vector<Bounds3> boxes = random_boxes(rng, 300, 10, 0.6);
  const Bvh bvh = build_bvh(boxes, BvhMode::Sah);
  int splits_possible = 0;
  for (int i = 0; i < 400; ++i) {
    // Neighbouring rays from one eye (a camera's), or rays from anywhere in any direction, whose
    // near children differ often (the packet splits).
    const bool coherent = i % 2 == 0;
    const Vec3 eye{5 + 8 * u(rng), 5 + 8 * u(rng), -8};
    const Vec3 aim{5 + 4 * u(rng), 5 + 4 * u(rng), 5 + 4 * u(rng)};
    Ray rays[kPacketLanes];
    for (int l = 0; l < kPacketLanes; ++l) {
      rays[l] = coherent ? Ray{eye, aim - eye + Vec3{0.05 * l, 0.02 * u(rng), 0}}
                         : Ray{{10 * u(rng) + 5, 10 * u(rng) + 5, 10 * u(rng) + 5},
                               {u(rng), u(rng), u(rng)}};
      splits_possible += rays[l].direction.x < 0;
    }
    expect_packet_walks_as_alone(boxes, bvh, rays, 1 + i % kPacketLanes);
    if (HasFailure()) return;
  }
  EXPECT_GT(splits_possible, 100);
}

// Every box entered at the same t by every ray: a stacked child whose entry equals a lane's t_max
// is still visited (<=, not <), and equal entries do not make the second child come first.
TEST(BvhPacket, EachRayWalksAsAloneOnTiedEntries) {
  std::vector<Bounds3> boxes;
  for (int i = 0; i < 64; ++i) boxes.push_back(Bounds3{{0, 0, 0}, {1, 1, 1.0 + i}});
  const Bvh bvh = build_bvh(boxes, BvhMode::Sah);
  Ray rays[kPacketLanes];
  for (int l = 0; l < kPacketLanes; ++l) rays[l] = Ray{{0.2 * (l + 1), 0.5, -1}, {0, 0, 1}};
  expect_packet_walks_as_alone(boxes, bvh, rays, kPacketLanes);
}

TEST(BvhPacket, EmptyAndSingleLeafTrees) {
  const std::vector<Bounds3> one = {Bounds3{{0, 0, 0}, {1, 1, 1}}};
  const Ray rays[kPacketLanes] = {
      {{0.5, 0.5, -1}, {0, 0, 1}}, {{2, 2, -1}, {0, 0, 1}}, {{0.2, 0.8, 3}, {0, 0, -1}}, {}};
  expect_packet_walks_as_alone(one, build_bvh(one, BvhMode::Sah), rays, 3);
  expect_packet_walks_as_alone({}, build_bvh({}, BvhMode::Sah), rays, 3);
}

}  // namespace
}  // namespace tessera
