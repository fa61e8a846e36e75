// VRML IndexedFaceSet (ISO/IEC 14772-1 §6.23) to a triangle mesh: polygons, convex or not,
// triangulated by ear clipping; normals given per vertex or per face, or generated from the
// creaseAngle; colours per vertex or per face and texture coordinates given or by the default
// mapping, on the corners of the triangles.
#pragma once

#include <array>
#include <compare>
#include <cstdint>
#include <string>
#include <vector>

#include "common/loaders/vrml_nodes.h"
#include "common/scene/mesh.h"

namespace tessera::vrml {

// Triangles, as index triples into `polygon`, covering the simple polygon `polygon` (in any
// plane, either orientation) and keeping its orientation. A polygon that has no ear left
// (self-intersecting, collinear) is finished as a fan.
std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(const std::vector<Vec3>& polygon);

struct FaceSetMesh {
  Mesh mesh;
  bool smooth = false;  // the corners carry normals to interpolate
};

// Which corner attributes a face set's mesh carries: only what its shape uses, so that other
// meshes pay nothing.
struct CornerAttributes {
  bool colours = false;     // from the Color node, when there is one
  bool tex_coords = false;  // from the TextureCoordinate node, or the default mapping
  auto operator<=>(const CornerAttributes&) const = default;
};

// ElevationGrid (§6.15) and Extrusion (§6.18) as the IndexedFaceSet that draws the same
// surface, with the node's ccw, solid, creaseAngle, normals and colours and its default
// texture coordinates, so that one path meshes all three.
NodePtr elevation_grid_face_set(const Node& grid);
NodePtr extrusion_face_set(const Node& extrusion);
// At least as many triangles as either of them makes of `node`, from its fields' sizes alone,
// so that a budget can refuse a grid or an extrusion before it is made.
std::uint64_t generated_triangles(const Node& node);

// The mesh of an IndexedFaceSet node (empty without coordinates), with the `wanted` corner
// attributes. Throws SceneError at the index field for an index out of range.
FaceSetMesh face_set_mesh(const Node& face_set, CornerAttributes wanted = {});

}  // namespace tessera::vrml
