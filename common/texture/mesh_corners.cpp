#include "common/texture/mesh_corners.h"

namespace tessera {

std::array<double, 3> corner_weights(const Mesh& mesh, std::uint32_t triangle, const Vec3& p) {
  const MeshTriangle& tri = mesh.triangles[triangle];
  const Vec3& a = mesh.positions[tri.v[0]];
  const Vec3 e1 = mesh.positions[tri.v[1]] - a, e2 = mesh.positions[tri.v[2]] - a, d = p - a;
  // The point's projection onto the plane in the edges' basis (Ericson, Real-Time Collision
  // Detection §3.4), so that a point a rounding error off the plane still gets weights
  // summing to one.
  const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
  const double denominator = d11 * d22 - d12 * d12;
  if (!(denominator > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  const double de1 = dot(d, e1), de2 = dot(d, e2);
  const double w1 = (d22 * de1 - d12 * de2) / denominator;
  const double w2 = (d11 * de2 - d12 * de1) / denominator;
  return {1 - w1 - w2, w1, w2};
}

Rgb corner_colour(const Mesh& mesh, std::uint32_t triangle, const Vec3& p) {
  const std::array<double, 3> w = corner_weights(mesh, triangle, p);
  const Rgb* c = &mesh.corner_colours[3 * static_cast<std::size_t>(triangle)];
  return c[0] * w[0] + c[1] * w[1] + c[2] * w[2];
}

TexCoord corner_tex_coord(const Mesh& mesh, std::uint32_t triangle, const Vec3& p) {
  const std::array<double, 3> w = corner_weights(mesh, triangle, p);
  const TexCoord* c = &mesh.corner_tex_coords[3 * static_cast<std::size_t>(triangle)];
  return {c[0].s * w[0] + c[1].s * w[1] + c[2].s * w[2],
          c[0].t * w[0] + c[1].t * w[1] + c[2].t * w[2]};
}

}  // namespace tessera
