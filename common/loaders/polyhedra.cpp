// Each polyhedron is given by its vertices; its faces are found as the planes through three
// vertices that have every vertex on one side (the shapes are convex, §3.3.1). That keeps the
// tables short and the faces right by construction, at a cost (n^4 for n <= 60 vertices) paid
// once per scene.
#include "common/loaders/polyhedra.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>
#include <vector>
#include "common/math/portable_math.h"

namespace tessera {
namespace {

constexpr double kPhi = std::numbers::phi;

// Adds (a, b, c) and its two cyclic permutations, with every choice of signs of the non-zero
// coordinates: the even permutations the Platonic and Archimedean solids are written with.
void add_cyclic(std::vector<Vec3>& points, double a, double b, double c) {
  const double values[3] = {a, b, c};
  for (int shift = 0; shift < 3; ++shift) {
    for (int signs = 0; signs < 8; ++signs) {
      Vec3 p;
      bool duplicate = false;
      for (int axis = 0; axis < 3; ++axis) {
        const double v = values[(axis + shift) % 3];
        const bool negate = (signs >> axis) & 1;
        if (negate && v == 0) duplicate = true;  // -0 is the point with +0
        p[axis] = negate ? -v : v;
      }
      if (!duplicate) points.push_back(p);
    }
  }
}

std::vector<Vec3> cube_corners(double s) {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) points.push_back({i & 1 ? s : -s, i & 2 ? s : -s, i & 4 ? s : -s});
  return points;
}

// A ring of `count` points of radius `r` at height `z` around the z-axis.
void add_ring(std::vector<Vec3>& points, int count, double r, double z) {
  for (int k = 0; k < count; ++k) {
    const double angle = 2 * std::numbers::pi * k / count;
    const SinCos sc = tessera::sincos(angle);
    points.push_back({r * sc.cos, r * sc.sin, z});
  }
}

std::vector<Vec3> vertices(Polyhedron which) {
  std::vector<Vec3> points;
  switch (which) {
    case Polyhedron::Tetrahedron:
      // Alternate corners of the cube [-1, 1]^3.
      points = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
      break;
    case Polyhedron::Octahedron:
      add_cyclic(points, 1, 0, 0);
      break;
    case Polyhedron::Icosahedron:
      add_cyclic(points, 0, 1, kPhi);
      break;
    case Polyhedron::Dodecahedron:
      points = cube_corners(1);
      add_cyclic(points, 0, 1 / kPhi, kPhi);
      break;
    case Polyhedron::Buckyball:
      // The truncated icosahedron: 12 pentagons and 20 hexagons.
      add_cyclic(points, 0, 1, 3 * kPhi);
      add_cyclic(points, 1, 2 + kPhi, 2 * kPhi);
      add_cyclic(points, kPhi, 2, 2 * kPhi + 1);
      break;
    case Polyhedron::Pyramid:
      // Square base in z = 0 with edges along x and y, apex on +z, like the cone: the
      // equilateral square pyramid, whose vertices all lie on the unit sphere.
      add_ring(points, 4, 1, 0);
      for (Vec3& p : points)
        p = {(p.x - p.y) / std::numbers::sqrt2, (p.x + p.y) / std::numbers::sqrt2, 0};
      points.push_back({0, 0, 1});
      break;
    case Polyhedron::Diamond:
      // A brilliant-like gem about the z-axis: an octagonal table on top, a crown down to the
      // girdle (the unit circle in z = 0), a pavilion down to the culet.
      add_ring(points, 8, 0.55, 0.35);
      add_ring(points, 8, 1, 0);
      points.push_back({0, 0, -0.85});
      break;
  }
  // Scale onto the unit sphere: the farthest vertex at distance 1.
  double radius = 0;
  for (const Vec3& p : points) radius = std::max(radius, length(p));
  for (Vec3& p : points) p = p / radius;
  return points;
}

// The faces of the convex hull of `points`: for each, the indices of its vertices in
// counter-clockwise order seen from outside.
std::vector<std::vector<std::uint32_t>> hull_faces(const std::vector<Vec3>& points) {
  constexpr double kTolerance = 1e-9;  // the points are O(1) and exact to ~1e-16
  const std::uint32_t n = static_cast<std::uint32_t>(points.size());
  std::set<std::vector<std::uint32_t>> seen;
  std::vector<std::vector<std::uint32_t>> faces;
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = i + 1; j < n; ++j) {
      for (std::uint32_t k = j + 1; k < n; ++k) {
        Vec3 normal = cross(points[j] - points[i], points[k] - points[i]);
        if (length(normal) < kTolerance) continue;  // collinear
        normal = normal / length(normal);
        const double offset = dot(normal, points[i]);
        bool above = false, below = false;
        std::vector<std::uint32_t> on_plane;
        for (std::uint32_t m = 0; m < n; ++m) {
          const double d = dot(normal, points[m]) - offset;
          if (d > kTolerance) above = true;
          if (d < -kTolerance) below = true;
          if (std::fabs(d) <= kTolerance) on_plane.push_back(m);
        }
        if (above == below) continue;  // a plane through the inside (or all points coplanar)
        if (!seen.insert(on_plane).second) continue;
        if (above) normal = -normal;  // outward
        // Order the face's vertices by angle around its centre, counter-clockwise about the
        // outward normal.
        Vec3 centre;
        for (std::uint32_t m : on_plane) centre += points[m];
        centre = centre / static_cast<double>(on_plane.size());
        const Vec3 u = points[on_plane[0]] - centre;
        const Vec3 v = cross(normal, u);
        auto angle = [&](std::uint32_t m) {
          const Vec3 d = points[m] - centre;
          return tessera::atan2(dot(d, v), dot(d, u));
        };
        std::sort(on_plane.begin(), on_plane.end(),
                  [&](std::uint32_t a, std::uint32_t b) { return angle(a) < angle(b); });
        faces.push_back(std::move(on_plane));
      }
    }
  }
  return faces;
}

const char* name(Polyhedron which) {
  switch (which) {
    case Polyhedron::Buckyball:
      return "buckyball";
    case Polyhedron::Diamond:
      return "diamond";
    case Polyhedron::Dodecahedron:
      return "dodecahedron";
    case Polyhedron::Icosahedron:
      return "icosahedron";
    case Polyhedron::Octahedron:
      return "octahedron";
    case Polyhedron::Pyramid:
      return "pyramid";
    case Polyhedron::Tetrahedron:
      return "tetrahedron";
  }
  return "";
}

}  // namespace

Mesh polyhedron_mesh(Polyhedron which) {
  Mesh mesh;
  mesh.source = name(which);
  mesh.positions = vertices(which);
  for (const std::vector<std::uint32_t>& face : hull_faces(mesh.positions)) {
    for (std::size_t i = 1; i + 1 < face.size(); ++i) {
      MeshTriangle t;
      t.v = {face[0], face[i], face[i + 1]};
      mesh.triangles.push_back(t);
    }
  }
  return mesh;
}

}  // namespace tessera
