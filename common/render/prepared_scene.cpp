#include "common/render/prepared_scene.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "common/texture/image_texture.h"

namespace tessera {

namespace {

CameraFrame make_camera_frame(const Camera& camera) {
  const SourceLocation nowhere{"camera", 0, 0};
  CameraFrame frame;
  frame.eye = camera.eye;
  frame.forward = view_direction(camera);
  if (frame.forward == Vec3{})
    throw SceneError(nowhere, "eyePoint and viewPoint coincide: the view has no direction");
  frame.right = camera_right(camera, frame.forward);
  if (frame.right == Vec3{})
    throw SceneError(nowhere, "upDirection is zero or parallel to the view direction");
  frame.up = cross(frame.right, frame.forward);
  if (!(camera.view_angle > 0 && camera.view_angle < 180))
    throw SceneError(nowhere, "viewAngle must lie strictly between 0 and 180 degrees");
  frame.tan_half_height = std::tan(camera.view_angle * std::numbers::pi / 360);
  frame.angle_on_smaller_side = camera.view_angle_on_smaller_side;
  return frame;
}

// Which effects the scene calls for; anything absent here costs nothing at render time.
EffectSet scene_effects(const Scene& scene) {
  const SceneGlobals& g = scene.globals;
  EffectSet effects;
  if (!scene.lights.empty() && !scene.objects.empty()) effects.add(Effect::HardShadows);
  for (const Light& light : scene.lights) {
    if (light.is_spot) effects.add(Effect::Spotlights);
    if (light.is_directional) effects.add(Effect::DirectionalLight);
  }
  if (!g.light_attenuation.is_identity() && !scene.lights.empty())
    effects.add(Effect::LightAttenuation);
  if (g.atmospheric_attenuation) effects.add(Effect::AtmosphericAttenuation);
  if (g.fog) effects.add(Effect::Fog);
  for (const SceneObject& object : scene.objects) {
    const Material& m = object.material;
    if (g.max_recursion_depth > 0 && m.reflectivity > g.min_reflectivity)
      effects.add(Effect::Reflection);
    if (g.max_recursion_depth > 0 && m.transparency > g.min_transparency)
      effects.add(Effect::Refraction);
    if (m.surface_roughness > 0) effects.add(Effect::SurfaceRoughness);
    if (std::holds_alternative<MeshShape>(object.geometry)) effects.add(Effect::Meshes);
    if (m.solid_texture.type != 0) effects.add(Effect::SolidTexture);
    if (m.flat_texture.kind == FlatTexture::Kind::Image) effects.add(Effect::ImageTexture);
    if (m.flat_texture.kind == FlatTexture::Kind::Procedural)
      effects.add(Effect::ProceduralTexture);
  }
  return effects;
}

// What the scene asks for that this renderer does not simulate yet: said, never dropped.
std::vector<std::string> unsupported_features(const Scene& scene) {
  std::vector<std::string> out;
  auto note = [&out](const std::string& where, const std::string& what) {
    const std::string line = where + ": " + what + " is not rendered yet";
    for (const std::string& seen : out)
      if (seen == line) return;
    out.push_back(line);
  };
  const std::string global = "scene";  // global attributes keep no location
  if (scene.globals.show_extents) note(global, "showExtents");
  if (scene.globals.adapted_shadow_computation) note(global, "adaptedShadowComputation");
  for (const SceneObject& object : scene.objects) {
    const Material& m = object.material;
    if (m.gloss_strength > 0 && m.reflectivity > 0) note(object.where.to_string(), "glossStrength");
    if (m.translucency_strength > 0 && m.transparency > 0)
      note(object.where.to_string(), "translucencyStrength");
  }
  return out;
}

bool has_texture(const EffectSet& effects) {
  return effects.has(Effect::SolidTexture) || effects.has(Effect::ImageTexture) ||
         effects.has(Effect::ProceduralTexture);
}

// Every image file the scene names, decoded once for all rays.
std::vector<Image> decode_images(const Scene& scene) {
  std::vector<Image> images;
  images.reserve(scene.images.size());
  for (const ImageFile& file : scene.images) {
    try {
      images.push_back(decode_image(file.bytes, file.path, kMaxTexturePixels));
    } catch (const std::runtime_error& e) {
      throw SceneError(file.where, e.what());
    }
  }
  return images;
}

ObjectTexture object_texture(const SceneObject& object, const Scene& scene,
                             const std::vector<Image>& images) {
  const Material& m = object.material;
  const Image* image = nullptr;
  for (std::size_t i = 0; i < scene.images.size(); ++i)
    if (scene.images[i].path == m.flat_texture.image_file) image = &images[i];
  if (m.flat_texture.kind == FlatTexture::Kind::Image && image == nullptr)
    throw SceneError(object.where, "image file '" + m.flat_texture.image_file + "' was not read");
  return {make_solid_pattern(m.solid_texture), make_flat_texture(m.flat_texture, image)};
}

// Pairs of transparent objects whose bounds meet: where the tracer looks for coincident
// boundaries (Tracer::cross_interface). Quadratic in the transparent objects only.
std::vector<std::vector<std::uint32_t>> find_transparent_neighbours(
    const Scene& scene, const EffectSet& effects, const std::vector<Bounds3>& bounds) {
  std::vector<std::vector<std::uint32_t>> out(scene.objects.size());
  if (!effects.has(Effect::Refraction)) return out;
  std::vector<std::uint32_t> transparent;
  for (std::uint32_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].material.transparency > scene.globals.min_transparency)
      transparent.push_back(i);
  for (std::size_t a = 0; a < transparent.size(); ++a)
    for (std::size_t b = a + 1; b < transparent.size(); ++b)
      if (bounds[transparent[a]].overlaps(bounds[transparent[b]])) {
        out[transparent[a]].push_back(transparent[b]);
        out[transparent[b]].push_back(transparent[a]);
      }
  return out;
}

}  // namespace

PreparedScene::PreparedScene(const Scene& scene, BvhMode mode)
    : scene_(&scene),
      camera_(make_camera_frame(scene.camera)),
      effects_(scene_effects(scene)),
      unsupported_(unsupported_features(scene)) {
  meshes_.reserve(scene.meshes.size());
  for (const Mesh& mesh : scene.meshes)
    meshes_.push_back(std::make_unique<MeshAccel>(build_mesh_accel(mesh, mode)));

  instances_.reserve(scene.objects.size());
  std::vector<Bounds3> bounds;
  bounds.reserve(scene.objects.size());
  for (const SceneObject& object : scene.objects) {
    const MeshAccel* mesh = nullptr;
    if (const auto* m = std::get_if<MeshShape>(&object.geometry)) mesh = meshes_.at(m->mesh).get();
    std::optional<Instance> instance = make_instance(object.geometry, object.transform, mesh);
    if (!instance) throw SceneError(object.where, "the shape's transform is singular");
    bounds.push_back(instance->world_bounds);
    instances_.push_back(std::move(*instance));
  }
  if (has_texture(effects_)) {
    images_ = decode_images(scene);
    textures_.reserve(scene.objects.size());
    for (const SceneObject& object : scene.objects)
      textures_.push_back(object_texture(object, scene, images_));
  }
  bvh_ = build_bvh(bounds, mode);
  transparent_neighbours_ = find_transparent_neighbours(scene, effects_, bounds);
}

}  // namespace tessera
