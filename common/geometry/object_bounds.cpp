// Object-space bounds of the generic shapes (shapes.h).
#include <algorithm>
#include <cmath>
#include <variant>

#include "common/geometry/shapes.h"

namespace tessera {

Bounds3 object_bounds(const ShapeGeometry& shape, const MeshAccel* mesh) {
  struct Visitor {
    const MeshAccel* mesh;
    Bounds3 operator()(const Sphere&) const { return {{-1, -1, -1}, {1, 1, 1}}; }
    Bounds3 operator()(const Cube&) const { return {{-1, -1, -1}, {1, 1, 1}}; }
    Bounds3 operator()(const TaperedCylinder& c) const {
      // Radius 1 at z = 0 and |1 + k| at z = 1, with k as intersect_tapered_cylinder rounds it.
      const double r = std::max(1.0, std::fabs(1 + (c.top_radius - 1)));
      return {{-r, -r, 0}, {r, r, 1}};
    }
    Bounds3 operator()(const MeshShape&) const { return mesh ? mesh->bounds : Bounds3{}; }
    Bounds3 operator()(const Torus& t) const {
      const double e = t.torus_radius + t.tube_radius;
      return {{-e, -e, -t.tube_radius}, {e, e, t.tube_radius}};
    }
    Bounds3 operator()(const AlgebraicSurface&) const { return {}; }
    Bounds3 operator()(const CsgShape&) const { return {}; }  // from its children (csg.h)
  };
  return std::visit(Visitor{mesh}, shape);
}

}  // namespace tessera
