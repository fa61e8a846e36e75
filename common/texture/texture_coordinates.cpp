#include "common/texture/texture_coordinates.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/math/portable_math.h"
#include "common/texture/mesh_corners.h"

namespace tessera {

namespace {

constexpr double kPi = std::numbers::pi;

// atan(y / x) / 2pi over the whole turn, in [0, 1]: 0 along +x, 1/4 along +y.
double turn_fraction(double y, double x) {
  const double a = tessera::atan2(y, x) / (2 * kPi);
  return a < 0 ? a + 1 : a;
}

// The polar angle from +z over pi, in [0, 1]; 0 for the origin.
double polar_fraction(const Vec3& p) {
  const double r = length(p);
  if (!(r > 0)) return 0;
  return tessera::acos(std::clamp(p.z / r, -1.0, 1.0)) / kPi;
}

TexCoord cap_coordinates(double x, double y, double r, bool distort) {
  if (!(r > 0)) return {0.5, 0.5};
  if (!distort) return {(x + r) / (2 * r), (y + r) / (2 * r)};  // eq. 4.37-4.38
  // Eq. 4.39-4.48 stretch each ray from the centre so that the circle of radius r reaches the
  // square's edge at the same angle: (s', t') = (cos a, sin a) / max(|cos a|, |sin a|).
  const double m = std::max(std::fabs(x), std::fabs(y));
  if (!(m > 0)) return {0.5, 0.5};
  const double radial = std::hypot(x, y) / r;
  return {(1 + radial * x / m) / 2, (1 + radial * y / m) / 2};
}

struct ShapeCoordinates {
  const Instance& instance;
  const WorldHit& hit;

  TexCoord operator()(const Sphere&) const { return sphere_texture_coordinates(hit.object_point); }
  TexCoord operator()(const Cube&) const {
    return cube_texture_coordinates(hit.object_point, hit.part);
  }
  TexCoord operator()(const TaperedCylinder& c) const {
    return tapered_cylinder_texture_coordinates(c, hit.object_point, hit.part);
  }
  TexCoord operator()(const Torus& t) const {
    return torus_texture_coordinates(t, hit.object_point);
  }
  // The mesh's own corner coordinates where it has them (VRML's TextureCoordinate), else
  // shrink wrapping.
  TexCoord operator()(const MeshShape&) const {
    const Mesh* mesh = instance.mesh ? instance.mesh->mesh : nullptr;
    if (mesh && !mesh->corner_tex_coords.empty())
      return corner_tex_coord(*mesh, hit.part, hit.object_point);
    return mesh_texture_coordinates(hit.object_point);
  }
  TexCoord operator()(const AlgebraicSurface& a) const {
    // The box extent is centred on the object's origin in the world, along the world axes.
    const Vec3 centre = instance.to_world.apply_point({0, 0, 0});
    return algebraic_texture_coordinates(hit.point - centre, a.extent.z);
  }
  // A boolean object's hits are on its children's surfaces, whose instances (WorldHit::object)
  // the tracer asks instead.
  TexCoord operator()(const CsgShape&) const { return {0.5, 0.5}; }
};

}  // namespace

TexCoord sphere_texture_coordinates(const Vec3& p) {
  return {turn_fraction(p.y, p.x), 1 - polar_fraction(p)};
}

TexCoord cube_texture_coordinates(const Vec3& p, std::uint32_t face) {
  const double x = (p.x + 1) / 2, y = (p.y + 1) / 2, z = (p.z + 1) / 2;
  switch (face) {
    case 0:
      return {z, y};  // -x: seen from -x, +z is to the right
    case 1:
      return {1 - z, y};  // +x
    case 2:
      return {x, z};  // -y: seen from below, +z up
    case 3:
      return {x, 1 - z};  // +y: seen from above, -z up
    case 4:
      return {1 - x, y};  // -z
    default:
      return {x, y};  // +z
  }
}

TexCoord tapered_cylinder_texture_coordinates(const TaperedCylinder& shape, const Vec3& p,
                                              std::uint32_t part) {
  if (part == 0) {
    double s = turn_fraction(p.y, p.x);
    if (shape.vrml_texture) s = s < 0.25 ? s + 0.75 : s - 0.25;
    return {s, std::clamp(p.z, 0.0, 1.0)};
  }
  const double radius = part == 1 ? 1 : shape.top_radius;
  TexCoord c = cap_coordinates(p.x, p.y, radius, shape.distort_texture);
  if (shape.vrml_texture && part == 1) c.t = 1 - c.t;
  return c;
}

TexCoord torus_texture_coordinates(const Torus& shape, const Vec3& p) {
  // The manual writes -sqrt(x^2 + y^2) - R, which is below -1 on every ring torus; the
  // tube's angle from the outer equator is meant.
  const double cos_phi = (std::hypot(p.x, p.y) - shape.torus_radius) / shape.tube_radius;
  double t = 0.5;
  if (cos_phi > 1)
    t = 0;
  else if (cos_phi >= -1)
    t = tessera::acos(cos_phi) / (2 * kPi);
  if (p.z > 0) t = 1 - t;
  return {turn_fraction(p.y, p.x), t};
}

TexCoord mesh_texture_coordinates(const Vec3& p) {
  return {turn_fraction(p.y, p.x), polar_fraction(p)};
}

TexCoord algebraic_texture_coordinates(const Vec3& from_centre, double depth) {
  const double t = depth > 0 ? 1 - (from_centre.z + depth / 2) / depth : 0.5;
  return {turn_fraction(from_centre.y, from_centre.x), std::clamp(t, 0.0, 1.0)};
}

TexCoord texture_coordinates(const Instance& instance, const WorldHit& hit) {
  return std::visit(ShapeCoordinates{instance, hit}, instance.geometry);
}

}  // namespace tessera
