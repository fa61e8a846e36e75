#include "common/render/prepared_scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "common/geometry/csg.h"
#include "common/geometry/motion.h"
#include "common/image/decoded_texture.h"
#include "common/math/float_error.h"
#include "common/math/portable_math.h"
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
  frame.tan_half_height = tessera::tan(camera.view_angle * std::numbers::pi / 360);
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
  for (const Light& light : scene.lights) {
    const LightAttenuation& a = light.attenuation ? *light.attenuation : g.light_attenuation;
    if (!light.is_directional && (!a.is_identity() || light.radius < kInfinity))
      effects.add(Effect::LightAttenuation);
  }
  if (g.atmospheric_attenuation) effects.add(Effect::AtmosphericAttenuation);
  if (g.fog) effects.add(Effect::Fog);
  if (g.sky) effects.add(Effect::SkyGradient);
  if (g.show_extents && !scene.objects.empty()) effects.add(Effect::ShowExtents);
  for (const SceneObject& object : scene.objects) {
    const Material& m = object.material;
    if (g.max_recursion_depth > 0 && m.reflectivity > g.min_reflectivity) {
      effects.add(Effect::Reflection);
      if (m.gloss_strength > 0) effects.add(Effect::Gloss);
    }
    if (g.max_recursion_depth > 0 && m.transparency > g.min_transparency) {
      effects.add(Effect::Refraction);
      if (m.translucency_strength > 0) effects.add(Effect::Translucency);
    }
    if (m.surface_roughness > 0) effects.add(Effect::SurfaceRoughness);
    if (const auto* mesh = std::get_if<MeshShape>(&object.geometry)) {
      effects.add(Effect::Meshes);
      if (mesh->mesh < scene.meshes.size() && !scene.meshes[mesh->mesh].corner_colours.empty())
        effects.add(Effect::VertexColors);
    }
    if (std::holds_alternative<CsgShape>(object.geometry)) effects.add(Effect::Csg);
    if (m.solid_texture.type != 0) effects.add(Effect::SolidTexture);
    if (m.flat_texture.kind == FlatTexture::Kind::Image) effects.add(Effect::ImageTexture);
    if (m.flat_texture.kind == FlatTexture::Kind::Procedural)
      effects.add(Effect::ProceduralTexture);
    if (object.motion && object.motion->moves() && g.motion_blur_frame_length > 0)
      effects.add(Effect::MotionBlur);
  }
  return effects;
}

// What the scene asks for that this renderer does not simulate, or that changes nothing
// here: said, never dropped.
std::vector<std::string> unsupported_features(const Scene& scene) {
  std::vector<std::string> out;
  const std::string global = "scene";  // global attributes keep no location
  // The manual's remedy for shadow acne: rays leaving a surface here start beyond the hit
  // point's rounding error, so shadows are right without it.
  if (scene.globals.adapted_shadow_computation)
    out.push_back(global +
                  ": adaptedShadowComputation changes nothing: shadow feelers already start "
                  "beyond the hit point's rounding error");
  return out;
}

// showExtents (§3.2.7): the twelve edges of every object's world bounds as white bars,
// ordinary opaque objects that glow white (emissive 1, no ambient or diffuse) and are
// `thickness_share` of the box's largest side thick. Unbounded objects get none.
std::vector<SceneObject> extent_bars(const std::vector<SceneObject>& objects,
                                     const std::vector<Bounds3>& bounds) {
  constexpr double thickness_share = 0.01;
  Material white;
  white.emissive = {1, 1, 1};
  white.ambient = {};
  white.diffuse = {};
  std::vector<SceneObject> bars;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const Bounds3& b = bounds[i];
    if (b.empty() || !is_finite(b.lo) || !is_finite(b.hi)) continue;
    const Vec3 size = b.hi - b.lo;
    const double half_thickness = thickness_share * max_component(size) / 2;
    if (!(half_thickness > 0)) continue;
    for (int axis = 0; axis < 3; ++axis)
      for (int corner = 0; corner < 4; ++corner) {
        // Along `axis`, at one of the four corners of the other two axes' extents.
        Vec3 centre = (b.lo + b.hi) * 0.5, half{half_thickness, half_thickness, half_thickness};
        half[axis] += size[axis] / 2;
        const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        centre[a1] = corner & 1 ? b.hi[a1] : b.lo[a1];
        centre[a2] = corner & 2 ? b.hi[a2] : b.lo[a2];
        bars.push_back({Cube{}, Affine::translation(centre) * Affine::scaling(half), white,
                        objects[i].where, std::nullopt});
      }
  }
  return bars;
}

// Whether some shape's colours vary over its surface: textures, or a mesh's corner colours.
bool has_texture(const EffectSet& effects) {
  return effects.has(Effect::SolidTexture) || effects.has(Effect::ImageTexture) ||
         effects.has(Effect::ProceduralTexture) || effects.has(Effect::VertexColors);
}

// Every image file the scene names, decoded once for all rays.
std::vector<Image> decode_images(const Scene& scene) {
  std::vector<Image> images;
  images.reserve(scene.images.size());
  for (const ImageFile& file : scene.images) {
    try {
      images.push_back(decode_texture(file.bytes, file.path, kMaxTexturePixels));
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
  ObjectTexture out{make_solid_pattern(m.solid_texture), make_flat_texture(m.flat_texture, image)};
  if (const auto* shape = std::get_if<MeshShape>(&object.geometry);
      shape && !scene.meshes[shape->mesh].corner_colours.empty()) {
    out.coloured_mesh = &scene.meshes[shape->mesh];
    out.colour_decal = m.corner_colours_decal;
  }
  return out;
}

// Whether a surface of object `index` is transparent (for a boolean object, a child's).
bool has_transparent_surface(const Scene& scene, std::uint32_t index) {
  const SceneObject& object = scene.objects[index];
  if (const auto* csg = std::get_if<CsgShape>(&object.geometry))
    return has_transparent_surface(scene, csg->left) || has_transparent_surface(scene, csg->right);
  return object.material.transparency > scene.globals.min_transparency;
}

// Which objects are children of boolean objects (parts of them, not objects by themselves);
// a SceneError unless every boolean object's children come before it and belong to it alone.
std::vector<bool> find_csg_children(const Scene& scene) {
  std::vector<bool> child(scene.objects.size(), false);
  for (std::uint32_t i = 0; i < scene.objects.size(); ++i) {
    const auto* csg = std::get_if<CsgShape>(&scene.objects[i].geometry);
    if (csg == nullptr) continue;
    for (const std::uint32_t c : {csg->left, csg->right}) {
      if (c >= i || child[c])
        throw SceneError(scene.objects[i].where,
                         "a boolean object's children must be distinct objects written before it");
      child[c] = true;
    }
  }
  return child;
}

// Pairs of transparent objects whose bounds meet: where the tracer looks for coincident
// boundaries (Tracer::cross_interface). Quadratic in the transparent objects only.
std::vector<std::vector<std::uint32_t>> find_transparent_neighbours(
    const Scene& scene, const EffectSet& effects, const std::vector<Bounds3>& bounds,
    const std::vector<bool>& csg_children) {
  std::vector<std::vector<std::uint32_t>> out(scene.objects.size());
  if (!effects.has(Effect::Refraction)) return out;
  std::vector<std::uint32_t> transparent;
  for (std::uint32_t i = 0; i < scene.objects.size(); ++i)
    if (!csg_children[i] && has_transparent_surface(scene, i)) transparent.push_back(i);
  for (std::size_t a = 0; a < transparent.size(); ++a)
    for (std::size_t b = a + 1; b < transparent.size(); ++b)
      if (bounds[transparent[a]].overlaps(bounds[transparent[b]])) {
        out[transparent[a]].push_back(transparent[b]);
        out[transparent[b]].push_back(transparent[a]);
      }
  return out;
}

// The BVH over the objects that are not children of boolean objects (those are reached through
// their boolean object), its leaves indexing Scene::objects as the tracer expects.
Bvh build_scene_bvh(const std::vector<Bounds3>& bounds, const std::vector<bool>& csg_children,
                    BvhMode mode) {
  std::vector<std::uint32_t> top_level;
  std::vector<Bounds3> top_bounds;
  for (std::uint32_t i = 0; i < bounds.size(); ++i) {
    if (csg_children[i]) continue;
    top_level.push_back(i);
    top_bounds.push_back(bounds[i]);
  }
  Bvh bvh = build_bvh(top_bounds, mode);
  for (std::uint32_t& index : bvh.primitive_order) index = top_level[index];
  return bvh;
}

OwnHull own_hull(const ShapeGeometry& geometry) {
  if (std::holds_alternative<Sphere>(geometry) || std::holds_alternative<Cube>(geometry))
    return {OwnHull::Kind::Convex};
  if (const auto* cylinder = std::get_if<TaperedCylinder>(&geometry)) {
    if (cylinder->wall && cylinder->base_cap && cylinder->top_cap) return {OwnHull::Kind::Convex};
  } else if (const auto* torus = std::get_if<Torus>(&geometry)) {
    // The outer half (rho >= R) lies on the boundary of the torus's convex hull, with the same
    // normal.
    return {OwnHull::Kind::TorusOuterHalf, torus->torus_radius * torus->torus_radius};
  }
  return {};
}

std::vector<OwnHull> find_own_hulls(const std::vector<Instance>& instances) {
  std::vector<OwnHull> out;
  out.reserve(instances.size());
  for (const Instance& instance : instances) out.push_back(own_hull(instance.geometry));
  return out;
}

// Sector k of a torus is the part of it whose nearest points of the core circle (radius R in the
// xy plane) lie at angles [k, k + 1] * 2 pi / n, n = kTorusLightBufferSectors: the points at
// those angles about its axis, and the points on the axis (every core point is nearest to them:
// they lie in every sector). Both boxes below hold the world image of every point within
// p = 1e-9 (R + r) of the sector, p being ten times the whole box's widening of the tube
// (torus_world_bounds), so the image of every point of the torus that its tests can hit: such a
// point lies within p of the torus, so within p of some sector (the computed ends of consecutive
// arcs are the same numbers; n times 2 pi / n falls short of 2 pi by rounding only, far less
// than p).
constexpr int kSectors = kTorusLightBufferSectors;
static_assert(kSectors % 4 == 0,
              "sector boundaries fall on the axes: each arc lies in one quadrant");

double sector_angle(int k) { return k * (2 * std::numbers::pi / kSectors); }

// The box of the annular sector rho in [max(R - r, 0), R + r], |z| <= r: in the plane, the box of
// its four corners (x = rho cos(a) and y = rho sin(a) are monotone in rho and, the arc lying in
// one quadrant, in a: their extremes are at the corners); padded by p, far more than the rounding
// of its corners (a few units in the last place of R + r). Its eight corners go to world space
// padded by their rounding, as any shape's box's do. Tight along the arc, loose across it when
// turned.
Bounds3 sector_corner_box(const Affine& to_world, const Torus& torus, int k) {
  const double big_r = torus.torus_radius, r = torus.tube_radius;
  const double outer = big_r + r, inner = std::max(big_r - r, 0.0);
  const double p = 1e-9 * outer;
  Bounds3 local;
  for (int end = 0; end < 2; ++end) {
    const double angle = sector_angle(k + end);
    const double c = std::cos(angle), s = std::sin(angle);
    local.extend(Vec3{outer * c, outer * s, 0});
    local.extend(Vec3{inner * c, inner * s, 0});
  }
  local.lo = local.lo - Vec3{p, p, r + p};
  local.hi = local.hi + Vec3{p, p, r + p};
  Bounds3 world;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 c{(corner & 1) ? local.hi.x : local.lo.x, (corner & 2) ? local.hi.y : local.lo.y,
                 (corner & 4) ? local.hi.z : local.lo.z};
    const Vec3 w = to_world.apply_point(c);
    const Vec3 e = to_world.point_error(c, Vec3{}) * 2;
    world.extend(w - e);
    world.extend(w + e);
  }
  return world;
}

// The box of the core arc swept by a ball of radius r + p, as torus_world_bounds takes the whole
// torus: under to_world's linear part L and translation t, along world axis i, t_i plus R times
// the range of L_i0 cos(a) + L_i1 sin(a) over the arc, plus or minus (r + p) |L_i| (the ball's
// image, an ellipsoid). The range's ends are the arc ends' values, or +-|(L_i0, L_i1)| where
// (L_i0, L_i1), or its opposite, points into the arc (between its ends by both cross products).
// Padded as the whole box is for the hit points' rounding through to_world, and by a further
// 16 eps of the terms' size for this sum's own. Tight across the arc when turned, loose along it
// (the ball overhangs the arc's ends by r).
Bounds3 sector_swept_box(const Affine& to_world, const Torus& torus, int k) {
  const double big_r = torus.torus_radius, r = torus.tube_radius, e = big_r + r;
  const double tube = r + 1e-9 * e;
  const double hit_error = 16 * kMachineEpsilon * e;
  const Vec3 error = to_world.point_error(Vec3{e, e, r}, Vec3{hit_error, hit_error, hit_error}) * 2;
  const double a = sector_angle(k), b = sector_angle(k + 1);
  const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b);
  Bounds3 world;
  for (int i = 0; i < 3; ++i) {
    const double u = to_world.m[i][0], v = to_world.m[i][1], w = to_world.m[i][2];
    const double at_a = u * ca + v * sa, at_b = u * cb + v * sb;
    double most = std::max(at_a, at_b), least = std::min(at_a, at_b);
    const double after_a = ca * v - sa * u, before_b = u * sb - v * cb;
    const double in_plane = std::sqrt(u * u + v * v);
    if (after_a >= 0 && before_b >= 0) most = in_plane;
    if (after_a <= 0 && before_b <= 0) least = -in_plane;
    const double row = std::sqrt(u * u + v * v + w * w);
    const double pad =
        tube * row + error[i] + 16 * kMachineEpsilon * (std::fabs(to_world.m[i][3]) + 2 * e * row);
    world.lo[i] = to_world.m[i][3] + big_r * least - pad;
    world.hi[i] = to_world.m[i][3] + big_r * most + pad;
  }
  return world;
}

}  // namespace

void light_buffer_pieces(const Instance& instance, std::vector<Bounds3>& out) {
  const auto* torus = std::get_if<Torus>(&instance.geometry);
  if (!torus || instance.motion) return;
  // Each box holds the sector's image, so their intersection does: the corner box bounds it
  // along the arc, the swept box across it.
  for (int k = 0; k < kSectors; ++k) {
    const Bounds3 corners = sector_corner_box(instance.to_world, *torus, k);
    const Bounds3 swept = sector_swept_box(instance.to_world, *torus, k);
    Bounds3 both;
    for (int i = 0; i < 3; ++i) {
      both.lo[i] = std::max(corners.lo[i], swept.lo[i]);
      both.hi[i] = std::min(corners.hi[i], swept.hi[i]);
    }
    out.push_back(both);
  }
}

namespace {

// At most this many lights get a light buffer (1.5 MB and about a millisecond each).
constexpr int kMaxLightBuffers = 16;

// A light buffer for each point light and spotlight that casts shadows, over the objects the
// scene BVH holds (children of boolean objects are reached through their parents).
std::vector<std::optional<LightBuffer>> build_light_buffers(
    const Scene& scene, const Bvh& bvh, const std::vector<Bounds3>& bounds,
    const std::vector<Instance>& instances) {
  std::vector<Bounds3> top_bounds, pieces;
  std::vector<std::uint32_t> first;  // object o's pieces start at first[o]
  top_bounds.reserve(bvh.primitive_order.size());
  first.reserve(bvh.primitive_order.size() + 1);
  for (const std::uint32_t index : bvh.primitive_order) {
    top_bounds.push_back(bounds[index]);
    first.push_back(static_cast<std::uint32_t>(pieces.size()));
    light_buffer_pieces(instances[index], pieces);
  }
  first.push_back(static_cast<std::uint32_t>(pieces.size()));
  if (pieces.empty()) first.clear();
  std::vector<std::optional<LightBuffer>> out(scene.lights.size());
  int built = 0;
  for (std::size_t l = 0; l < scene.lights.size() && built < kMaxLightBuffers; ++l) {
    const Light& light = scene.lights[l];
    if (light.is_directional || !light.casts_shadows) continue;
    out[l].emplace(light.position, top_bounds, bvh.primitive_order,
                   opaque_balls(scene, instances, bvh.primitive_order, light.position),
                   LightBuffer::Pieces{pieces, first});
    ++built;
  }
  return out;
}

}  // namespace

PreparedScene::PreparedScene(const Scene& scene, BvhMode mode, int build_threads)
    : scene_(&scene),
      camera_(make_camera_frame(scene.camera)),
      effects_(scene_effects(scene)),
      unsupported_(unsupported_features(scene)) {
  meshes_.reserve(scene.meshes.size());
  for (const Mesh& mesh : scene.meshes)
    meshes_.push_back(std::make_unique<MeshAccel>(build_mesh_accel(mesh, mode, build_threads)));

  // Boolean objects point at their children's instances: the vector must never reallocate
  // (showExtents adds up to 12 bars an object).
  const bool extents = effects_.has(Effect::ShowExtents);
  instances_.reserve(scene.objects.size() * (extents ? 13 : 1));
  std::vector<bool> csg_children = find_csg_children(scene);
  std::vector<Bounds3> bounds;
  bounds.reserve(instances_.capacity());
  const auto add_instance = [&](const SceneObject& object) {
    std::optional<Instance> instance;
    if (const auto* csg = std::get_if<CsgShape>(&object.geometry)) {
      instance = make_csg_instance(*csg, instances_[csg->left], instances_[csg->right]);
    } else {
      const MeshAccel* mesh = nullptr;
      if (const auto* m = std::get_if<MeshShape>(&object.geometry))
        mesh = meshes_.at(m->mesh).get();
      instance = object.motion && object.motion->moves() && effects_.has(Effect::MotionBlur)
                     ? make_moving_instance(object.geometry, object.transform, *object.motion,
                                            scene.globals.motion_blur_frame_length, mesh)
                     : make_instance(object.geometry, object.transform, mesh);
    }
    if (!instance) throw SceneError(object.where, "the shape's transform is singular");
    instance->object = static_cast<std::uint32_t>(instances_.size());
    bounds.push_back(instance->world_bounds);
    instances_.push_back(std::move(*instance));
  };
  for (const SceneObject& object : scene.objects) add_instance(object);
  if (extents) {
    // The bars are objects of a copy of the scene, so that every lookup by instance finds them.
    with_extents_ = std::make_unique<Scene>(scene);
    for (const SceneObject& bar : extent_bars(scene.objects, bounds)) {
      add_instance(bar);
      with_extents_->objects.push_back(bar);
    }
    csg_children.resize(instances_.size(), false);
    scene_ = with_extents_.get();
  }
  const std::vector<SceneObject>& objects = scene_->objects;
  if (has_texture(effects_)) {
    images_ = decode_images(scene);
    textures_.reserve(objects.size());
    for (const SceneObject& object : objects)
      textures_.push_back(object_texture(object, scene, images_));
  }
  bvh_ = build_scene_bvh(bounds, csg_children, mode);
  transparent_neighbours_ = find_transparent_neighbours(*scene_, effects_, bounds, csg_children);
  own_hulls_ = find_own_hulls(instances_);
  if (mode != BvhMode::None)
    light_buffers_ = build_light_buffers(*scene_, bvh_, bounds, instances_);
  light_buffers_.resize(scene_->lights.size());
}

}  // namespace tessera
