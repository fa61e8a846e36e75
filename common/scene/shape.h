// The generic shapes of SDL §3.3 in their own object space (docs/ARCHITECTURE.md, "Generic
// shapes"):
//   sphere: unit sphere at the origin;  cube: [-1, 1]^3;
//   tapered cylinder: z in [0, 1], radius 1 at z = 0 and `top_radius` at z = 1 (cone: 0,
//   cylinder: 1);  mesh: triangles of Scene::meshes[mesh];
//   torus: around the z axis, lying in the XY-plane (§3.3.5);
//   algebraic surface: the zero set of a fixed polynomial (common/geometry/algebraic_surfaces.h)
//   clipped to a box that the CT only translates (§3.3.6);
//   boolean object (CSG, §3.2.4): the union, intersection or difference of two other objects.
#pragma once

#include <cstddef>
#include <cstdint>
#include <variant>

#include "common/math/vec3.h"

namespace tessera {

struct Sphere {
  friend bool operator==(const Sphere&, const Sphere&) = default;
};
struct Cube {
  friend bool operator==(const Cube&, const Cube&) = default;
};
struct TaperedCylinder {
  double top_radius = 1;
  bool distort_texture = false;  // caps' texture mapping: distort (true) or clip (false)
  // Which parts are drawn (VRML's Cylinder and Cone may leave out side, bottom or top). An
  // open shape has no inside: it is no operand for a boolean object.
  bool wall = true, base_cap = true, top_cap = true;
  // VRML97's texture mapping (§6.12, §6.17) instead of the manual's: the wall's s starts at +y
  // (the VRML loader turns it to -z) rather than +x, and the base cap's t runs the other way,
  // so that seen from outside it reads right side up.
  bool vrml_texture = false;
  friend bool operator==(const TaperedCylinder&, const TaperedCylinder&) = default;
};
struct MeshShape {
  std::size_t mesh = 0;              // index into Scene::meshes
  bool interpolate_normals = false;  // Phong-interpolated vertex normals, else flat
  friend bool operator==(const MeshShape&, const MeshShape&) = default;
};

// (x^2 + y^2 + z^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2), R = torus_radius, r = tube_radius: a
// ring torus when r < R, a horn torus when r = R, a self-intersecting spindle torus when r > R.
struct Torus {
  double tube_radius = 0.5;
  double torus_radius = 1;
  friend bool operator==(const Torus&, const Torus&) = default;
};

// The algebraic surfaces of §3.3.6, in the order the manual lists them.
enum class AlgebraicKind {
  OneSheetHyperboloid,
  TwoSheetHyperboloid,
  EllipticCylinder,
  EllipticCone,
  EllipticParaboloid,
  HyperbolicParaboloid,
  PinchedSurfaceWithHoles,
  PinchedSurfaceWithLobe,
  FourLobes,
  SteinersRomanSurface,
  ToothCube,
};

struct AlgebraicSurface {
  AlgebraicKind kind = AlgebraicKind::OneSheetHyperboloid;
  // Width, height and depth of the box extent along the world x, y and z axes, centred on
  // where the CT takes the object's origin: the CT translates the box but never scales or
  // rotates it (§3.3.6).
  Vec3 extent{2, 2, 2};
  friend bool operator==(const AlgebraicSurface&, const AlgebraicSurface&) = default;
};

enum class CsgOperation { Union, Intersection, Difference };

// A boolean object (§3.2.4). Its children are other entries of Scene::objects, written before
// it, each with its own transform and material; a child may be a boolean object itself. The
// children are parts of this object and not objects of the scene by themselves. The boolean
// object's own transform is the identity and its material is unused: every surface point
// belongs to one child, which gives it its material.
struct CsgShape {
  CsgOperation operation = CsgOperation::Union;
  std::uint32_t left = 0;   // index into Scene::objects
  std::uint32_t right = 0;  // index into Scene::objects; subtracted in a difference
  friend bool operator==(const CsgShape&, const CsgShape&) = default;
};

using ShapeGeometry =
    std::variant<Sphere, Cube, TaperedCylinder, MeshShape, Torus, AlgebraicSurface, CsgShape>;

}  // namespace tessera
