// Flat texture coordinates (s, t) of a point on each generic shape, SDL §4.3.2 (eq. 4.28-4.51),
// computed on the generic shape (object space) so that textures stay attached to moving
// shapes. s runs left to right and t bottom to top; both lie in [0, 1].
#pragma once

#include <cstdint>

#include "common/geometry/instance.h"
#include "common/math/vec3.h"
#include "common/scene/shape.h"
#include "common/scene/tex_coord.h"

namespace tessera {

// Eq. 4.33-4.34: s the longitude from +x towards +y, t = 1 at the north pole (+z).
TexCoord sphere_texture_coordinates(const Vec3& p);
// Each face onto the whole square, as seen from outside: the four side faces with +y up, the
// top (+y) with -z up and the bottom (-y) with +z up. `face` is LocalHit::part (-x, +x, -y, +y,
// -z, +z).
TexCoord cube_texture_coordinates(const Vec3& p, std::uint32_t face);
// Wall (part 0): eq. 4.35-4.36. Caps (part 1 at z = 0, part 2 at z = 1): the cap's disc onto
// the square, clipped (eq. 4.37-4.38) or distorted so that the circle meets the square's edge
// (eq. 4.39-4.48), as the shape's distort-texture flag says.
TexCoord tapered_cylinder_texture_coordinates(const TaperedCylinder& shape, const Vec3& p,
                                              std::uint32_t part);
// Eq. 4.49-4.51, with cos(phi) = (sqrt(x^2 + y^2) - R) / r.
TexCoord torus_texture_coordinates(const Torus& shape, const Vec3& p);
// Shrink wrapping of meshes without corner texture coordinates, eq. 4.31-4.32: s the longitude, t =
// theta / pi from +z.
TexCoord mesh_texture_coordinates(const Vec3& p);
// Shrink wrapping of algebraic surfaces, eq. 4.29-4.30: `from_centre` is the hit relative to
// the centre of the box extent, `depth` the box's depth along z.
TexCoord algebraic_texture_coordinates(const Vec3& from_centre, double depth);

// The coordinates of a hit on an instance, by its shape (for a mesh with corner texture
// coordinates, those interpolated).
TexCoord texture_coordinates(const Instance& instance, const WorldHit& hit);

}  // namespace tessera
