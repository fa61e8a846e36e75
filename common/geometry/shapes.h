// Ray/shape intersection for the generic shapes of common/scene/shape.h, in object space.
//
// Every routine finds the nearest hit with t in (0, t_max) of a ray given in the shape's object
// space, fills `hit` and returns true, or returns false. They are robust by construction
// (docs/ARCHITECTURE.md, "Robust rays"): numerically stable quadratics, hit points re-projected
// onto the surface with an error bound, watertight triangles. A ray leaving a surface from an
// origin produced by offset_ray_origin() with that bound never hits the same surface again at that
// point.
#pragma once

#include <vector>

#include "common/accel/mesh_accel.h"
#include "common/geometry/local_hit.h"
#include "common/math/ray.h"
#include "common/scene/shape.h"
#include "common/stats/intersection_counters.h"

namespace tessera {

bool intersect_sphere(const Ray& ray, double t_max, LocalHit& hit);
bool intersect_cube(const Ray& ray, double t_max, LocalHit& hit);
// The local normal of every hit on the cube's face `part` (LocalHit::part: -x, +x, -y, +y, -z,
// +z).
Vec3 cube_face_normal(std::uint32_t part);
// Whether the ray hits the sphere (the cube) with t in (0, t_max): intersect_sphere's
// (intersect_cube's) answer, without building the hit (shadow rays).
bool occluded_sphere(const Ray& ray, double t_max);
bool occluded_cube(const Ray& ray, double t_max);
bool intersect_tapered_cylinder(const TaperedCylinder& shape, const Ray& ray, double t_max,
                                LocalHit& hit);
bool intersect_torus(const Torus& shape, const Ray& ray, double t_max, LocalHit& hit);
// Whether the ray hits the torus with t in (0, t_max): always intersect_torus' answer, most
// often without polishing the hit (shadow rays).
bool occluded_torus(const Torus& shape, const Ray& ray, double t_max);
// Meshes go through their own BVH (common/accel/mesh_accel.h).
bool intersect_mesh(const MeshAccel& mesh, bool interpolate_normals, const Ray& ray, double t_max,
                    LocalHit& hit, IntersectionCounters& counters);
// Whether the ray hits the mesh with t in (0, t_max): any hit ends the traversal (shadow rays).
bool occluded_mesh(const MeshAccel& mesh, const Ray& ray, double t_max,
                   IntersectionCounters& counters);

// Every crossing of the surface with t in (0, t_max), ascending by t, for CSG (csg.h). A ray
// touching the surface (a tangent, or the horn torus' pinch) crosses it twice at the same t,
// so the parity of a crossing's index still tells inside from outside. A crossing within its
// error bound of the origin is left out, as by the nearest-hit routines: it is the surface a
// ray starting there is leaving, and the origin's side of it is the side it was offset to.
std::vector<LocalHit> sphere_crossings(const Ray& ray, double t_max);
std::vector<LocalHit> cube_crossings(const Ray& ray, double t_max);
std::vector<LocalHit> tapered_cylinder_crossings(const TaperedCylinder& shape, const Ray& ray,
                                                 double t_max);
std::vector<LocalHit> torus_crossings(const Torus& shape, const Ray& ray, double t_max);
// A mesh's crossings are those of all its triangles; hits of two triangles at one point (the
// ray through their shared edge) that cross in the same sense are one crossing. Counting them
// tells inside from outside only for a closed mesh.
std::vector<LocalHit> mesh_crossings(const MeshAccel& mesh, bool interpolate_normals,
                                     const Ray& ray, double t_max, IntersectionCounters& counters);

// Algebraic surfaces are clipped to their box extent, a box in world space: the instance
// narrows [t_min, t_max] to the world ray's span through it (algebraic_extent_span; t means the
// same in both spaces) and passes the span with the object-space ray. Hits and crossings have
// t in (max(t_min, 0), t_max), which must be finite.
bool algebraic_extent_span(const AlgebraicSurface& shape, const Affine& to_world,
                           const Ray& world_ray, double& t_min, double& t_max);
Bounds3 algebraic_extent(const AlgebraicSurface& shape, const Affine& to_world);
bool intersect_algebraic(const AlgebraicSurface& shape, const Ray& ray, double t_min, double t_max,
                         LocalHit& hit);
std::vector<LocalHit> algebraic_crossings(const AlgebraicSurface& shape, const Ray& ray,
                                          double t_min, double t_max);

// Bounds of a generic shape in its object space; empty for an algebraic surface, whose extent
// is a world-space box (algebraic_extent), and for a boolean object (csg.h).
Bounds3 object_bounds(const ShapeGeometry& shape, const MeshAccel* mesh);

}  // namespace tessera
