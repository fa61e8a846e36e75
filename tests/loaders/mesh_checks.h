// Properties of triangle meshes checked by the polyhedra and teapot tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <set>
#include <utility>

#include "common/scene/mesh.h"

namespace tessera::test {

// Each undirected edge of `mesh` and how often it is used in each direction.
struct EdgeUse {
  int forward = 0;   // as (lower index, higher index)
  int backward = 0;  // as (higher index, lower index)
};

inline std::map<std::pair<std::uint32_t, std::uint32_t>, EdgeUse> edge_uses(const Mesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, EdgeUse> edges;
  for (const MeshTriangle& t : mesh.triangles) {
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = t.v[i], b = t.v[(i + 1) % 3];
      EdgeUse& use = edges[{std::min(a, b), std::max(a, b)}];
      ++(a < b ? use.forward : use.backward);
    }
  }
  return edges;
}

// Closed and consistently wound: every edge is used by exactly two triangles, once in each
// direction.
inline ::testing::AssertionResult is_closed_and_oriented(const Mesh& mesh) {
  for (const auto& [edge, use] : edge_uses(mesh)) {
    if (use.forward != 1 || use.backward != 1) {
      return ::testing::AssertionFailure()
             << mesh.source << ": edge " << edge.first << "-" << edge.second << " is used "
             << use.forward << " + " << use.backward << " times";
    }
  }
  return ::testing::AssertionSuccess();
}

// V - E + F over the vertices the triangles use.
inline long euler_characteristic(const Mesh& mesh) {
  std::set<std::uint32_t> used;
  for (const MeshTriangle& t : mesh.triangles) used.insert(t.v.begin(), t.v.end());
  return static_cast<long>(used.size()) - static_cast<long>(edge_uses(mesh).size()) +
         static_cast<long>(mesh.triangles.size());
}

// The volume enclosed by a closed, outward-wound mesh (divergence theorem).
inline double enclosed_volume(const Mesh& mesh) {
  double six_volume = 0;
  for (const MeshTriangle& t : mesh.triangles) {
    six_volume +=
        dot(mesh.positions[t.v[0]], cross(mesh.positions[t.v[1]], mesh.positions[t.v[2]]));
  }
  return six_volume / 6;
}

}  // namespace tessera::test
