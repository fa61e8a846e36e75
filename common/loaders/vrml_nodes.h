// The VRML node model: a parsed world is a tree (a DAG where USE shares a node) of nodes with
// typed field values, PROTO instances already expanded. Field defaults are applied by whoever
// reads the node (vrml_scene.cpp), so a node holds only the fields the file gave.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "common/scene/source_location.h"

namespace tessera::vrml {

enum class FieldType {
  SFBool,
  SFInt32,
  SFFloat,
  SFTime,
  SFVec2f,
  SFVec3f,
  SFColor,
  SFRotation,
  SFString,
  SFNode,
  MFBool,
  MFInt32,
  MFFloat,
  MFTime,
  MFVec2f,
  MFVec3f,
  MFColor,
  MFRotation,
  MFString,
  MFNode,
};

// The type spelled `name` ("SFVec3f"), or false.
bool parse_field_type(std::string_view name, FieldType& type);
bool is_multiple(FieldType type);
// Numbers per element: 1 for Bool, Int32, Float, Time; 2 for Vec2f; 3 for Vec3f and Color; 4
// for Rotation; 0 for String and Node.
int components(FieldType type);

struct Node;
using NodePtr = std::shared_ptr<const Node>;

struct FieldValue {
  FieldType type = FieldType::SFFloat;
  std::vector<double> numbers;  // every element's components in order (booleans as 0 and 1)
  std::vector<std::string> strings;
  // SFNode NULL is an empty list; in an MFNode, a node that is not drawn (ignored or
  // unsupported) is null, so that the others keep their indices.
  std::vector<NodePtr> nodes;
  SourceLocation where;
  std::size_t size() const;  // elements
};

struct Node {
  std::string type;  // "Transform", "Shape", ...
  SourceLocation where;
  std::map<std::string, FieldValue> fields;
  // In a PROTO body: field name -> the interface field it IS.
  std::map<std::string, std::string> is_links;
  const FieldValue* field(const std::string& name) const {
    const auto found = fields.find(name);
    return found == fields.end() ? nullptr : &found->second;
  }
};

// How the parser treats a node type.
enum class NodeRole {
  Rendered,     // converted to the scene; its fields are checked
  NonVisual,    // sensors, interpolators, scripts, sound: accepted and ignored
  Unsupported,  // visual but not rendered (Text, PointSet, ...): a warning names it
};

struct FieldSpec {
  std::string_view name;
  FieldType type;
};

struct NodeSpec {
  std::string_view type;
  NodeRole role;
  std::vector<FieldSpec> fields;  // for Rendered nodes; the others' fields are skipped
  const FieldSpec* field(std::string_view name) const;
};

// The built-in node type spelled `type` (case-sensitive, as VRML is), or null.
const NodeSpec* find_node_spec(std::string_view type);

}  // namespace tessera::vrml
