// Closed triangle meshes and random transforms for the geometry tests.
#pragma once

#include <array>
#include <cmath>
#include <random>

#include "common/math/affine.h"
#include "common/scene/mesh.h"

namespace tessera::testing {

inline void add_triangle(Mesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  MeshTriangle t;
  t.v = {a, b, c};
  mesh.triangles.push_back(t);
}

// The octahedron |x| + |y| + |z| = 1 (times `scale`, moved by `offset`), outward-wound.
inline Mesh octahedron(double scale = 1, const Vec3& offset = {}) {
  Mesh mesh;
  mesh.source = "octahedron";
  const Vec3 v[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3& p : v) mesh.positions.push_back(p * scale + offset);
  for (int sx = 0; sx < 2; ++sx)
    for (int sy = 0; sy < 2; ++sy)
      for (int sz = 0; sz < 2; ++sz) {
        const auto x = static_cast<std::uint32_t>(sx), y = static_cast<std::uint32_t>(2 + sy),
                   z = static_cast<std::uint32_t>(4 + sz);
        // Counter-clockwise seen from outside when the octant's sign count is even.
        if ((sx + sy + sz) % 2 == 0)
          add_triangle(mesh, x, y, z);
        else
          add_triangle(mesh, x, z, y);
      }
  // Give every vertex its outward normal (for smooth-shading tests).
  for (const Vec3& p : v) mesh.normals.push_back(p);
  for (MeshTriangle& t : mesh.triangles) t.n = t.v;
  return mesh;
}

// The cube [-1, 1]^3 with each face split into n x n quads of two triangles, vertices shared.
inline Mesh subdivided_cube(int n, const Vec3& offset = {}) {
  Mesh mesh;
  mesh.source = "subdivided cube";
  const int side = n + 1;
  // Vertex index on the cube's surface grid, created on demand.
  std::vector<std::int64_t> index(static_cast<std::size_t>(side * side * side), -1);
  auto vertex = [&](int i, int j, int k) {
    std::int64_t& slot = index[static_cast<std::size_t>((i * side + j) * side + k)];
    if (slot < 0) {
      slot = static_cast<std::int64_t>(mesh.positions.size());
      mesh.positions.push_back(Vec3{-1 + 2.0 * i / n, -1 + 2.0 * j / n, -1 + 2.0 * k / n} + offset);
    }
    return static_cast<std::uint32_t>(slot);
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int positive = 0; positive < 2; ++positive)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          // Grid coordinates (u, v) in the face, w fixed.
          auto at = [&](int u, int v) {
            std::array<int, 3> c{};
            c[static_cast<std::size_t>(axis)] = positive ? n : 0;
            c[static_cast<std::size_t>((axis + 1) % 3)] = u;
            c[static_cast<std::size_t>((axis + 2) % 3)] = v;
            return vertex(c[0], c[1], c[2]);
          };
          const std::uint32_t p00 = at(a, b), p10 = at(a + 1, b), p11 = at(a + 1, b + 1),
                              p01 = at(a, b + 1);
          // (u, v, axis) is right-handed, so u x v points along +axis.
          if (positive) {
            add_triangle(mesh, p00, p10, p11);
            add_triangle(mesh, p00, p11, p01);
          } else {
            add_triangle(mesh, p00, p11, p10);
            add_triangle(mesh, p00, p01, p11);
          }
        }
  return mesh;
}

inline Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    const Vec3 v{g(rng), g(rng), g(rng)};
    const double len = length(v);
    if (len > 1e-3) return v / len;
  }
}

// translate * rotate * scale with scales 10^[-4, 4] (often non-uniform), any rotation and
// translations up to 10^8 in magnitude.
inline Affine random_transform(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::uniform_real_distribution<double> exponent(-4, 4);
  const double base = exponent(rng);
  Vec3 s{std::pow(10, base), std::pow(10, base), std::pow(10, base)};
  if (unit(rng) < 0.7)
    s = {std::pow(10, exponent(rng)), std::pow(10, exponent(rng)), std::pow(10, exponent(rng))};
  const double magnitude = std::pow(10, 8 * unit(rng));
  const Vec3 t = random_unit(rng) * (unit(rng) < 0.1 ? 0 : magnitude);
  const Affine r = *Affine::rotation(360 * unit(rng), random_unit(rng));
  return Affine::translation(t) * r * Affine::scaling(s);
}

}  // namespace tessera::testing
