// Shadow feelers walking the scene BVH four at a time against each alone: every lane's
// transmittance is bit for bit that of feeler_transmittance, and the packet counts the box and
// shape tests the lanes' own walks count, also where some lanes are blocked early (an opaque
// object stops a lane) and others pass through glass, and where the lanes diverge.
#include "common/render/shadow_feelers.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <random>

#include "common/loaders/scene_loader.h"

namespace tessera {
namespace {

void expect_packet_as_alone(const PreparedScene& scene, const Ray* rays, const double* t_max,
                            int count, int& blocked, int& partial) {
  IntersectionCounters packet_counters;
  double factors[kPacketLanes];
  feeler_transmittance_packet(scene, rays, t_max, count, factors, packet_counters);
  IntersectionCounters alone;
  for (int l = 0; l < count; ++l) {
    const double factor = feeler_transmittance(scene, rays[l], t_max[l], alone);
    ASSERT_EQ(std::bit_cast<std::uint64_t>(factors[l]), std::bit_cast<std::uint64_t>(factor))
        << "lane " << l << ": " << factors[l] << " vs " << factor;
    blocked += factor == 0 ? 1 : 0;
    partial += factor > 0 && factor < 1 ? 1 : 0;
  }
  EXPECT_EQ(packet_counters.bvh_nodes, alone.bvh_nodes);
  EXPECT_EQ(packet_counters.shape_tests, alone.shape_tests);
  EXPECT_EQ(packet_counters.triangle_tests, alone.triangle_tests);
}

// Feelers from random points of the scene's bounds towards a light: four from neighbouring
// points towards one light (as a camera packet's hits), or four unrelated ones, of every length
// (t_max 1 ends on the light; infinite for a directional light).
void check_scene(const char* relative, int& blocked, int& partial) {
  SCOPED_TRACE(relative);
  const Scene loaded = load_scene_file(std::filesystem::path(TESSERA_SOURCE_DIR) / relative);
  const PreparedScene scene(loaded, BvhMode::Sah);
  ASSERT_FALSE(scene.bvh().nodes.empty());
  const Bounds3 box = scene.bvh().nodes[0].bounds;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const auto point = [&] {
    const Vec3 span = box.hi - box.lo;
    return Vec3{box.lo.x + u(rng) * span.x, box.lo.y + u(rng) * span.y, box.lo.z + u(rng) * span.z};
  };
  for (int i = 0; i < 4000; ++i) {
    Ray rays[kPacketLanes];
    double t_max[kPacketLanes];
    const Vec3 light = point() + Vec3{0, 4, 0};
    const Vec3 base = point();
    const int kind = i % 3;
    for (int l = 0; l < kPacketLanes; ++l) {
      const Vec3 origin = kind == 0 ? base + Vec3{0.01 * l, 0, 0.003 * l} : point();
      if (kind == 2) {
        rays[l] = Ray{origin, unit_or_zero(point() - origin), 0};
        t_max[l] = kInfinity;
      } else {
        rays[l] = Ray{origin, (kind == 0 ? light : point()) - origin, 0};
        t_max[l] = 1;
      }
    }
    expect_packet_as_alone(scene, rays, t_max, 1 + i % kPacketLanes, blocked, partial);
    if (testing::Test::HasFatalFailure()) return;
  }
}

TEST(ShadowFeelers, PacketLanesMatchFeelersAlone) {
  int blocked = 0, partial = 0;
  for (const char* scene :
       {"scenes/demo.sdl", "scenes/features/csg.sdl", "scenes/features/torus.sdl",
        "scenes/features/refraction.sdl", "scenes/features/mesh.sdl"}) {
    check_scene(scene, blocked, partial);
    if (HasFatalFailure()) return;
  }
  // The rays must exercise both ends: lanes stopped by an opaque object, lanes through glass.
  EXPECT_GT(blocked, 1000);
  EXPECT_GT(partial, 100);
}

}  // namespace
}  // namespace tessera
