#include "common/loaders/vrml_nodes.h"

#include <array>
#include <utility>

namespace tessera::vrml {
namespace {

constexpr std::array<std::pair<std::string_view, FieldType>, 20> kFieldTypes{{
    {"SFBool", FieldType::SFBool},     {"SFInt32", FieldType::SFInt32},
    {"SFFloat", FieldType::SFFloat},   {"SFTime", FieldType::SFTime},
    {"SFVec2f", FieldType::SFVec2f},   {"SFVec3f", FieldType::SFVec3f},
    {"SFColor", FieldType::SFColor},   {"SFRotation", FieldType::SFRotation},
    {"SFString", FieldType::SFString}, {"SFNode", FieldType::SFNode},
    {"MFBool", FieldType::MFBool},     {"MFInt32", FieldType::MFInt32},
    {"MFFloat", FieldType::MFFloat},   {"MFTime", FieldType::MFTime},
    {"MFVec2f", FieldType::MFVec2f},   {"MFVec3f", FieldType::MFVec3f},
    {"MFColor", FieldType::MFColor},   {"MFRotation", FieldType::MFRotation},
    {"MFString", FieldType::MFString}, {"MFNode", FieldType::MFNode},
}};

using enum FieldType;

// Fields shared by the grouping nodes.
// The fields every grouping node has.
std::vector<FieldSpec> grouping(std::vector<FieldSpec> fields) {
  fields.insert(fields.end(), {{"bboxCenter", SFVec3f}, {"bboxSize", SFVec3f}});
  return fields;
}

// The fields every face set (IndexedFaceSet, ElevationGrid, Extrusion) has.
std::vector<FieldSpec> face_set(std::vector<FieldSpec> fields) {
  fields.insert(fields.end(), {{"ccw", SFBool}, {"solid", SFBool}, {"creaseAngle", SFFloat}});
  return fields;
}

// The node types of ISO/IEC 14772-1 §6 with the fields a file may give (exposedFields and
// fields; eventIns and eventOuts take no value). One line per type.
const std::vector<NodeSpec>& node_specs() {
  static const std::vector<NodeSpec> specs = {
      // Grouping
      {"Transform", NodeRole::Rendered,
       grouping({{"center", SFVec3f},
                 {"children", MFNode},
                 {"rotation", SFRotation},
                 {"scale", SFVec3f},
                 {"scaleOrientation", SFRotation},
                 {"translation", SFVec3f}})},
      {"Group", NodeRole::Rendered, grouping({{"children", MFNode}})},
      {"Anchor", NodeRole::Rendered,
       grouping({{"children", MFNode},
                 {"description", SFString},
                 {"parameter", MFString},
                 {"url", MFString}})},
      {"Collision", NodeRole::Rendered,
       grouping({{"children", MFNode}, {"collide", SFBool}, {"proxy", SFNode}})},
      {"Billboard", NodeRole::Rendered,
       grouping({{"axisOfRotation", SFVec3f}, {"children", MFNode}})},
      {"Switch", NodeRole::Rendered, {{"choice", MFNode}, {"whichChoice", SFInt32}}},
      {"LOD", NodeRole::Rendered, {{"level", MFNode}, {"center", SFVec3f}, {"range", MFFloat}}},
      {"Inline", NodeRole::Rendered, grouping({{"url", MFString}})},
      // Shapes and their properties
      {"Shape", NodeRole::Rendered, {{"appearance", SFNode}, {"geometry", SFNode}}},
      {"Appearance",
       NodeRole::Rendered,
       {{"material", SFNode}, {"texture", SFNode}, {"textureTransform", SFNode}}},
      {"Material",
       NodeRole::Rendered,
       {{"ambientIntensity", SFFloat},
        {"diffuseColor", SFColor},
        {"emissiveColor", SFColor},
        {"shininess", SFFloat},
        {"specularColor", SFColor},
        {"transparency", SFFloat}}},
      {"ImageTexture",
       NodeRole::Rendered,
       {{"url", MFString}, {"repeatS", SFBool}, {"repeatT", SFBool}}},
      {"TextureTransform",
       NodeRole::Rendered,
       {{"center", SFVec2f}, {"rotation", SFFloat}, {"scale", SFVec2f}, {"translation", SFVec2f}}},
      {"Box", NodeRole::Rendered, {{"size", SFVec3f}}},
      {"Sphere", NodeRole::Rendered, {{"radius", SFFloat}}},
      {"Cone",
       NodeRole::Rendered,
       {{"bottomRadius", SFFloat}, {"height", SFFloat}, {"side", SFBool}, {"bottom", SFBool}}},
      {"Cylinder",
       NodeRole::Rendered,
       {{"bottom", SFBool},
        {"height", SFFloat},
        {"radius", SFFloat},
        {"side", SFBool},
        {"top", SFBool}}},
      {"IndexedFaceSet", NodeRole::Rendered,
       face_set({{"color", SFNode},
                 {"coord", SFNode},
                 {"normal", SFNode},
                 {"texCoord", SFNode},
                 {"colorIndex", MFInt32},
                 {"colorPerVertex", SFBool},
                 {"convex", SFBool},
                 {"coordIndex", MFInt32},
                 {"normalIndex", MFInt32},
                 {"normalPerVertex", SFBool},
                 {"texCoordIndex", MFInt32}})},
      {"ElevationGrid", NodeRole::Rendered,
       face_set({{"color", SFNode},
                 {"normal", SFNode},
                 {"texCoord", SFNode},
                 {"height", MFFloat},
                 {"colorPerVertex", SFBool},
                 {"normalPerVertex", SFBool},
                 {"xDimension", SFInt32},
                 {"xSpacing", SFFloat},
                 {"zDimension", SFInt32},
                 {"zSpacing", SFFloat}})},
      {"Extrusion", NodeRole::Rendered,
       face_set({{"beginCap", SFBool},
                 {"endCap", SFBool},
                 {"convex", SFBool},
                 {"crossSection", MFVec2f},
                 {"orientation", MFRotation},
                 {"scale", MFVec2f},
                 {"spine", MFVec3f}})},
      {"Coordinate", NodeRole::Rendered, {{"point", MFVec3f}}},
      {"Normal", NodeRole::Rendered, {{"vector", MFVec3f}}},
      {"Color", NodeRole::Rendered, {{"color", MFColor}}},
      {"TextureCoordinate", NodeRole::Rendered, {{"point", MFVec2f}}},
      // Lights, camera, environment
      {"DirectionalLight",
       NodeRole::Rendered,
       {{"ambientIntensity", SFFloat},
        {"color", SFColor},
        {"direction", SFVec3f},
        {"intensity", SFFloat},
        {"on", SFBool}}},
      {"PointLight",
       NodeRole::Rendered,
       {{"ambientIntensity", SFFloat},
        {"attenuation", SFVec3f},
        {"color", SFColor},
        {"intensity", SFFloat},
        {"location", SFVec3f},
        {"on", SFBool},
        {"radius", SFFloat}}},
      {"SpotLight",
       NodeRole::Rendered,
       {{"ambientIntensity", SFFloat},
        {"attenuation", SFVec3f},
        {"beamWidth", SFFloat},
        {"color", SFColor},
        {"cutOffAngle", SFFloat},
        {"direction", SFVec3f},
        {"intensity", SFFloat},
        {"location", SFVec3f},
        {"on", SFBool},
        {"radius", SFFloat}}},
      {"Viewpoint",
       NodeRole::Rendered,
       {{"fieldOfView", SFFloat},
        {"jump", SFBool},
        {"orientation", SFRotation},
        {"position", SFVec3f},
        {"description", SFString}}},
      {"NavigationInfo",
       NodeRole::Rendered,
       {{"avatarSize", MFFloat},
        {"headlight", SFBool},
        {"speed", SFFloat},
        {"type", MFString},
        {"visibilityLimit", SFFloat}}},
      {"Background",
       NodeRole::Rendered,
       {{"groundAngle", MFFloat},
        {"groundColor", MFColor},
        {"backUrl", MFString},
        {"bottomUrl", MFString},
        {"frontUrl", MFString},
        {"leftUrl", MFString},
        {"rightUrl", MFString},
        {"topUrl", MFString},
        {"skyAngle", MFFloat},
        {"skyColor", MFColor}}},
      {"Fog",
       NodeRole::Rendered,
       {{"color", SFColor}, {"fogType", SFString}, {"visibilityRange", SFFloat}}},
      // Accepted and ignored: they animate, sense or sound, and a still image has none of it.
      {"TimeSensor", NodeRole::NonVisual, {}},
      {"TouchSensor", NodeRole::NonVisual, {}},
      {"ProximitySensor", NodeRole::NonVisual, {}},
      {"VisibilitySensor", NodeRole::NonVisual, {}},
      {"PlaneSensor", NodeRole::NonVisual, {}},
      {"SphereSensor", NodeRole::NonVisual, {}},
      {"CylinderSensor", NodeRole::NonVisual, {}},
      {"PositionInterpolator", NodeRole::NonVisual, {}},
      {"OrientationInterpolator", NodeRole::NonVisual, {}},
      {"ColorInterpolator", NodeRole::NonVisual, {}},
      {"ScalarInterpolator", NodeRole::NonVisual, {}},
      {"CoordinateInterpolator", NodeRole::NonVisual, {}},
      {"NormalInterpolator", NodeRole::NonVisual, {}},
      {"Script", NodeRole::NonVisual, {}},
      {"Sound", NodeRole::NonVisual, {}},
      {"AudioClip", NodeRole::NonVisual, {}},
      {"WorldInfo", NodeRole::NonVisual, {}},
      // Visual, not rendered (yet).
      {"Text", NodeRole::Unsupported, {}},
      {"FontStyle", NodeRole::Unsupported, {}},
      {"PointSet", NodeRole::Unsupported, {}},
      {"IndexedLineSet", NodeRole::Unsupported, {}},
      {"PixelTexture", NodeRole::Unsupported, {}},
      {"MovieTexture", NodeRole::Unsupported, {}},
  };
  return specs;
}

}  // namespace

bool parse_field_type(std::string_view name, FieldType& type) {
  for (const auto& [spelling, t] : kFieldTypes) {
    if (spelling == name) {
      type = t;
      return true;
    }
  }
  return false;
}

bool is_multiple(FieldType type) { return type >= FieldType::MFBool; }

int components(FieldType type) {
  switch (type) {
    case SFVec2f:
    case MFVec2f:
      return 2;
    case SFVec3f:
    case MFVec3f:
    case SFColor:
    case MFColor:
      return 3;
    case SFRotation:
    case MFRotation:
      return 4;
    case SFString:
    case MFString:
    case SFNode:
    case MFNode:
      return 0;
    default:
      return 1;
  }
}

std::size_t FieldValue::size() const {
  const int n = components(type);
  if (n > 0) return numbers.size() / static_cast<std::size_t>(n);
  return type == SFString || type == MFString ? strings.size() : nodes.size();
}

const FieldSpec* NodeSpec::field(std::string_view name) const {
  for (const FieldSpec& f : fields)
    if (f.name == name) return &f;
  return nullptr;
}

const NodeSpec* find_node_spec(std::string_view type) {
  for (const NodeSpec& spec : node_specs())
    if (spec.type == type) return &spec;
  return nullptr;
}

}  // namespace tessera::vrml
