#include "common/accel/mesh_accel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "common/geometry/shapes.h"
#include "common/geometry/triangle.h"
#include "common/loaders/teapot.h"

namespace tessera {
namespace {

Mesh random_triangles(std::mt19937_64& rng, int n, double world, double size) {
  std::uniform_real_distribution<double> u(0, 1);
  Mesh mesh;
  for (int i = 0; i < n; ++i) {
    const Vec3 c{world * u(rng), world * u(rng), world * u(rng)};
    MeshTriangle t;
    for (int k = 0; k < 3; ++k) {
      t.v[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.push_back(c + Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5} * size);
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

// The nearest triangle by testing every one.
bool brute_force(const Mesh& mesh, const Ray& ray, double& t, std::uint32_t& index) {
  bool found = false;
  t = kInfinity;
  for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
    const MeshTriangle& tri = mesh.triangles[i];
    TriangleHit h;
    if (intersect_triangle(mesh.positions[tri.v[0]], mesh.positions[tri.v[1]],
                           mesh.positions[tri.v[2]], ray, t, h)) {
      t = h.t, index = i, found = true;
    }
  }
  return found;
}

TEST(MeshAccel, SahAndNoneMatchBruteForceOnRandomTriangles) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(0, 1);
  const Mesh mesh = random_triangles(rng, 2000, 10, 1.2);
  const MeshAccel sah = build_mesh_accel(mesh, BvhMode::Sah);
  const MeshAccel none = build_mesh_accel(mesh, BvhMode::None);
  EXPECT_EQ(sah.mesh, &mesh);
  EXPECT_EQ(sah.bounds.lo, none.bounds.lo);
  EXPECT_EQ(sah.bounds.hi, none.bounds.hi);
  IntersectionCounters sah_counters, none_counters;
  int hits = 0;
  for (int r = 0; r < 1000; ++r) {
    const Vec3 o{30 * u(rng) - 10, 30 * u(rng) - 10, 30 * u(rng) - 10};
    const Vec3 target{10 * u(rng), 10 * u(rng), 10 * u(rng)};
    const Ray ray{o, (target - o) * (0.1 + u(rng))};
    double t = 0;
    std::uint32_t index = 0;
    const bool expected = brute_force(mesh, ray, t, index);
    LocalHit a, b;
    ASSERT_EQ(intersect_mesh(sah, false, ray, kInfinity, a, sah_counters), expected) << r;
    ASSERT_EQ(intersect_mesh(none, false, ray, kInfinity, b, none_counters), expected) << r;
    if (!expected) continue;
    ++hits;
    EXPECT_EQ(a.t, t);
    EXPECT_EQ(b.t, t);
    EXPECT_EQ(a.part, index);
    EXPECT_EQ(b.part, index);
  }
  EXPECT_GT(hits, 300);
  // Without a tree, every ray that meets the mesh's box tests every triangle.
  EXPECT_EQ(none_counters.triangle_tests % mesh.triangles.size(), 0u);
  EXPECT_GE(none_counters.triangle_tests, static_cast<std::uint64_t>(hits) * mesh.triangles.size());
  // The tree tests a small fraction of the triangles.
  EXPECT_LT(sah_counters.triangle_tests * 20, none_counters.triangle_tests);
  EXPECT_LT(sah_counters.bvh_nodes + sah_counters.triangle_tests,
            (none_counters.bvh_nodes + none_counters.triangle_tests) / 10);
}

// The float traversal prunes conservatively: the same nearest hits (and occlusion) as testing
// every triangle far from the origin (where float's spacing is 0.008 and a triangle may be
// smaller), with tiny triangles, and with axis-parallel rays.
TEST(MeshAccel, MatchesBruteForceFarFromTheOrigin) {
  struct Case {
    double offset, world, size;
  };
  for (const Case& k :
       {Case{1e5, 10, 1.2}, Case{-1e5, 1e-3, 1e-4}, Case{3e7, 1, 0.05}, Case{0, 1e-4, 1e-6}}) {
    std::mt19937_64 rng(79);
    std::uniform_real_distribution<double> u(0, 1);
    Mesh mesh = random_triangles(rng, 1000, k.world, k.size);
    for (Vec3& p : mesh.positions) p = p + Vec3{k.offset, k.offset, -k.offset};
    const MeshAccel sah = build_mesh_accel(mesh, BvhMode::Sah);
    IntersectionCounters counters;
    int hits = 0;
    for (int r = 0; r < 2000; ++r) {
      const Vec3 base{k.offset, k.offset, -k.offset};
      Vec3 o = base + Vec3{3 * u(rng) - 1, 3 * u(rng) - 1, 3 * u(rng) - 1} * k.world;
      // Aimed at a corner of a triangle half of the time: grazing and shared-edge cases.
      const Vec3 target = r % 2 ? mesh.positions[rng() % mesh.positions.size()]
                                : base + Vec3{u(rng), u(rng), u(rng)} * k.world;
      if (r % 5 == 0) o.x = target.x, o.y = target.y;  // along z
      const Ray ray{o, target - o};
      double t = 0;
      std::uint32_t index = 0;
      const bool expected = brute_force(mesh, ray, t, index);
      LocalHit hit;
      ASSERT_EQ(intersect_mesh(sah, false, ray, kInfinity, hit, counters), expected)
          << k.offset << " ray " << r;
      ASSERT_EQ(occluded_mesh(sah, ray, kInfinity, counters), expected) << k.offset << " ray " << r;
      if (!expected) continue;
      ++hits;
      ASSERT_EQ(hit.t, t) << k.offset << " ray " << r;
      ASSERT_EQ(hit.part, index) << k.offset << " ray " << r;
    }
    EXPECT_GT(hits, 500) << k.offset;
  }
}

// Triangles hit at the same t (here the same triangle twice, in several places of the tree):
// the smaller index wins, whatever order the traversal meets them in.
TEST(MeshAccel, EqualDistancesGoToTheSmallerTriangleIndex) {
  std::mt19937_64 rng(80);
  std::uniform_real_distribution<double> u(0, 1);
  Mesh mesh = random_triangles(rng, 500, 10, 1.2);
  const std::size_t n = mesh.triangles.size();
  for (std::size_t i = 0; i < n; ++i) mesh.triangles.push_back(mesh.triangles[n - 1 - i]);
  const MeshAccel sah = build_mesh_accel(mesh, BvhMode::Sah);
  IntersectionCounters counters;
  int hits = 0;
  for (int r = 0; r < 1000; ++r) {
    const Vec3 o{30 * u(rng) - 10, 30 * u(rng) - 10, 30 * u(rng) - 10};
    const Ray ray{o, Vec3{10 * u(rng), 10 * u(rng), 10 * u(rng)} - o};
    double t = 0;
    std::uint32_t index = 0;
    if (!brute_force(mesh, ray, t, index)) continue;
    ++hits;
    LocalHit hit;
    ASSERT_TRUE(intersect_mesh(sah, false, ray, kInfinity, hit, counters));
    ASSERT_EQ(hit.part, index) << r;
    ASSERT_LT(index, n) << r;
  }
  EXPECT_GT(hits, 200);
}

TEST(MeshAccel, EmptyMeshAndDegenerateTriangles) {
  const Mesh empty;
  const MeshAccel accel = build_mesh_accel(empty, BvhMode::Sah);
  EXPECT_TRUE(accel.bounds.empty());
  EXPECT_TRUE(accel.bvh.nodes.empty());
  IntersectionCounters counters;
  LocalHit hit;
  EXPECT_FALSE(intersect_mesh(accel, false, {{0, 0, -1}, {0, 0, 1}}, kInfinity, hit, counters));

  // A mesh of zero-area triangles is never hit, but builds fine.
  Mesh flat;
  flat.positions = {{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, {0, 0, 0}};
  for (int i = 0; i < 10; ++i) {
    MeshTriangle t;
    t.v = {0, 1, static_cast<std::uint32_t>(i % 2 ? 2 : 3)};
    flat.triangles.push_back(t);
  }
  // The tree leaves them out; the flat "acceleration off" keeps them and must reject them.
  for (const BvhMode mode : {BvhMode::Sah, BvhMode::None}) {
    const MeshAccel flat_accel = build_mesh_accel(flat, mode);
    EXPECT_EQ(flat_accel.bvh.primitive_order.size(), mode == BvhMode::Sah ? 0u : 10u);
    for (const Ray& ray : {Ray{{1, 1, -1}, {0, 0, 1}}, Ray{{-1, -1, 0}, {1, 1, 0}}}) {
      EXPECT_FALSE(intersect_mesh(flat_accel, false, ray, kInfinity, hit, counters));
      EXPECT_FALSE(occluded_mesh(flat_accel, ray, kInfinity, counters));
      EXPECT_TRUE(mesh_crossings(flat_accel, false, ray, kInfinity, counters).empty());
    }
  }
}

// Shadow rays: any hit before t_max, found with an early exit, as by testing every triangle.
TEST(MeshAccel, OccludedMatchesBruteForceAndStopsEarly) {
  std::mt19937_64 rng(78);
  std::uniform_real_distribution<double> u(0, 1);
  const Mesh mesh = random_triangles(rng, 2000, 10, 1.2);
  const MeshAccel sah = build_mesh_accel(mesh, BvhMode::Sah);
  const MeshAccel none = build_mesh_accel(mesh, BvhMode::None);
  IntersectionCounters any_hit, closest;
  int occluded = 0, clear = 0;
  for (int r = 0; r < 1000; ++r) {
    const Vec3 o{30 * u(rng) - 10, 30 * u(rng) - 10, 30 * u(rng) - 10};
    const Vec3 target{10 * u(rng), 10 * u(rng), 10 * u(rng)};
    const Ray ray{o, target - o};
    const double t_max = 0.2 + u(rng);
    bool expected = false;
    for (const MeshTriangle& tri : mesh.triangles) {
      TriangleHit h;
      expected = expected || intersect_triangle(mesh.positions[tri.v[0]], mesh.positions[tri.v[1]],
                                                mesh.positions[tri.v[2]], ray, t_max, h);
    }
    ASSERT_EQ(occluded_mesh(sah, ray, t_max, any_hit), expected) << r;
    IntersectionCounters none_counters;
    ASSERT_EQ(occluded_mesh(none, ray, t_max, none_counters), expected) << r;
    LocalHit hit;
    ASSERT_EQ(intersect_mesh(sah, false, ray, t_max, hit, closest), expected) << r;
    ++(expected ? occluded : clear);
  }
  EXPECT_GT(occluded, 200);
  EXPECT_GT(clear, 200);
  // Stopping at the first hit tests fewer triangles than finding the nearest.
  EXPECT_LT(any_hit.triangle_tests, closest.triangle_tests);
}

// Every leaf the traversal reads (the wide tree's, or a root that is a leaf) starts a quad of
// leaf_quads, and so does every binary leaf that starts one of them; each triangle of the tree
// sits in its lane once, and every other lane (gaps before leaves, the tail) holds NaN corners,
// which never hit.
TEST(MeshAccel, LeavesFillWholeQuads) {
  std::mt19937_64 rng(79);
  const Mesh mesh = random_triangles(rng, 999, 10, 1.2);
  for (const BvhMode mode : {BvhMode::Sah, BvhMode::None}) {
    const MeshAccel accel = build_mesh_accel(mesh, mode);
    const std::vector<std::uint32_t>& order = accel.bvh.primitive_order;
    ASSERT_EQ(accel.leaf_quads.size(), (order.size() + 3) / 4);
    std::vector<bool> in_leaf(order.size() + 1, false);
    for (const BvhNode& node : accel.bvh.nodes) {
      if (node.count == 0) continue;
      for (std::uint32_t i = node.first_or_second_child;
           i < node.first_or_second_child + node.count; ++i)
        in_leaf.at(i) = true;
    }
    if (accel.bvh.wide.empty()) {
      EXPECT_EQ(accel.bvh.nodes.at(0).first_or_second_child % 4, 0u);
    }
    int partial_leaves = 0;
    for (const BvhWideNode& node : accel.bvh.wide)
      for (int c = 0; c < kWideChildren; ++c)
        if (node.count[c] > 0) {
          EXPECT_EQ(node.child[c] % 4, 0u);
          partial_leaves += node.count[c] % 4 != 0;
          // Its range holds triangles only: the binary leaves it takes lie together.
          for (std::uint32_t i = node.child[c]; i < node.child[c] + node.count[c]; ++i)
            EXPECT_TRUE(in_leaf.at(i));
        }
    if (mode == BvhMode::Sah) {
      EXPECT_GT(partial_leaves, 10);  // so that there are gaps
    }
    std::vector<int> seen(mesh.triangles.size(), 0);
    for (std::size_t i = 0; i < 4 * accel.leaf_quads.size(); ++i) {
      const TriangleQuad& quad = accel.leaf_quads[i / 4];
      const int lane = static_cast<int>(i % 4);
      if (i < order.size() && in_leaf[i]) {
        const MeshTriangle& tri = mesh.triangles.at(order[i]);
        ++seen[order[i]];
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(quad_corner(quad, c, lane), mesh.positions[tri.v[static_cast<std::size_t>(c)]]);
      } else {
        if (i < order.size()) {
          EXPECT_EQ(order[i], MeshAccel::kNoTriangle);
        }
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isnan(quad_corner(quad, c, lane).x));
      }
    }
    for (const int n : seen) EXPECT_EQ(n, 1);
  }
}

// The wide tree's invariants: every wide node is reached once, every triangle of the mesh lies
// in exactly one leaf (the rest of a leaf's range are gaps), within the float box of that leaf
// and of every node above it, and no leaf holds more than kMeshLeafTests.max_size triangles.
TEST(MeshAccel, WideTreeHoldsEveryTriangleOnceInsideItsBoxes) {
  std::mt19937_64 rng(80);
  for (const Mesh& mesh : {random_triangles(rng, 3000, 10, 1.2), teapot_mesh()}) {
    const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
    const std::vector<std::uint32_t>& order = accel.bvh.primitive_order;
    const auto box_of = [](const FloatChildBoxes& boxes, int c) {
      Bounds3 b;
      for (int a = 0; a < 3; ++a) b.lo[a] = boxes.bound[a][0][c], b.hi[a] = boxes.bound[a][1][c];
      return b;
    };
    const auto inside = [](const Bounds3& inner, const Bounds3& outer) {
      for (int a = 0; a < 3; ++a)
        if (!(outer.lo[a] <= inner.lo[a] && inner.hi[a] <= outer.hi[a])) return false;
      return true;
    };
    std::vector<int> seen(mesh.triangles.size(), 0), reached(accel.bvh.wide.size(), 0);
    std::uint32_t largest_leaf = 0;
    // (wide node, the boxes of the nodes above it)
    std::vector<std::pair<std::uint32_t, std::vector<Bounds3>>> pending = {
        {0, {accel.bvh.nodes[0].bounds}}};
    while (!pending.empty()) {
      const auto [index, above] = pending.back();
      pending.pop_back();
      ++reached.at(index);
      const BvhWideNode& node = accel.bvh.wide[index];
      for (int c = 0; c < kWideChildren; ++c) {
        const Bounds3 box = box_of(node.boxes, c);
        if (box.empty()) continue;
        std::vector<Bounds3> boxes = above;
        boxes.push_back(box);
        if (node.count[c] == 0) {
          pending.emplace_back(node.child[c], boxes);
          continue;
        }
        std::uint32_t triangles = 0;
        for (std::uint32_t i = node.child[c]; i < node.child[c] + node.count[c]; ++i) {
          if (order.at(i) == MeshAccel::kNoTriangle) continue;
          ++triangles, ++seen.at(order[i]);
          Bounds3 triangle;
          for (const std::uint32_t v : mesh.triangles[order[i]].v)
            triangle.extend(mesh.positions[v]);
          for (const Bounds3& b : boxes) EXPECT_TRUE(inside(triangle, b));
        }
        largest_leaf = std::max(largest_leaf, triangles);
      }
    }
    for (const int n : reached) EXPECT_EQ(n, 1);
    for (const int n : seen) EXPECT_EQ(n, 1);
    EXPECT_LE(largest_leaf, kMeshLeafTests.max_size);
    // Leaves of the SAH larger than the binary tree's (split down to four) were taken whole.
    EXPECT_GT(largest_leaf, kMeshLeafTests.split_above);
  }
}

}  // namespace
}  // namespace tessera
