// Reading a parsed VRML node's fields with the specification's defaults (ISO/IEC 14772-1 §6):
// the node holds only what the file gave, and types were checked when it was parsed.
#pragma once

#include <array>
#include <numbers>
#include <vector>

#include "common/loaders/vrml_nodes.h"
#include "common/math/affine.h"
#include "common/scene/rgb.h"

namespace tessera::vrml {

inline double sf_float(const Node& n, const char* name, double fallback) {
  const FieldValue* v = n.field(name);
  return v && !v->numbers.empty() ? v->numbers[0] : fallback;
}
inline bool sf_bool(const Node& n, const char* name, bool fallback) {
  return sf_float(n, name, fallback ? 1 : 0) != 0;
}
inline std::array<double, 2> sf_vec2(const Node& n, const char* name,
                                     const std::array<double, 2>& fallback) {
  const FieldValue* v = n.field(name);
  if (!v || v->numbers.size() < 2) return fallback;
  return {v->numbers[0], v->numbers[1]};
}
inline Vec3 sf_vec3(const Node& n, const char* name, const Vec3& fallback) {
  const FieldValue* v = n.field(name);
  if (!v || v->numbers.size() < 3) return fallback;
  return {v->numbers[0], v->numbers[1], v->numbers[2]};
}
inline Rgb sf_color(const Node& n, const char* name, const Rgb& fallback) {
  const Vec3 c = sf_vec3(n, name, {fallback.r, fallback.g, fallback.b});
  return {c.x, c.y, c.z};
}
// An SFRotation (axis x y z, angle in radians) as a transform; a zero axis is no rotation.
inline Affine sf_rotation(const Node& n, const char* name) {
  const FieldValue* v = n.field(name);
  if (!v || v->numbers.size() < 4) return Affine::identity();
  const double degrees = v->numbers[3] * 180 / std::numbers::pi;
  return Affine::rotation(degrees, {v->numbers[0], v->numbers[1], v->numbers[2]})
      .value_or(Affine::identity());
}
inline const std::vector<double>& mf_numbers(const Node& n, const char* name) {
  static const std::vector<double> none;
  const FieldValue* v = n.field(name);
  return v ? v->numbers : none;
}
inline const std::vector<NodePtr>& mf_nodes(const Node& n, const char* name) {
  static const std::vector<NodePtr> none;
  const FieldValue* v = n.field(name);
  return v ? v->nodes : none;
}
// The node of an SFNode field, or null (NULL, absent, or a node that is not drawn). MFNode
// lists hold null for nodes that are not drawn (FieldValue::nodes).
inline const Node* sf_node(const Node& n, const char* name) {
  const std::vector<NodePtr>& nodes = mf_nodes(n, name);
  return nodes.empty() ? nullptr : nodes.front().get();
}

}  // namespace tessera::vrml
