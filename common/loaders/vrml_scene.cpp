// VRML nodes to the Scene (docs/VRML.md has the mapping): a walk down the node tree keeping the
// current transform, as the SDL loader keeps its CT.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <unordered_set>
#include <variant>
#include <vector>

#include "common/image/decoded_texture.h"
#include "common/loaders/vrml_fields.h"
#include "common/loaders/vrml_lexer.h"
#include "common/loaders/vrml_loader.h"
#include "common/loaders/vrml_mesh.h"
#include "common/loaders/vrml_parser.h"
#include "common/math/portable_math.h"

namespace tessera {
namespace vrml {
namespace {

double degrees(double radians) { return radians * 180 / std::numbers::pi; }

Rgb clamp_unit(const Rgb& c) {
  return {std::clamp(c.r, 0.0, 1.0), std::clamp(c.g, 0.0, 1.0), std::clamp(c.b, 0.0, 1.0)};
}

// "ROUTE (3), TimeSensor (1)"
std::string listing(const std::map<std::string, int>& counts) {
  std::string out;
  for (const auto& [name, count] : counts)
    out += (out.empty() ? "" : ", ") + name + " (" + std::to_string(count) + ")";
  return out;
}

// A sphere around an object, for framing the camera.
struct BoundingSphere {
  Vec3 centre;
  double radius = 0;
};

class Converter : public ProtoFiles {
 public:
  Converter(const SceneSource& source, const std::string& path, LoadMeter& meter,
            const std::optional<Camera>& camera)
      : source_(source), path_(path), meter_(meter), camera_(camera) {}

  Scene run() {
    const SourceLocation start{path_, 1, 1};
    const ParsedWorld* parsed = parsed_world(path_, start);
    if (!parsed) throw SceneError(start, quoted(path_) + " " + why_unreadable(source_, path_));
    world(*parsed, path_, Affine::identity(), 0);
    finish();
    return std::move(scene_);
  }

 private:
  // ---- Files
  // The world of the file at `path`, read, lexed and parsed once per load however many Inlines
  // name it; null when the source has no such file.
  const ParsedWorld* parsed_world(const std::string& path, const SourceLocation& from) {
    if (const auto known = worlds_.find(path); known != worlds_.end()) return known->second.get();
    if (!being_parsed_.insert(path).second) return nullptr;  // an EXTERNPROTO cycle
    const std::optional<std::string> bytes = read(path, from);
    if (!bytes) {
      being_parsed_.erase(path);
      return nullptr;
    }
    auto parsed = std::make_unique<const ParsedWorld>(
        parse_vrml(lex_vrml(vrml_text(*bytes, path, meter_), path, meter_), meter_, this));
    being_parsed_.erase(path);
    for (const auto& [name, count] : parsed->ignored) ignored_[name] += count;
    for (const auto& [name, count] : parsed->unsupported) unsupported_[name] += count;
    for (const std::string& w : parsed->warnings) scene_.warnings.push_back(w);
    return worlds_.emplace(path, std::move(parsed)).first->second.get();
  }

  // The world of the file an EXTERNPROTO names, as Inline's.
  const ParsedWorld* proto_file(const std::string& from_file, const std::string& url,
                                const SourceLocation& at, std::string& why) override {
    const std::optional<std::string> path = resolve_scene_path(from_file, url);
    if (!path) {
      why = quoted(url) + " names no file";
      return nullptr;
    }
    if (being_parsed_.contains(*path)) {
      why = quoted(*path) + " is being read: the EXTERNPROTO names its own file";
      return nullptr;
    }
    const ParsedWorld* world = parsed_world(*path, at);
    if (!world) why = quoted(*path) + " " + why_unreadable(source_, *path);
    return world;
  }

  // Leaves out a part of the world with a warning, or under --strict stops (leave_out).
  void leave_out(const SourceLocation& where, const std::string& message) {
    vrml::leave_out(meter_.budget(), scene_.warnings, where, message);
  }

  // The file the url `name` of a node in the current file names: nullopt, with `why`, when it
  // is of a scheme the loader does not read or names no file.
  std::optional<std::string> url_path(const std::string& name, std::string& why) const {
    const std::optional<std::string> local = local_path_of_url(name);
    if (!local) {
      why = "the url scheme of " + quoted(name) + " is not read (the loader fetches nothing)";
      return std::nullopt;
    }
    std::optional<std::string> path = resolve_scene_path(file_, *local);
    if (!path) why = quoted(name) + " names no file";
    return path;
  }

  // A file's roots are a group: the Inline's children.
  void world(const ParsedWorld& parsed, const std::string& path, const Affine& ct, int depth) {
    const std::string outer = file_;
    file_ = path;
    group(parsed.roots, ct, depth);
    file_ = outer;
  }

  // The bytes of a file the world names (a world or an image), counted as read; nullopt when
  // there is no such file.
  std::optional<std::string> read(const std::string& path, const SourceLocation& from) {
    std::optional<std::string> bytes = source_.read(path);
    if (!bytes) return bytes;
    const std::uint64_t limit = meter_.budget().max_file_bytes;
    if (bytes->size() > limit)
      meter_.fail(LoadLimit::FileBytes, from,
                  quoted(path) + " is larger than " + std::to_string(limit) + " bytes");
    meter_.add(LoadLimit::BytesRead, bytes->size(), from);
    return bytes;
  }

  static std::string quoted(const std::string& path) { return "'" + path + "'"; }

  // ---- Children of grouping nodes, and what their DirectionalLights light
  // The children of one grouping node. The DirectionalLights among them light only the objects
  // laid down for the group (§6.16), and those of the Billboards inside it, which are laid down
  // after the walk (finish).
  void group(std::span<const NodePtr> nodes, const Affine& ct, int depth) {
    open_groups_.push_back({static_cast<std::uint32_t>(scene_.objects.size()), {}, {}});
    for (const NodePtr& c : nodes) {
      if (!c) continue;  // a node that is not drawn
      // A node walked again (USE, or a file Inlined again) is walked in full each time: count
      // every such visit, so that a DAG that doubles at every level stops at once.
      if (!visited_.insert(c.get()).second) meter_.add(LoadLimit::UseReplays, 1, c->where);
      const std::size_t lights = scene_.lights.size();
      child(*c, ct, depth);
      if (c->type == "DirectionalLight" && scene_.lights.size() > lights)
        open_groups_.back().lights.push_back(lights);
    }
    close_group();
  }

  // Scopes the closing group's DirectionalLights to its objects, hands them down to the
  // Billboards inside it, and those Billboards up to the enclosing group, whose lights they
  // inherit as well.
  void close_group() {
    const OpenGroup closing = std::move(open_groups_.back());
    open_groups_.pop_back();
    const ObjectRange range{closing.first_object,
                            static_cast<std::uint32_t>(scene_.objects.size())};
    for (const std::size_t light : closing.lights) scene_.lights[light].scope.push_back(range);
    for (const std::size_t b : closing.billboards) {
      std::vector<std::size_t>& inherited = billboards_[b].lights;
      inherited.insert(inherited.end(), closing.lights.begin(), closing.lights.end());
    }
    if (!open_groups_.empty()) {
      std::vector<std::size_t>& outer = open_groups_.back().billboards;
      outer.insert(outer.end(), closing.billboards.begin(), closing.billboards.end());
    }
  }

  void child(const Node& n, const Affine& ct, int depth) {
    const std::string& t = n.type;
    if (t == "Transform") {
      group(mf_nodes(n, "children"), ct * transform(n), depth);
    } else if (t == "Group" || t == "Anchor" || t == "Collision") {
      group(mf_nodes(n, "children"), ct, depth);
    } else if (t == "Billboard") {
      if (!open_groups_.empty()) open_groups_.back().billboards.push_back(billboards_.size());
      billboards_.push_back({&n, ct, depth, file_, {}});  // turned once the camera is known
    } else if (t == "Switch") {
      const std::vector<NodePtr>& choice = mf_nodes(n, "choice");
      const double which = sf_float(n, "whichChoice", -1);
      // The index counts every child, also those that are not drawn (null).
      if (which >= 0 && which < static_cast<double>(choice.size()))
        group(std::span(choice).subspan(static_cast<std::size_t>(which), 1), ct, depth);
    } else if (t == "LOD") {
      const std::vector<NodePtr>& levels = mf_nodes(n, "level");
      group(std::span(levels).first(std::min<std::size_t>(levels.size(), 1)), ct,
            depth);  // the most detailed level
    } else if (t == "Inline") {
      inline_world(n, ct, depth);
    } else if (t == "Shape") {
      shape(n, ct);
    } else if (t == "DirectionalLight" || t == "PointLight" || t == "SpotLight") {
      light(n, ct);
    } else if (depth > 0 &&
               (t == "Viewpoint" || t == "NavigationInfo" || t == "Background" || t == "Fog")) {
      // Bindable nodes of Inlined files are not bound at load (§4.6.10, §6.53).
    } else if (t == "Viewpoint") {
      // The first is bound and must give a view; a later one that gives none is not listed.
      const std::optional<Camera> camera = viewpoint(n, ct);
      if (!viewpoint_ && !camera)
        throw SceneError(n.where, "Viewpoint: the transform leaves the view no direction");
      if (!viewpoint_) viewpoint_ = camera;
      if (camera) scene_.viewpoints.push_back({viewpoint_name(n), *camera});
    } else if (t == "NavigationInfo") {
      if (!headlight_) headlight_ = sf_bool(n, "headlight", true);
    } else if (t == "Background") {
      if (!background_seen_) background(n, ct);
    } else if (t == "Fog") {
      if (!fog_seen_) fog(n);
    } else {
      throw SceneError(n.where, quoted(t) + " is not a child node: it belongs in a " +
                                    "field of a Shape, Appearance or geometry node");
    }
  }

  // Transform (§6.52): T * C * R * SR * S * -SR * -C.
  static Affine transform(const Node& n) {
    const Vec3 center = sf_vec3(n, "center", {});
    const Affine scale_orientation = sf_rotation(n, "scaleOrientation");
    const Affine undo_orientation = scale_orientation.inverse().value_or(Affine::identity());
    return Affine::translation(sf_vec3(n, "translation", {})) * Affine::translation(center) *
           sf_rotation(n, "rotation") * scale_orientation *
           Affine::scaling(sf_vec3(n, "scale", {1, 1, 1})) * undo_orientation *
           Affine::translation(-center);
  }

  void inline_world(const Node& n, const Affine& ct, int depth) {
    const FieldValue* url = n.field("url");
    if (!url) return;
    const std::uint64_t max_depth = meter_.budget().max_inline_depth;
    if (static_cast<std::uint64_t>(depth) + 1 > max_depth)
      meter_.fail(LoadLimit::InlineDepth, n.where,
                  "Inlines nest deeper than " + std::to_string(max_depth));
    std::string why = "it has no url";  // of the last url that could not be read
    for (const std::string& name : url->strings) {
      const std::optional<std::string> path = url_path(name, why);
      if (!path) continue;
      if (const ParsedWorld* parsed = parsed_world(*path, n.where)) {
        meter_.add(LoadLimit::InlineExpansions, 1, n.where);
        world(*parsed, *path, ct, depth + 1);
        return;
      }
      why = quoted(*path) + " " + why_unreadable(source_, *path);
    }
    leave_out(n.where, "Inline: " + why + ": left out");
  }

  // ---- Shapes
  void shape(const Node& n, const Affine& ct) {
    const Node* geometry = sf_node(n, "geometry");
    if (!geometry) return;
    const Node* look = sf_node(n, "appearance");
    const Material material = appearance(look);
    const std::string& t = geometry->type;
    if (t == "Sphere") {
      // Turned so that the texture's poles lie on y, as VRML's do, and its s = 0 (on +x) at
      // -z, wrapping counter-clockwise seen from +y (§6.44).
      const double r = sf_float(*geometry, "radius", 1);
      add(Sphere{},
          ct * Affine::scaling({r, r, r}) * *Affine::rotation(-90, {1, 0, 0}) *
              *Affine::rotation(90, {0, 0, 1}),
          material, *geometry);
    } else if (t == "Box") {
      add(Cube{}, ct * Affine::scaling(sf_vec3(*geometry, "size", {2, 2, 2}) * 0.5), material,
          *geometry);
    } else if (t == "Cone" || t == "Cylinder") {
      const bool cone = t == "Cone";
      TaperedCylinder shape{cone ? 0.0 : 1.0,
                            false,
                            sf_bool(*geometry, "side", true),
                            sf_bool(*geometry, "bottom", true),
                            !cone && sf_bool(*geometry, "top", true),
                            /*vrml_texture=*/true};
      // With a part left out the inside shows: light it as well.
      Material m = material;
      if (!shape.wall || !shape.base_cap || (!cone && !shape.top_cap)) m.light_back_faces = true;
      const double r = sf_float(*geometry, cone ? "bottomRadius" : "radius", 1);
      add(shape, ct * along_y(r, sf_float(*geometry, "height", 2)), m, *geometry);
    } else if (t == "IndexedFaceSet" || t == "ElevationGrid" || t == "Extrusion") {
      face_set(*geometry, ct, material, look ? sf_node(*look, "material") : nullptr);
    } else {
      throw SceneError(geometry->where, quoted(t) + " is not a geometry node");
    }
  }

  // Our tapered cylinder stands on z in [0, 1]; VRML's Cone and Cylinder are centred on the
  // origin along y. Scale to radius and height, turn z to y, and centre.
  static Affine along_y(double radius, double height) {
    return Affine::translation({0, -height / 2, 0}) * *Affine::rotation(-90, {1, 0, 0}) *
           Affine::scaling({radius, radius, height});
  }

  // IndexedFaceSet, ElevationGrid, Extrusion: a mesh. Its texture coordinates are made when
  // the shape has an image texture, and its colours (Color) when it has none or an intensity
  // texture on a lit shape, since an RGB texture replaces them and an intensity texture
  // modulates them (§4.14.2); they replace the diffuse colour as a texture does.
  void face_set(const Node& n, const Affine& ct, Material material, const Node* material_node) {
    // A face set that is not solid may be seen from behind: light both faces.
    if (!sf_bool(n, "solid", true)) material.light_back_faces = true;
    CornerAttributes wanted;
    wanted.tex_coords = material.flat_texture.kind == FlatTexture::Kind::Image;
    const bool modulated =
        wanted.tex_coords && material_node && images_.at(material.flat_texture.image_file);
    wanted.colours = (!wanted.tex_coords || modulated) && sf_node(n, "color");
    if (wanted.colours) {
      replace_diffuse(material_node, material);
      material.corner_colours_decal = !material_node;
    }
    auto [mesh_index, smooth] = mesh(n, wanted);
    if (mesh_index) add(MeshShape{*mesh_index, smooth}, ct, material, n);
  }

  // The mesh of a face set node with the wanted corner attributes, made once per node and
  // attributes however often USE repeats it.
  std::pair<std::optional<std::size_t>, bool> mesh(const Node& n, CornerAttributes wanted) {
    if (const auto made = meshes_.find({&n, wanted}); made != meshes_.end()) return made->second;
    NodePtr generated;
    if (n.type == "ElevationGrid" || n.type == "Extrusion") {
      // Their meshes grow with the product of two fields' sizes: check before making them.
      meter_.ensure_room(LoadLimit::Triangles, generated_triangles(n), n.where);
      generated = n.type == "ElevationGrid" ? elevation_grid_face_set(n) : extrusion_face_set(n);
    }
    FaceSetMesh made = face_set_mesh(generated ? *generated : n, wanted);
    meter_.add_mesh(made.mesh, n.where);
    std::pair<std::optional<std::size_t>, bool> out{std::nullopt, made.smooth};
    if (!made.mesh.triangles.empty()) {
      out.first = scene_.meshes.size();
      scene_.meshes.push_back(std::move(made.mesh));
    }
    meshes_[{&n, wanted}] = out;
    return out;
  }

  void add(const ShapeGeometry& geometry, const Affine& to_world, const Material& material,
           const Node& at) {
    meter_.add_object(at.where);
    scene_.objects.push_back({geometry, to_world, material, at.where, std::nullopt});
  }

  // Material (§6.27) onto the lighting model of §4.1 (docs/VRML.md): without one, a shape is
  // unlit and white.
  Material appearance(const Node* node) {
    const Node* m = node ? sf_node(*node, "material") : nullptr;
    Material out;
    if (!m) {
      out.emissive = {1, 1, 1};
      out.ambient = out.diffuse = out.specular = {};
    } else {
      const Rgb diffuse = sf_color(*m, "diffuseColor", {0.8, 0.8, 0.8});
      out.diffuse = diffuse;
      out.ambient = diffuse * sf_float(*m, "ambientIntensity", 0.2);
      out.emissive = sf_color(*m, "emissiveColor", {});
      out.specular = sf_color(*m, "specularColor", {});
      out.specular_exponent = sf_float(*m, "shininess", 0.2) * 128;
      out.transparency = std::clamp(sf_float(*m, "transparency", 0), 0.0, 1.0);
    }
    if (const Node* t = node ? sf_node(*node, "texture") : nullptr) {
      texture(*t, m, out);
      out.flat_texture.transform = texture_transform(sf_node(*node, "textureTransform"));
    }
    return out;
  }

  // A colour that replaces the diffuse colour (an RGB texture, Color) modulates a white
  // material; with no material the shape is unlit and the colour shows as it is (a decal), so
  // the material's own white glow goes.
  static void replace_diffuse(const Node* material, Material& out) {
    if (material) {
      out.ambient = Rgb::gray(sf_float(*material, "ambientIntensity", 0.2));
      out.diffuse = {1, 1, 1};
    } else {
      out.emissive = {};
    }
  }

  // TextureTransform (§6.48): Tc' = -C x S x R x C x T x Tc, as the rows of a 2D affine map
  // (FlatTexture::transform). No node: the identity, so that coordinates beyond [0, 1] repeat
  // the texture.
  // One or two channels (intensity, and alpha): an image that modulates the colour under it.
  // Nullopt for bytes that cannot be opened as an image.
  static std::optional<bool> is_intensity_image(const std::string& bytes, const std::string& path) {
    try {
      return texture_channels(bytes, path) <= 2;
    } catch (const std::runtime_error&) {
      return std::nullopt;
    }
  }

  static std::array<double, 6> texture_transform(const Node* n) {
    if (!n) return {1, 0, 0, 0, 1, 0};
    const auto [cs, ct] = sf_vec2(*n, "center", {0, 0});
    const auto [ss, st] = sf_vec2(*n, "scale", {1, 1});
    const auto [ts, tt] = sf_vec2(*n, "translation", {0, 0});
    const double angle = sf_float(*n, "rotation", 0);
    const auto [sin_a, cos_a] = tessera::sincos(angle);
    // The linear part S R takes Tc + T + C; then less C.
    const double a = ss * cos_a, b = -ss * sin_a, d = st * sin_a, e = st * cos_a;
    const double us = ts + cs, ut = tt + ct;
    return {a, b, a * us + b * ut - cs, d, e, d * us + e * ut - ct};
  }

  // ImageTexture (§6.22) with the shape's own texture mapping (texture_coordinates.h) or a
  // face set's texture coordinates. An RGB texture replaces the diffuse colour; on a lit
  // shape, an intensity texture modulates it (§4.14.2).
  void texture(const Node& t, const Node* material, Material& out) {
    if (t.type != "ImageTexture") return;  // PixelTexture, MovieTexture: listed as not rendered
    std::string why = "it has no url";     // of the last url that could not be read
    for (const std::string& name :
         t.field("url") ? t.field("url")->strings : std::vector<std::string>{}) {
      const std::optional<std::string> path = url_path(name, why);
      if (!path) continue;
      if (!images_.contains(*path)) {  // read once, however many shapes it textures
        std::optional<std::string> bytes = read(*path, t.where);
        if (!bytes) {
          why = quoted(*path) + " " + why_unreadable(source_, *path);
          continue;
        }
        const std::optional<bool> intensity = is_intensity_image(*bytes, *path);
        if (!intensity) {
          why = quoted(*path) + " is not an image this loader can decode";
          continue;
        }
        meter_.add_texture(bytes->size(), texture_pixels(*bytes, *path), t.where);
        images_[*path] = *intensity;
        scene_.images.push_back({*path, std::move(*bytes), t.where});
      }
      FlatTexture& flat = out.flat_texture;
      flat.kind = FlatTexture::Kind::Image;
      flat.image_file = *path;
      flat.decal = !material;
      if (!(images_[*path] && material)) replace_diffuse(material, out);
      flat.clamp_s = !sf_bool(t, "repeatS", true);
      flat.clamp_t = !sf_bool(t, "repeatT", true);
      return;
    }
    leave_out(t.where, "ImageTexture: " + why + ": the shape is drawn untextured");
  }

  // ---- Lights (§6.16, §6.36, §6.43)
  void light(const Node& n, const Affine& ct) {
    if (!sf_bool(n, "on", true)) return;
    meter_.add_light(n.where);
    const double intensity = std::clamp(sf_float(n, "intensity", 1), 0.0, 1.0);
    const Rgb color = sf_color(n, "color", {1, 1, 1}) * intensity;
    ambient_ += color * std::clamp(sf_float(n, "ambientIntensity", 0), 0.0, 1.0);
    Light out;
    out.color = color;
    if (n.type == "DirectionalLight") {
      out.is_directional = true;
      out.direction = unit_or_zero(ct.apply_vector(sf_vec3(n, "direction", {0, 0, -1})));
      if (out.direction == Vec3{}) throw SceneError(n.where, "DirectionalLight: zero direction");
    } else {
      out.position = ct.apply_point(sf_vec3(n, "location", {}));
      const Vec3 a = sf_vec3(n, "attenuation", {1, 0, 0});
      if (!(LightAttenuation{a.x, a.y, a.z}).is_identity()) out.attenuation = {a.x, a.y, a.z};
      // The radius is in the light's coordinates; under a non-uniform scale the sphere it
      // bounds becomes an ellipsoid, taken here as the sphere around it (never too short).
      const double radius = sf_float(n, "radius", 100);
      if (radius < 0) throw SceneError(n.where, n.type + ": radius must not be negative");
      out.radius =
          radius * std::max({length(ct.apply_vector({1, 0, 0})), length(ct.apply_vector({0, 1, 0})),
                             length(ct.apply_vector({0, 0, 1}))});
    }
    if (n.type == "SpotLight") {
      out.is_spot = true;
      out.spot.direction = unit_or_zero(ct.apply_vector(sf_vec3(n, "direction", {0, 0, -1})));
      if (out.spot.direction == Vec3{}) throw SceneError(n.where, "SpotLight: zero direction");
      const double cutoff =
          std::clamp(sf_float(n, "cutOffAngle", 0.785398), 1e-6, std::numbers::pi / 2);
      const double beam = std::clamp(sf_float(n, "beamWidth", 1.570796), 0.0, cutoff);
      out.spot.cutoff_degrees = degrees(cutoff);
      // Full intensity inside beamWidth falling linearly to zero at cutOffAngle, approximated
      // by cos^e with half intensity halfway between them (docs/VRML.md).
      if (beam < cutoff) {
        const double halfway = tessera::cos((beam + cutoff) / 2);
        out.spot.exponent = tessera::log(0.5) / tessera::log(halfway);
      }
    }
    scene_.lights.push_back(out);
  }

  // ---- Bindable nodes: the first of each kind counts (§4.6.10)
  // Nullopt when the transform leaves the view no direction.
  static std::optional<Camera> viewpoint(const Node& n, const Affine& ct) {
    const Affine orientation = sf_rotation(n, "orientation");
    Camera camera;
    camera.eye = ct.apply_point(sf_vec3(n, "position", {0, 0, 10}));
    camera.look_at =
        camera.eye + unit_or_zero(ct.apply_vector(orientation.apply_vector({0, 0, -1})));
    camera.up = ct.apply_vector(orientation.apply_vector({0, 1, 0}));
    camera.view_angle = degrees(std::clamp(sf_float(n, "fieldOfView", 0.785398), 1e-6, 3.14159));
    camera.view_angle_on_smaller_side = true;
    if (camera.look_at == camera.eye || camera_right(camera, view_direction(camera)) == Vec3{})
      return std::nullopt;
    return camera;
  }

  // What a page lists it as: its description, else where it is.
  static std::string viewpoint_name(const Node& n) {
    const FieldValue* description = n.field("description");
    if (description && !description->strings.empty() && !description->strings[0].empty())
      return description->strings[0];
    return n.where.to_string();
  }

  // Background (§6.5): skyColor[0] everywhere, or, given sky or ground angles, the gradient
  // about the Background's +y. Colours beyond one per angle and one more are ignored, as are
  // angles beyond them.
  void background(const Node& n, const Affine& ct) {
    background_seen_ = true;
    for (const char* url : {"backUrl", "bottomUrl", "frontUrl", "leftUrl", "rightUrl", "topUrl"})
      if (const FieldValue* v = n.field(url); v && !v->strings.empty()) {
        ++unsupported_["Background panorama"];
        break;
      }
    SkyGradient sky;
    sky.up = unit_or_zero(ct.apply_vector({0, 1, 0}));
    sky.sky_colours = colours(n, "skyColor");
    if (sky.sky_colours.empty()) sky.sky_colours.push_back(Rgb{});
    scene_.globals.background = sky.sky_colours.front();
    sky.sky_angles = angles(n, "skyAngle", sky.sky_colours.size() - 1);
    sky.sky_colours.resize(sky.sky_angles.size() + 1);
    sky.ground_colours = colours(n, "groundColor");
    if (!sky.ground_colours.empty()) {
      sky.ground_angles = angles(n, "groundAngle", sky.ground_colours.size() - 1);
      sky.ground_colours.resize(sky.ground_angles.size() + 1);
    }
    if ((!sky.sky_angles.empty() || !sky.ground_angles.empty()) && sky.up != Vec3{})
      scene_.globals.sky = sky;
  }

  static std::vector<Rgb> colours(const Node& n, const char* field) {
    const std::vector<double>& numbers = mf_numbers(n, field);
    std::vector<Rgb> out;
    for (std::size_t i = 0; i + 2 < numbers.size(); i += 3)
      out.push_back({numbers[i], numbers[i + 1], numbers[i + 2]});
    return out;
  }

  // At most `count` angles of the field, in radians: increasing, within [0, pi].
  static std::vector<double> angles(const Node& n, const char* field, std::size_t count) {
    const std::vector<double>& all = mf_numbers(n, field);
    std::vector<double> out(all.begin(),
                            all.begin() + static_cast<std::ptrdiff_t>(std::min(count, all.size())));
    for (std::size_t i = 0; i < out.size(); ++i)
      if (!(out[i] >= (i == 0 ? 0 : out[i - 1]) && out[i] <= std::numbers::pi))
        throw SceneError(n.field(field)->where, std::string("Background: ") + field +
                                                    " must increase from 0 to at most pi");
    return out;
  }

  void fog(const Node& n) {
    fog_seen_ = true;
    const double range = sf_float(n, "visibilityRange", 0);
    if (range <= 0) return;
    const FieldValue* type = n.field("fogType");
    Fog fog{0, range, sf_color(n, "color", {1, 1, 1})};
    fog.exponential = type && !type->strings.empty() && type->strings[0] == "EXPONENTIAL";
    scene_.globals.fog = fog;
  }

  // ---- After the walk: camera, headlight, ambient light, warnings
  void finish() {
    SceneGlobals& g = scene_.globals;
    g.global_ambient = clamp_unit(ambient_);
    if (camera_) {
      scene_.camera = *camera_;
      scene_.camera.view_angle_on_smaller_side = true;
    } else {
      scene_.camera = viewpoint_ ? *viewpoint_ : framing_camera(billboard_spheres());
    }
    // Billboards nested in billboards are turned as they come: this loop sees them appended.
    // Each is walked inside a group holding the DirectionalLights it inherited from the groups
    // around it, so that they light its objects too.
    for (std::size_t i = 0; i < billboards_.size(); ++i) {
      const Billboard b = billboards_[i];  // a copy: the walk may append
      file_ = b.file;
      open_groups_.push_back({static_cast<std::uint32_t>(scene_.objects.size()), b.lights, {}});
      group(mf_nodes(*b.node, "children"), b.ct * billboard_turn(*b.node, b.ct), b.depth);
      close_group();
    }
    if (headlight_.value_or(true)) {
      Light headlight;  // along the view, intensity 1, ambientIntensity 0 (§6.29)
      headlight.is_directional = true;
      headlight.direction = view_direction(scene_.camera);
      // A browser's headlight casts no shadow; traced ones would fringe foreground objects.
      headlight.casts_shadows = false;
      scene_.lights.push_back(headlight);
    }
    if (!ignored_.empty())
      scene_.warnings.push_back(path_ +
                                ": ignored (a still image has no animation, sensing or "
                                "sound): " +
                                listing(ignored_));
    if (!unsupported_.empty())
      scene_.warnings.push_back(path_ + ": not rendered (yet): " + listing(unsupported_));
  }

  // For framing a world without a Viewpoint, before the Billboards can be turned: about each
  // Billboard's origin, the sphere that holds its children however it turns (exactly under a
  // uniform scale). Its children are laid down unturned, measured, and taken away again.
  std::vector<BoundingSphere> billboard_spheres() {
    const std::size_t objects = scene_.objects.size(), lights = scene_.lights.size(),
                      billboards = billboards_.size(), warnings = scene_.warnings.size();
    std::vector<BoundingSphere> out;
    for (std::size_t i = 0; i < billboards_.size(); ++i) {  // nested ones are appended
      const Billboard b = billboards_[i];
      const std::size_t first = scene_.objects.size();
      file_ = b.file;
      group(mf_nodes(*b.node, "children"), b.ct, b.depth);
      BoundingSphere around{b.ct.apply_point({}), 0};
      for (std::size_t k = first; k < scene_.objects.size(); ++k) {
        const BoundingSphere part = bounding_sphere(scene_.objects[k]);
        around.radius = std::max(around.radius, length(part.centre - around.centre) + part.radius);
      }
      if (scene_.objects.size() > first) out.push_back(around);
    }
    scene_.objects.erase(scene_.objects.begin() + static_cast<std::ptrdiff_t>(objects),
                         scene_.objects.end());
    scene_.lights.erase(scene_.lights.begin() + static_cast<std::ptrdiff_t>(lights),
                        scene_.lights.end());
    billboards_.erase(billboards_.begin() + static_cast<std::ptrdiff_t>(billboards),
                      billboards_.end());
    scene_.warnings.erase(scene_.warnings.begin() + static_cast<std::ptrdiff_t>(warnings),
                          scene_.warnings.end());
    return out;
  }

  // Billboard (§6.6): the turn about axisOfRotation that points the children's +z at the eye;
  // with a zero axis, +z at the eye and +y along the camera's up.
  Affine billboard_turn(const Node& n, const Affine& ct) const {
    const std::optional<Affine> to_local = ct.inverse();
    if (!to_local) return Affine::identity();
    const Vec3 eye = unit_or_zero(to_local->apply_point(scene_.camera.eye));
    const Vec3 axis = unit_or_zero(sf_vec3(n, "axisOfRotation", {0, 1, 0}));
    if (axis == Vec3{}) {
      const Vec3 up = to_local->apply_vector(scene_.camera.up);
      const Vec3 x = unit_or_zero(cross(up, eye));
      if (eye == Vec3{} || x == Vec3{}) return Affine::identity();
      return Affine::from_columns(x, cross(eye, x), eye);
    }
    const Vec3 z = Vec3{0, 0, 1} - axis * axis.z;  // +z and the eye, across the axis
    const Vec3 towards = eye - axis * dot(eye, axis);
    if (unit_or_zero(z) == Vec3{} || unit_or_zero(towards) == Vec3{}) return Affine::identity();
    const double angle = tessera::atan2(dot(axis, cross(z, towards)), dot(z, towards));
    return Affine::rotation(degrees(angle), axis).value_or(Affine::identity());
  }

  // No Viewpoint: look at the centre of the world's bounds (its objects' and `spheres`, the
  // Billboards') down -z, from the distance at which their bounding sphere fills the field of
  // view (`000_…` §4.4.2). An empty world gets VRML's default Viewpoint.
  Camera framing_camera(std::vector<BoundingSphere> spheres) const {
    Camera camera;
    camera.eye = {0, 0, 10};
    camera.look_at = {0, 0, 0};
    camera.view_angle = 45;
    camera.view_angle_on_smaller_side = true;
    for (const SceneObject& object : scene_.objects) spheres.push_back(bounding_sphere(object));
    if (spheres.empty()) return camera;
    Vec3 lo{kHuge, kHuge, kHuge}, hi = -lo;
    for (const BoundingSphere& s : spheres) {
      lo = min(lo, s.centre - Vec3{s.radius, s.radius, s.radius});
      hi = max(hi, s.centre + Vec3{s.radius, s.radius, s.radius});
    }
    const Vec3 centre = (lo + hi) * 0.5;
    double radius = 0;
    for (const BoundingSphere& s : spheres)
      radius = std::max(radius, length(s.centre - centre) + s.radius);
    if (!(radius > 0)) radius = 1;
    const double distance = radius / tessera::sin(camera.view_angle * std::numbers::pi / 360);
    camera.look_at = centre;
    camera.eye = centre + Vec3{0, 0, distance};
    return camera;
  }

  static constexpr double kHuge = 1e300;

  // Takes time in the object's vertices, whatever the budget counted for its mesh (one USEd
  // mesh of many vertices is measured once per object): so it watches the load's deadline.
  BoundingSphere bounding_sphere(const SceneObject& object) const {
    meter_.check_time(object.where);
    const Affine& m = object.transform;
    std::vector<Vec3> points;  // in object space
    if (const auto* shape = std::get_if<MeshShape>(&object.geometry)) {
      points = scene_.meshes[shape->mesh].positions;
    } else if (std::holds_alternative<Sphere>(object.geometry)) {
      // The unit sphere's image is an ellipsoid within the largest column's length.
      const Vec3 c = m.apply_point({});
      double r = 0;
      for (const Vec3& axis : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}})
        r = std::max(r, length(m.apply_vector(axis)));
      return {c, r};
    } else {
      const double z0 = std::holds_alternative<Cube>(object.geometry) ? -1 : 0;
      for (const double x : {-1.0, 1.0})
        for (const double y : {-1.0, 1.0})
          for (const double z : {z0, 1.0}) points.push_back({x, y, z});
    }
    Vec3 lo{kHuge, kHuge, kHuge}, hi = -lo;
    for (Vec3& p : points) {
      p = m.apply_point(p);
      lo = min(lo, p);
      hi = max(hi, p);
    }
    BoundingSphere out{(lo + hi) * 0.5, 0};
    for (const Vec3& p : points) out.radius = std::max(out.radius, length(p - out.centre));
    return out;
  }

  const SceneSource& source_;
  const std::string path_;
  LoadMeter& meter_;
  const std::optional<Camera> camera_;  // the camera setting, bound in place of a Viewpoint
  // Every file's parsed world by path, alive for the whole conversion: Billboards and the mesh
  // cache hold nodes by address until the end.
  std::map<std::string, std::unique_ptr<const ParsedWorld>> worlds_;
  std::set<std::string> being_parsed_;       // files whose parse has not finished
  std::unordered_set<const Node*> visited_;  // nodes the walk has been through
  std::string file_;                         // the file being converted, for resolving Inline urls
  Scene scene_;
  std::map<std::string, int> ignored_, unsupported_;
  struct Billboard {
    const Node* node;
    Affine ct;
    int depth;
    std::string file;
    std::vector<std::size_t> lights;  // DirectionalLights of the groups around it
  };
  std::vector<Billboard> billboards_;
  // The grouping nodes being walked, innermost last: where their objects begin, their
  // DirectionalLights (in Scene::lights) and the Billboards inside them (in billboards_).
  struct OpenGroup {
    std::uint32_t first_object;
    std::vector<std::size_t> lights, billboards;
  };
  std::vector<OpenGroup> open_groups_;
  std::map<std::string, bool> images_;  // in Scene::images: whether an intensity image
  std::map<std::pair<const Node*, CornerAttributes>, std::pair<std::optional<std::size_t>, bool>>
      meshes_;
  std::optional<Camera> viewpoint_;
  std::optional<bool> headlight_;
  bool background_seen_ = false;
  bool fog_seen_ = false;
  Rgb ambient_;
};

}  // namespace
}  // namespace vrml

Scene load_vrml(const SceneSource& source, const std::string& path, const LoadBudget& budget,
                const std::optional<Camera>& camera) {
  LoadMeter meter(budget);
  return vrml::Converter(source, path, meter, camera).run();
}

}  // namespace tessera
