// Boolean objects (constructive solid geometry, SDL §3.2.4): the union, intersection or
// difference of two solids, each a shape under its own transform or a boolean object itself.
//
// A ray meets a boolean object where its inside/outside state changes. Each child reports every
// crossing of its boundary along the ray, in order (the per-shape *_crossings routines of
// shapes.h); whether the ray's origin is inside a shape follows from the parity of its crossings
// ahead. Walking both children's crossings in order and combining their states (union: in A or
// B; intersection: in A and B; difference: in A and not B) gives the node's own crossings, and
// so up the tree. The hit is the nearest crossing of the root.
//
// Coincident faces (docs/ARCHITECTURE.md, "Robust rays"): crossings of the two children whose
// t differ by no more than the sum of their error bounds are one event: both children change
// state at once and the node's state is compared only before and after all of them. So A - A is
// empty, A u A and A n A have A's crossings, and a box minus a cylinder flush with its faces
// has a clean hole. When the state changes, the crossing reported is that of the left child if
// its own change agrees with the node's (it enters when the node is entered), else the right
// child's: a fixed order, the same for every ray. A surface of the subtracted child of a
// difference has its normals flipped, so that they point out of the result.
#pragma once

#include <vector>

#include "common/geometry/instance.h"

namespace tessera {

// The instance of a boolean object over its children's instances, which must outlive it (and
// not move). World bounds: union, the union of the children's; intersection, their
// intersection; difference, the left child's.
Instance make_csg_instance(const CsgShape& shape, const Instance& left, const Instance& right);

// One crossing of a solid's boundary along a ray: the hit (normal pointing out of the solid),
// the bound on its t's error, and whether the ray is inside the solid after it.
struct SolidCrossing {
  WorldHit hit;
  double t_error = 0;
  bool entering = false;
};

// Every crossing with t > 0 of the solid an instance bounds, in order along the ray, and whether
// the ray's origin is inside it. For a shape, its crossings; for a boolean object, those where
// its state changes. Meshes must be closed for the result to mean anything.
struct SolidCrossings {
  bool inside_at_origin = false;
  std::vector<SolidCrossing> crossings;
};
SolidCrossings solid_crossings(const Instance& instance, const Ray& world_ray,
                               IntersectionCounters& counters);

// Nearest hit of a boolean object with t in (0, t_max), or false (intersect_instance).
bool intersect_csg(const Instance& instance, const Ray& world_ray, double t_max, WorldHit& hit,
                   IntersectionCounters& counters);

}  // namespace tessera
