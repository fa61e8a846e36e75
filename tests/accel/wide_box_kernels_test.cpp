// Issue 18 §3: the mesh traversal gives the same answers whichever box kernel it runs
// (wide_box_kernel.h), so that images do not depend on the CPU. Every kernel this build and CPU
// can select traces the same rays through the same meshes, and renders the mesh scenes, and is
// compared bit for bit with the scalar kernel (the box tests alone: float_child_boxes_test.cpp).
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "common/accel/mesh_accel.h"
#include "common/accel/wide_box_kernel.h"
#include "common/accel/wide_bvh_traverse.h"
#include "common/geometry/shapes.h"
#include "common/loaders/scene_loader.h"
#include "common/render/prepared_scene.h"
#include "common/render/render.h"

namespace tessera {
namespace {

std::vector<WideBoxKernel> selectable_kernels() {
  std::vector<WideBoxKernel> kernels;
  for (const auto kernel : kWideBoxKernels)
    if (wide_box_kernel_supported(kernel)) kernels.push_back(kernel);
  return kernels;
}

// Forces a kernel for the scope, then returns to the automatic choice.
struct ForcedKernel {
  explicit ForcedKernel(WideBoxKernel kernel) { force_wide_box_kernel(kernel); }
  ~ForcedKernel() { force_wide_box_kernel(std::nullopt); }
  ForcedKernel(const ForcedKernel&) = delete;
  ForcedKernel& operator=(const ForcedKernel&) = delete;
};

// Everything the mesh queries answer for a set of rays, as bits.
std::vector<std::uint64_t> trace_all(const MeshAccel& accel, const std::vector<Ray>& rays) {
  std::vector<std::uint64_t> out;
  const auto put = [&](double x) { out.push_back(std::bit_cast<std::uint64_t>(x)); };
  const auto put_vec = [&](const Vec3& v) { put(v.x), put(v.y), put(v.z); };
  IntersectionCounters counters;
  for (const Ray& ray : rays) {
    for (const double t_max : {kInfinity, 0.7}) {
      LocalHit hit;
      if (intersect_mesh(accel, true, ray, t_max, hit, counters)) {
        put(hit.t), put_vec(hit.point), put_vec(hit.normal), put_vec(hit.shading_normal);
        out.push_back(hit.part);
      } else {
        out.push_back(~0ull);
      }
      out.push_back(occluded_mesh(accel, ray, t_max, counters) ? 1 : 0);
    }
    for (const LocalHit& crossing : mesh_crossings(accel, false, ray, kInfinity, counters)) {
      put(crossing.t);
      out.push_back(crossing.part);
    }
  }
  out.push_back(counters.bvh_nodes);
  out.push_back(counters.triangle_tests);
  return out;
}

// `count` random triangles of about unit size, their centres in the cube of side 10 at `corner`.
Mesh random_triangles(std::mt19937_64& rng, int count, const Vec3& corner) {
  std::uniform_real_distribution<double> u(0, 1);
  Mesh mesh;
  for (int i = 0; i < count; ++i) {
    const Vec3 c = corner + Vec3{u(rng), u(rng), u(rng)} * 10;
    MeshTriangle t;
    for (int k = 0; k < 3; ++k) {
      t.v[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.push_back(c + Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5});
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

TEST(WideBoxKernels, EveryKernelTracesMeshesAlike) {
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> u(0, 1);
  for (const double offset : {0.0, 1e5}) {
    const Mesh mesh = random_triangles(rng, 3000, {offset, offset, -offset});
    const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
    std::vector<Ray> rays;
    for (int r = 0; r < 3000; ++r) {
      const Vec3 center = Vec3{offset, offset, -offset} + Vec3{5, 5, 5};
      const Vec3 origin = center + Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5} * 30;
      const Vec3 target = center + Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5} * 10;
      rays.push_back({origin, (target - origin) * (0.05 + u(rng))});
    }
    std::optional<std::vector<std::uint64_t>> reference;
    for (const WideBoxKernel kernel : selectable_kernels()) {
      SCOPED_TRACE(std::string(wide_box_kernel_name(kernel)));
      const ForcedKernel forced(kernel);
      ASSERT_EQ(wide_box_kernel(), kernel);
      const std::vector<std::uint64_t> answers = trace_all(accel, rays);
      if (!reference) {
        reference = answers;
        EXPECT_GT(answers.size(), 3 * rays.size());  // not all misses
      } else {
        EXPECT_EQ(answers, *reference);
      }
    }
  }
}

TEST(WideBoxKernels, EveryKernelRendersMeshScenesAlike) {
  const std::filesystem::path scenes = std::filesystem::path(TESSERA_SOURCE_DIR) / "scenes";
  for (const char* name : {"features/mesh.sdl", "features/mesh_formats.sdl", "features/teapot.sdl",
                           "vrml/world.wrl"}) {
    SCOPED_TRACE(name);
    const Scene scene = load_scene_file(scenes / name);
    const PreparedScene prepared(scene, BvhMode::Sah);
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    std::optional<Image> reference;
    for (const WideBoxKernel kernel : selectable_kernels()) {
      SCOPED_TRACE(std::string(wide_box_kernel_name(kernel)));
      const ForcedKernel forced(kernel);
      RenderStats stats;
      const Image image = render_image(prepared, settings, 0, stats);
      if (!reference) {
        reference = image;
      } else {
        ASSERT_EQ(image.rgb.size(), reference->rgb.size());
        for (std::size_t i = 0; i < image.rgb.size(); ++i)
          ASSERT_EQ(std::bit_cast<std::uint32_t>(image.rgb[i]),
                    std::bit_cast<std::uint32_t>(reference->rgb[i]))
              << "value " << i;
      }
    }
  }
}

// Stacks of n triangles whose boxes overlap, each a fifth higher than the one below, which the SAH
// keeps in leaves of many sizes (up to 16), odd ones among them, whose last test of several reads
// the next leaf's first pair (or the padding pair after the last leaf); those lanes must not
// count. A ray through the stack crosses each triangle once; rays from each triangle
// up and down (its leaf's triangles behind them, the next leaf's maybe ahead) are occluded alike,
// with the same counts, by every kernel.
TEST(WideBoxKernels, EveryKernelTracesStacksOfTrianglesAlike) {
  for (int n = 1; n <= 40; ++n) {
    SCOPED_TRACE(std::to_string(n) + " triangles");
    Mesh mesh;
    std::vector<double> heights;  // where the rays below meet each triangle
    for (int k = 0; k < n; ++k) {
      const double base = 0.2 * k;
      const auto first = static_cast<std::uint32_t>(mesh.positions.size());
      for (const Vec3& p : {Vec3{-1, -1, base}, Vec3{3, -1, base + 1}, Vec3{-1, 3, base + 0.5}})
        mesh.positions.push_back(p);
      mesh.triangles.push_back(MeshTriangle{{first, first + 1, first + 2}});
      // (0.25, 0.25) has weights 0.375, 0.3125 and 0.3125 in every triangle.
      heights.push_back(base + 0.3125 + 0.3125 * 0.5);
    }
    const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
    std::optional<std::vector<std::uint64_t>> reference;
    for (const WideBoxKernel kernel : selectable_kernels()) {
      SCOPED_TRACE(std::string(wide_box_kernel_name(kernel)));
      const ForcedKernel forced(kernel);
      IntersectionCounters counters;
      std::vector<int> crossed(static_cast<std::size_t>(n), 0);
      for (const LocalHit& crossing :
           mesh_crossings(accel, false, Ray{{0.25, 0.25, -1}, {0, 0, 1}}, kInfinity, counters))
        ++crossed.at(crossing.part);
      EXPECT_EQ(crossed, std::vector<int>(static_cast<std::size_t>(n), 1));
      std::vector<std::uint64_t> answers;
      for (const double height : heights) {
        for (const double dz : {1.0, -1.0}) {
          IntersectionCounters ray_counters;
          const Ray ray{{0.25, 0.25, height}, {0, 0, dz}};
          answers.push_back(occluded_mesh(accel, ray, kInfinity, ray_counters) ? 1 : 0);
          answers.push_back(ray_counters.triangle_tests);
          answers.push_back(ray_counters.bvh_nodes);
        }
      }
      if (!reference) {
        reference = answers;
      } else {
        EXPECT_EQ(answers, *reference);
      }
    }
  }
}

// The boxes an any-order traversal tests, counted apart: one for the root, eight for the root's
// wide node and for every interior child whose box the float test accepts (any order visits
// them all when the visitor keeps t_max), recursively.
std::uint64_t boxes_an_any_order_walk_tests(const Bvh& bvh, const Ray& ray, double t_max) {
  const FloatBoxRay box_ray(ray);
  const FloatBoxLimit limit(float_far_limit(t_max));
  std::uint64_t boxes = 1;
  std::vector<std::uint32_t> pending = {0};
  while (!pending.empty()) {
    const BvhWideNode& node = bvh.wide[pending.back()];
    pending.pop_back();
    boxes += kWideChildren;
    float entry[kWideChildren];
    const unsigned hits = intersect_float_child_boxes_scalar(node.boxes, box_ray, limit, entry);
    for (int c = 0; c < kWideChildren; ++c)
      if ((hits >> c & 1u) != 0 && node.count[c] == 0) pending.push_back(node.child[c]);
  }
  return boxes;
}

// Every kernel's count of boxes tested (IntersectionCounters::bvh_nodes) must be the walk's
// above, for rays that start inside the mesh's box (no root test to miss) and outside it: the
// traversal's loop has several ways to its next node and leaf (docs/PERFORMANCE.md "The wide
// traversal's own instructions"), and no other test pins the count.
TEST(WideBoxKernels, EveryKernelCountsEightBoxesANodeStep) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(0, 1);
  const MeshAccel accel = build_mesh_accel(random_triangles(rng, 2000, {0, 0, 0}), BvhMode::Sah);
  ASSERT_GT(accel.bvh.wide.size(), 10u);
  std::uint64_t steps = 0;
  for (const WideBoxKernel kernel : selectable_kernels()) {
    SCOPED_TRACE(std::string(wide_box_kernel_name(kernel)));
    const ForcedKernel forced(kernel);
    std::mt19937_64 ray_rng(32);
    for (int r = 0; r < 500; ++r) {
      const double spread = r % 2 == 0 ? 8 : 30;  // inside the root box, or mostly outside
      const Vec3 origin =
          Vec3{5, 5, 5} + Vec3{u(ray_rng) - 0.5, u(ray_rng) - 0.5, u(ray_rng) - 0.5} * spread;
      const Vec3 direction{u(ray_rng) - 0.5, u(ray_rng) - 0.5, u(ray_rng) - 0.5};
      const Ray ray{origin, direction};
      const double t_max = r % 3 == 0 ? 4.0 : kInfinity;
      std::uint64_t nodes_visited = 0;
      std::uint64_t leaves = 0;
      traverse_wide_bvh_leaves(accel.bvh, ray, t_max, nodes_visited, kAnyOrder, [&] {
        return [&](std::uint32_t, std::uint32_t, double limit, auto) { return ++leaves, limit; };
      });
      const bool enters =
          starts_inside(accel.bvh.nodes[0].bounds, ray.origin, t_max) ||
          intersect_bounds(accel.bvh.nodes[0].bounds, ray.origin,
                           {1 / direction.x, 1 / direction.y, 1 / direction.z}, t_max);
      const std::uint64_t expected =
          enters ? boxes_an_any_order_walk_tests(accel.bvh, ray, t_max) : 1;
      ASSERT_EQ(nodes_visited, expected) << "ray " << r;
      steps += (expected - 1) / kWideChildren;
    }
  }
  EXPECT_GT(steps, 1000u);  // the walks went deep
}

// The traversal takes a child entered alone for a leaf from leaf_children's bit rather than from
// its count: every kernel's bits must be the children with a count, in slot order.
TEST(WideBoxKernels, LeafChildrenAreTheChildrenWithACount) {
  std::mt19937_64 rng(18);
  const std::uint32_t counts[] = {0, 1, 2, 5, 16, 17, 24, 0x7fffffff};
  std::uniform_int_distribution<std::size_t> pick(0, std::size(counts) - 1);
  std::bernoulli_distribution interior(0.4);
  for (int n = 0; n < 20000; ++n) {
    BvhWideNode node;
    unsigned expected = 0;
    for (int c = 0; c < kWideChildren; ++c) {
      node.count[c] = interior(rng) ? 0 : counts[pick(rng)];
      node.child[c] = static_cast<std::uint32_t>(rng());
      if (node.count[c] > 0) expected |= 1u << c;
    }
    ASSERT_EQ(leaf_children(node, WideBoxKernelTag<WideBoxKernel::Scalar>{}), expected);
    if (wide_box_kernel_supported(WideBoxKernel::Sse2)) {
      ASSERT_EQ(leaf_children(node, WideBoxKernelTag<WideBoxKernel::Sse2>{}), expected);
    }
    if (wide_box_kernel_supported(WideBoxKernel::Avx2)) {
      ASSERT_EQ(leaf_children(node, WideBoxKernelTag<WideBoxKernel::Avx2>{}), expected);
    }
    if (wide_box_kernel_supported(WideBoxKernel::Avx512Vl)) {
      ASSERT_EQ(leaf_children(node, WideBoxKernelTag<WideBoxKernel::Avx512Vl>{}), expected);
    }
  }
}

TEST(WideBoxKernels, NamesRoundTripAndScalarIsAlwaysThere) {
  for (const auto kernel : kWideBoxKernels)
    EXPECT_EQ(parse_wide_box_kernel(wide_box_kernel_name(kernel)), kernel);
  EXPECT_EQ(wide_box_kernel_name(WideBoxKernel::Avx512Vl), "avx512vl");
  EXPECT_EQ(parse_wide_box_kernel("avx512"), std::nullopt);
  EXPECT_TRUE(wide_box_kernel_supported(WideBoxKernel::Scalar));
}

// The automatic choice is the widest kernel the CPU runs; the AVX-512VL one only where it also
// runs AVX2's, whose code it is. Where it cannot run, the tests above compare the others only.
TEST(WideBoxKernels, TheAvx512VlKernelIsChosenWhereTheCpuHasIt) {
  EXPECT_TRUE(!wide_box_kernel_supported(WideBoxKernel::Avx512Vl) ||
              wide_box_kernel_supported(WideBoxKernel::Avx2));
  if (std::getenv("TESSERA_BOX_KERNEL") != nullptr) GTEST_SKIP() << "TESSERA_BOX_KERNEL is set";
  if (!wide_box_kernel_supported(WideBoxKernel::Avx512Vl))
    GTEST_SKIP() << "no AVX-512F, VL, DQ and BW on this CPU: the avx512vl kernel is not tested";
  EXPECT_EQ(wide_box_kernel(), WideBoxKernel::Avx512Vl);
}

}  // namespace
}  // namespace tessera
