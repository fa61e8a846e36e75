// A mesh's corner attributes (Mesh::corner_colours, Mesh::corner_tex_coords) at a hit,
// interpolated over the triangle hit with the point's barycentric coordinates. The weights are
// found from the hit's object-space point, so that the intersection routines need not report
// them and meshes without corner attributes pay nothing.
#pragma once

#include <array>
#include <cstdint>

#include "common/math/vec3.h"
#include "common/scene/mesh.h"

namespace tessera {

// The barycentric weights of `p` (on or near the triangle's plane) with respect to the
// corners of triangle `triangle`, in the order of MeshTriangle::v; a third each for a
// degenerate triangle.
std::array<double, 3> corner_weights(const Mesh& mesh, std::uint32_t triangle, const Vec3& p);

// The interpolated corner colour / texture coordinate of triangle `triangle` at `p`. The mesh
// must have that attribute.
Rgb corner_colour(const Mesh& mesh, std::uint32_t triangle, const Vec3& p);
TexCoord corner_tex_coord(const Mesh& mesh, std::uint32_t triangle, const Vec3& p);

}  // namespace tessera
