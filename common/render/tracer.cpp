#include "common/render/tracer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <new>
#include <numbers>

#include "common/accel/bvh_traverse.h"
#include "common/math/float_error.h"
#include "common/render/cone.h"
#include "common/render/optics.h"
#include "common/render/render.h"
#include "common/render/shadow_feelers.h"

namespace tessera {

namespace {

// A ray may cross at most this many false interfaces (media of lower priority) in a row.
constexpr int kMaxFalseInterfaces = 64;

// At most this many surfaces are taken as one coincident interface.
constexpr int kMaxCoincident = 8;

// Eq. 4.3: the normal perturbed by surface roughness, renormalized.
Vec3 perturb_normal(const Vec3& n, double roughness, SampleStream& rng) {
  const double rx = rng.next(), ry = rng.next(), rz = rng.next();
  const Vec3 p = n + Vec3{rx, ry, rz} * roughness - Vec3{1, 1, 1} * (roughness / 2);
  return normalize_or(p, n);
}

// The positive part of a cosine, or its absolute value when back faces are lit (§4.1.3).
double facing(double cosine, bool light_back_faces) {
  return light_back_faces ? std::fabs(cosine) : std::max(cosine, 0.0);
}

// Gloss and translucency (eq. 4.18-4.19): the mean of `trace_along` over a cone of `count`
// rays around `axis`, of radius strength / 2. A rim ray jittered across the surface, to the
// other side than the axis leaves on, is traced along the axis instead. The callers give each
// cone ray the weight of its share of the pixel (the path's weight times the reflectivity or
// transparency, over `count`), so that below nested cones recursion stops once a ray's share
// falls under minReflectivity or minTransparency, instead of growing as count^depth.
template <typename TraceAlong>
Rgb blurred(const Vec3& axis, double strength, int count, const Vec3& surface_normal,
            SampleStream& rng, TraceAlong&& trace_along) {
  const double side = dot(axis, surface_normal);
  return Cone(axis, strength / 2).mean<Rgb>(count, rng, [&](const Vec3& direction) {
    return trace_along(dot(direction, surface_normal) * side > 0 ? direction : axis);
  });
}

// The unit vector `l` from `point` towards `light` and the distance to it, infinite for a
// directional light; false when the point is at the light. `directional` is the light's
// is_directional, or a constant false where the scene has no directional lights.
[[gnu::always_inline]] inline bool towards_light(const Light& light, bool directional,
                                                 const Vec3& point, Vec3& l, double& distance) {
  if (directional) {
    l = -light.direction;
    distance = kInfinity;
    return true;
  }
  const Vec3 to_light = light.position - point;
  distance = length(to_light);
  if (!(distance > 0)) return false;
  l = to_light / distance;
  return true;
}

// Eq. 4.10-4.11: the diffuse and specular terms scaled by the material's opacity, unless it
// retains them.
double diffuse_scale(const Material& m) { return m.retain_diffuse_color ? 1 : 1 - m.transparency; }
double specular_scale(const Material& m) {
  return m.retain_specular_reflection ? 1 : 1 - m.transparency;
}
bool has_specular_term(const Material& m) { return !m.specular.is_zero() && specular_scale(m) > 0; }

}  // namespace

Tracer::Tracer(const PreparedScene& scene, const RenderSettings& settings, RenderStats& stats,
               const RenderInterrupt& interrupt)
    : scene_(scene),
      stats_(stats),
      effects_(render_effects(scene, settings)),
      cone_samples_(settings.cone_samples),
      shadow_cone_radius_(settings.shadow_jitter / 2),
      illuminate_(lighting_for(effects_)),
      interrupt_(interrupt) {
  for (const Light& light : scene.scene().lights)
    cos_cutoff_.push_back(std::cos(light.spot.cutoff_degrees * std::numbers::pi / 180));
  packet_lighting_ = effects_.has(Effect::HardShadows) && !effects_.has(Effect::SoftShadows) &&
                     !effects_.has(Effect::Gloss) && !effects_.has(Effect::Translucency);
  if (packet_lighting_) {
    const std::size_t entries = kPacketLanes * scene.scene().lights.size();
    packet_terms_.resize(entries);
    packet_lights_.resize(entries);
    packet_shadows_.resize(entries);
  }
}

void Tracer::check_interrupt() {
  poll_countdown_ = kPollRays;
  if (interrupt_.requested()) throw RenderInterrupted();
}

bool Tracer::cones_within_budget() {
  if (stats_.camera_rays != budget_sample_) {  // the sample's first cone
    budget_sample_ = stats_.camera_rays;
    budget_start_ = secondary_rays();
  }
  if (secondary_rays() - budget_start_ < kMaxRaysPerSample) return true;
  if (stats_.pixels != budget_pixel_) {
    budget_pixel_ = stats_.pixels;
    ++stats_.ray_budget_pixels;
  }
  return false;
}

// The local_illumination compiled for the render's shadow mode and lights, chosen once per
// tracer and called through a pointer: a branch per hit for each would cost more.
Tracer::Illumination Tracer::lighting_for(const EffectSet& effects) {
  const bool directional = effects.has(Effect::DirectionalLight);
  if (effects.has(Effect::SoftShadows))
    return directional ? &Tracer::local_illumination<ShadowMode::Soft, true>
                       : &Tracer::local_illumination<ShadowMode::Soft, false>;
  if (effects.has(Effect::HardShadows))
    return directional ? &Tracer::local_illumination<ShadowMode::Hard, true>
                       : &Tracer::local_illumination<ShadowMode::Hard, false>;
  return directional ? &Tracer::local_illumination<ShadowMode::None, true>
                     : &Tracer::local_illumination<ShadowMode::None, false>;
}

bool Tracer::closest_hit(const Ray& ray, Hit& hit) {
  const std::vector<Instance>& instances = scene_.instances();
  bool found = false;
  hit.time = ray.time;
  // Straight into hit.world, which intersect_instance leaves alone on a miss: a WorldHit of
  // its own per shape test cost a zeroing (rep stos) and a copy, some 5 % of the traversal's time.
  traverse_bvh(
      scene_.bvh(), ray, kInfinity, stats_.intersections.bvh_nodes,
      [&](std::uint32_t index, double t_max) {
        if (!intersect_instance(instances[index], ray, t_max, hit.world, stats_.intersections))
          return t_max;
        hit.instance = index;
        found = true;
        return hit.world.t;
      });
  return found;
}

void Tracer::find_packet_hits(const Ray* rays, int count) {
  const std::vector<Instance>& instances = scene_.instances();
  double t_max[kPacketLanes];
  for (int l = 0; l < count; ++l) {
    packet_rays_[l] = rays[l];
    packet_found_[l] = false;
    packet_hits_[l].time = rays[l].time;
    t_max[l] = kInfinity;
  }
  packet_count_ = count;
  // The leaf visit of closest_hit's traverse_bvh, per ray.
  traverse_bvh_packet_leaves(scene_.bvh(), PacketRays(rays, count), t_max,
                             stats_.intersections.bvh_nodes,
                             [&](int lane, std::uint32_t first, std::uint32_t size, double limit) {
                               Hit& hit = packet_hits_[lane];
                               for (std::uint32_t i = first; i < first + size; ++i) {
                                 const std::uint32_t index = scene_.bvh().primitive_order[i];
                                 if (!intersect_instance(instances[index], packet_rays_[lane],
                                                         limit, hit.world, stats_.intersections))
                                   continue;
                                 hit.instance = index;
                                 packet_found_[lane] = true;
                                 limit = hit.world.t;
                               }
                               return limit;
                             });
}

void Tracer::light_packet_hits(const MediumStack& air, SampleStream* rngs) {
  const std::vector<Light>& lights = scene_.scene().lights;
  const double epsilon = scene_.scene().globals.shadow_feeler_epsilon;
  const bool directional_lights = effects_.has(Effect::DirectionalLight);
  // Each lane as trace_from_hit and local_illumination go, up to the feelers.
  Vec3 offsets[kPacketLanes];
  for (int lane = 0; lane < packet_count_; ++lane) {
    Surface& s = packet_surfaces_[lane];
    const Hit& hit = packet_hits_[lane];
    packet_surface_found_[lane] =
        find_surface(packet_rays_[lane], packet_found_[lane], packet_hits_[lane], RayKind::Camera,
                     air, rngs[lane], s, packet_backgrounds_[lane]);
    const bool lit = packet_surface_found_[lane] && s.colours.lit;
    if (lit) offsets[lane] = spawn_offset(hit, epsilon);
    const bool has_specular = lit && has_specular_term(*s.m);
    for (std::size_t index = 0; index < lights.size(); ++index) {
      LightTerms& t = packet_terms_[lane * lights.size() + index];
      const Vec3& view_dir = s.ray->direction;
      packet_lights_[lane * lights.size() + index] =
          lit && (directional_lights
                      ? light_terms<true>(hit, *s.m, s.normal, view_dir, has_specular, index, t)
                      : light_terms<false>(hit, *s.m, s.normal, view_dir, has_specular, index, t));
    }
  }
  // The feelers towards each light, of the lanes it may light, walk the scene BVH together.
  for (std::size_t index = 0; index < lights.size(); ++index) {
    const Light& light = lights[index];
    if (!light.casts_shadows) continue;
    const bool directional = directional_lights && light.is_directional;
    Ray rays[kPacketLanes];
    double t_max[kPacketLanes], factors[kPacketLanes];
    int lanes[kPacketLanes];
    int count = 0;
    for (int lane = 0; lane < packet_count_; ++lane) {
      const std::size_t k = lane * lights.size() + index;
      if (!packet_lights_[k]) continue;
      const Feeler f = feeler(packet_hits_[lane], offsets[lane], directional, packet_terms_[k].l,
                              light.position);
      ++stats_.shadow_rays;
      poll_interrupt();
      rays[count] = f.ray;
      t_max[count] = f.t_max;
      lanes[count++] = lane;
    }
    if (count == 0) continue;
    feeler_transmittance_packet(scene_, rays, t_max, count, factors, stats_.intersections);
    for (int j = 0; j < count; ++j) packet_shadows_[lanes[j] * lights.size() + index] = factors[j];
  }
}

Rgb Tracer::trace_packet_ray(int lane, const MediumStack& media, SampleStream& rng) {
  if (!packet_lighting_)
    return trace_from_hit(packet_rays_[lane], packet_found_[lane], packet_hits_[lane],
                          RayKind::Camera, 0, 1.0, media, rng);
  if (!packet_surface_found_[lane]) return packet_backgrounds_[lane];
  // local_illumination<ShadowMode::Hard> from light_packet_hits' terms and shadows.
  const Surface& s = packet_surfaces_[lane];
  const std::vector<Light>& lights = scene_.scene().lights;
  Rgb color = unlit_colour(*s.m, s.colours);
  if (s.colours.lit) {
    for (std::size_t index = 0; index < lights.size(); ++index) {
      const std::size_t k = lane * lights.size() + index;
      if (!packet_lights_[k]) continue;
      const double shadow = lights[index].casts_shadows ? packet_shadows_[k] : 1;
      if (shadow <= 0) continue;
      color += light_contribution(lights[index], packet_terms_[k], *s.m, s.colours, shadow);
    }
  }
  return finish_surface(s, packet_hits_[lane], color, 0, 1.0, rng);
}

std::optional<WorldHit> Tracer::first_hit(const Ray& ray) {
  Hit hit;
  if (!closest_hit(ray, hit)) return std::nullopt;
  return hit.world;
}

double Tracer::shadow_factor(const Feeler& feeler) {
  ++stats_.shadow_rays;
  poll_interrupt();
  return feeler_transmittance(scene_, feeler.ray, feeler.t_max, stats_.intersections);
}

Vec3 Tracer::spawn_offset(const Hit& hit, double epsilon) const {
  const SceneGlobals& g = scene_.scene().globals;
  if (std::holds_alternative<MeshShape>(scene_.instances()[hit.world.object].geometry))
    epsilon = std::max(epsilon, g.mesh_epsilon);
  return surface_offset(hit.world.point_error, hit.world.normal, epsilon);
}

Vec3 Tracer::spawn_origin(const Hit& hit, const Vec3& direction, double epsilon) const {
  return offset_ray_origin_by(hit.world.point, spawn_offset(hit, epsilon), hit.world.normal,
                              direction);
}

Tracer::Crossing Tracer::cross_interface(const Ray& ray, Hit& hit, const MediumStack& media) {
  const std::vector<Instance>& instances = scene_.instances();
  const std::vector<SceneObject>& objects = scene_.scene().objects;

  // Assigned, not brace-initialized: GCC zeroed the whole of `crossing{media, true}` (272 bytes,
  // a `rep stos`) before copying the stack's entries in use, at every transparent hit.
  Crossing crossing;
  crossing.after = media;
  const auto cross = [&](const Hit& h) {
    const Material& m = objects[h.world.object].material;
    crossing.after = dot(h.world.normal, ray.direction) < 0
                         ? crossing.after.entered({h.instance, m.priority, m.speed_of_light})
                         : crossing.after.exited(h.instance);
  };
  const std::vector<std::uint32_t>& neighbours = scene_.transparent_neighbours(hit.instance);
  if (neighbours.empty()) {
    // Usually so: the hit is the only surface, without the array of candidates below, whose
    // construction zeroes eight Hits (1.2 kB).
    cross(hit);
  } else {
    // Probe a short stretch of the ray around the hit, as long as the hit's rounding (times a
    // margin for the other surface's own rounding), for the transparent objects whose bounds
    // meet this one's.
    Hit found[kMaxCoincident];
    int count = 0;
    found[count++] = hit;
    const Vec3& p = hit.world.point;
    const double reach =
        8 * (length(hit.world.point_error) + kMachineEpsilon * max_component(abs(p))) /
            length(ray.direction) +
        std::numeric_limits<double>::min();
    const Ray probe{p - ray.direction * reach, ray.direction, ray.time};
    const Vec3 margin = abs(ray.direction) * reach;
    const Bounds3 stretch{p - margin, p + margin};
    for (const std::uint32_t index : neighbours) {
      if (count == kMaxCoincident || !instances[index].world_bounds.overlaps(stretch)) continue;
      WorldHit h;
      if (intersect_instance(instances[index], probe, 2 * reach, h, stats_.intersections))
        found[count++] = {h, index};
    }
    for (int k = 0; k < count; ++k) cross(found[k]);
    if (count > 1) {
      // The governing surface: that of the medium entered, or else of the medium left.
      const auto index_of = [&](std::uint32_t instance) {
        for (int k = 0; k < count; ++k)
          if (found[k].instance == instance) return k;
        return -1;
      };
      int chosen = index_of(crossing.after.top().instance);
      if (chosen < 0) chosen = std::max(index_of(media.top().instance), 0);
      Vec3 error = found[chosen].world.point_error;
      for (int k = 0; k < count; ++k)
        error = max(error, found[k].world.point_error +
                               abs(found[k].world.point - found[chosen].world.point));
      const double t = hit.world.t;
      hit = found[chosen];
      hit.world.t = t;
      hit.world.point_error = error;
    }
  }
  crossing.known = dot(hit.world.normal, ray.direction) < 0 || media.contains(hit.instance);
  return crossing;
}

[[gnu::always_inline]] inline Tracer::Feeler Tracer::feeler(const Hit& hit, const Vec3& offset,
                                                            bool directional, const Vec3& d,
                                                            const Vec3& target) const {
  const Vec3 origin = offset_ray_origin_by(hit.world.point, offset, hit.world.normal, d);
  // A point light's feeler ends at t = 1, on the light; a directional light's never ends.
  if (directional) return {Ray{origin, d, hit.time}, kInfinity};
  return {Ray{origin, target - origin, hit.time}, 1.0};
}

double Tracer::soft_visibility(const Hit& hit, const Vec3& offset, const Light& light,
                               const Vec3& l, double distance, SampleStream& rng) {
  const int count = cones_within_budget() ? cone_samples_ : 1;
  return Cone(l, shadow_cone_radius_).mean<double>(count, rng, [&](const Vec3& d) {
    return shadow_factor(
        feeler(hit, offset, light.is_directional, d, hit.world.point + d * distance));
  });
}

Rgb Tracer::unlit_colour(const Material& m, const SurfaceColours& colours) {
  Rgb color = m.emissive;  // eq. 4.4
  Rgb ambient = colours.ambient_term;
  if (!m.retain_ambient_color) ambient *= 1 - m.transparency;  // eq. 4.6
  color += ambient;
  return color;
}

template <bool kDirectionalLights>
[[gnu::always_inline]] inline bool Tracer::light_terms(const Hit& hit, const Material& m,
                                                       const Vec3& normal, const Vec3& view_dir,
                                                       bool has_specular, std::size_t index,
                                                       LightTerms& t) const {
  const Light& light = scene_.scene().lights[index];
  const bool directional = kDirectionalLights && light.is_directional;
  if (directional && !light.lights(hit.world.object)) return false;
  if (!towards_light(light, directional, hit.world.point, t.l, t.distance)) return false;

  // Spotlight: zero outside the cut-off, cos^exponent inside (§4.1.3); the power is taken in
  // light_contribution, once the point is known to be lit.
  t.cos_alpha = 1;
  if (light.is_spot) {
    t.cos_alpha = std::clamp(dot(-t.l, light.spot.direction), -1.0, 1.0);
    if (t.cos_alpha < cos_cutoff_[index]) return false;
  }

  t.n_dot_l = facing(dot(normal, t.l), m.light_back_faces);
  t.n_dot_h = 0;
  if (has_specular) {
    // The halfway vector -V + L vanishes when light and view are opposite: no highlight.
    const Vec3 h = normalize_or(t.l - view_dir, Vec3{});
    t.n_dot_h = facing(dot(normal, h), m.light_back_faces);
  }
  if (t.n_dot_l <= 0 && t.n_dot_h <= 0) return false;

  t.attenuation = 1;  // eq. 4.12
  if (effects_.has(Effect::LightAttenuation) && !directional) {
    if (t.distance > light.radius) return false;
    const SceneGlobals& g = scene_.scene().globals;
    const LightAttenuation& a = light.attenuation ? *light.attenuation : g.light_attenuation;
    const double denominator =
        a.constant + a.linear * t.distance + a.quadratic * t.distance * t.distance;
    if (denominator > 1) t.attenuation = 1 / denominator;
  }
  return true;
}

[[gnu::always_inline]] inline Rgb Tracer::light_contribution(const Light& light,
                                                             const LightTerms& t, const Material& m,
                                                             const SurfaceColours& colours,
                                                             double shadow) {
  const double cone = light.is_spot && light.spot.exponent != 0
                          ? std::pow(std::max(t.cos_alpha, 0.0), light.spot.exponent)
                          : 1;
  Rgb contribution = colours.diffuse * light.color * (t.n_dot_l * diffuse_scale(m));  // eq. 4.8
  if (t.n_dot_h > 0)                                                                  // eq. 4.9
    contribution +=
        m.specular * light.color * (std::pow(t.n_dot_h, m.specular_exponent) * specular_scale(m));
  return contribution * (t.attenuation * shadow * cone);  // eq. 4.7
}

template <ShadowMode kShadows, bool kDirectionalLights>
Rgb Tracer::local_illumination(const Hit& hit, const Material& m, const SurfaceColours& colours,
                               const Vec3& normal, const Vec3& view_dir, SampleStream& rng) {
  const Scene& scene = scene_.scene();
  Rgb color = unlit_colour(m, colours);
  if (!colours.lit) return color;
  // Every feeler leaves the hit by the same offset; only its side depends on the light.
  Vec3 feeler_offset;
  if constexpr (kShadows != ShadowMode::None)
    feeler_offset = spawn_offset(hit, scene.globals.shadow_feeler_epsilon);

  const bool has_specular = has_specular_term(m);
  for (std::size_t index = 0; index < scene.lights.size(); ++index) {
    LightTerms t;
    if (!light_terms<kDirectionalLights>(hit, m, normal, view_dir, has_specular, index, t))
      continue;
    const Light& light = scene.lights[index];
    double shadow = 1;  // eq. 4.24-4.26: the share of the light that reaches the hit
    if constexpr (kShadows == ShadowMode::Hard) {
      if (light.casts_shadows)
        shadow = shadow_factor(feeler(
            hit, feeler_offset, kDirectionalLights && light.is_directional, t.l, light.position));
    } else if constexpr (kShadows == ShadowMode::Soft) {
      if (light.casts_shadows)
        shadow = soft_visibility(hit, feeler_offset, light, t.l, t.distance, rng);
    }
    if (shadow <= 0) continue;
    color += light_contribution(light, t, m, colours, shadow);
  }
  return color;
}

Rgb Tracer::reflection(const Ray& ray, const Hit& hit, const Material& m, const Vec3& normal,
                       int depth, double weight, const MediumStack& media, SampleStream& rng) {
  const Vec3 mirror = normalize_or(reflect(ray.direction, normal), ray.direction);  // eq. 4.13
  const double epsilon = scene_.scene().globals.reflectivity_epsilon;
  const bool glossy = effects_.has(Effect::Gloss) && m.gloss_strength > 0 && cones_within_budget();
  const double ray_weight = weight * m.reflectivity / (glossy ? cone_samples_ : 1);
  const auto trace_along = [&](const Vec3& direction) {
    ++stats_.reflection_rays;
    const Ray reflected{spawn_origin(hit, direction, epsilon), direction, ray.time};
    return trace(reflected, RayKind::Reflected, depth + 1, ray_weight, media, rng);
  };
  const Rgb incoming =
      glossy ? blurred(mirror, m.gloss_strength, cone_samples_, hit.world.normal, rng, trace_along)
             : trace_along(mirror);
  return incoming * m.reflectivity;  // eq. 4.14
}

Rgb Tracer::transmission(const Ray& ray, const Hit& hit, const Material& m, const Vec3& normal,
                         int depth, double weight, const MediumStack& media,
                         const Crossing& crossing, SampleStream& rng) {
  const SceneGlobals& g = scene_.scene().globals;
  const bool entering = dot(hit.world.normal, ray.direction) < 0;
  MediumStack after = crossing.after;
  // Leaving an object the ray was not known to be in (the eye inside glass): its medium is
  // the one behind the surface.
  const double c1 = crossing.known ? media.top().speed_of_light : m.speed_of_light;
  const double c2 = after.top().speed_of_light;

  Vec3 direction = ray.direction;  // disableRefraction: straight through
  if (!m.disable_refraction) {
    const Vec3 n = entering ? normal : -normal;  // against the incoming ray
    if (const std::optional<Vec3> refracted = refract(ray.direction, n, c2 / c1)) {
      direction = *refracted;
    } else {
      // Total internal reflection: the transmitted share reflects and stays in this medium.
      direction = normalize_or(reflect(ray.direction, n), ray.direction);
      after = media;
    }
  }
  const bool translucent =
      effects_.has(Effect::Translucency) && m.translucency_strength > 0 && cones_within_budget();
  const double ray_weight = weight * m.transparency / (translucent ? cone_samples_ : 1);
  const auto trace_along = [&](const Vec3& d) {
    ++stats_.refraction_rays;
    const Ray refracted{spawn_origin(hit, d, g.transparency_epsilon), d, ray.time};
    return trace(refracted, RayKind::Refracted, depth + 1, ray_weight, after, rng);
  };
  const Rgb incoming = translucent ? blurred(direction, m.translucency_strength, cone_samples_,
                                             hit.world.normal, rng, trace_along)
                                   : trace_along(direction);
  return incoming * m.transparency;  // eq. 4.17
}

Rgb Tracer::apply_atmosphere(const Rgb& color, double distance) const {
  const SceneGlobals& g = scene_.scene().globals;
  Rgb out = color;
  if (const auto& a = g.atmospheric_attenuation; a && a->front_distance != a->back_distance) {
    // Eq. 4.20-4.21, s clipped between the front and back scales.
    double s = a->back_scale + (distance - a->back_distance) * (a->front_scale - a->back_scale) /
                                   (a->front_distance - a->back_distance);
    s = std::clamp(s, std::min(a->front_scale, a->back_scale),
                   std::max(a->front_scale, a->back_scale));
    out = out * s + a->color * (1 - s);
  }
  if (const auto& fog = g.fog; fog && fog->start != fog->end) {
    // Eq. 4.22-4.23, f clipped to [0, 1]; or VRML's exponential fog.
    const double f = fog->exponential
                         ? (distance < fog->end ? std::exp(-distance / (fog->end - distance)) : 0.0)
                         : std::clamp((fog->end - distance) / (fog->end - fog->start), 0.0, 1.0);
    out = out * f + fog->color * (1 - f);
  }
  return out;
}

Rgb Tracer::trace(const Ray& ray_in, RayKind kind, int depth, double weight,
                  const MediumStack& media_in, SampleStream& rng) {
  // The hit is left unzeroed: closest_hit writes every member it has before any is read, and
  // zeroing its 152 bytes (the members' initializers, a `rep stos`) for every ray cost the demo
  // some 2 % of its time. The byte array's lifetime implicitly creates the Hit, an aggregate and
  // so an implicit-lifetime type, within it (C++20 [intro.object]).
  alignas(Hit) std::byte hit_storage[sizeof(Hit)];
  Hit& hit = *std::launder(reinterpret_cast<Hit*>(hit_storage));
  const bool found = closest_hit(ray_in, hit);
  return trace_from_hit(ray_in, found, hit, kind, depth, weight, media_in, rng);
}

Rgb Tracer::trace_from_hit(const Ray& ray_in, bool found, Hit& hit, RayKind kind, int depth,
                           double weight, const MediumStack& media_in, SampleStream& rng) {
  Surface s;
  Rgb background;
  if (!find_surface(ray_in, found, hit, kind, media_in, rng, s, background)) return background;
  const Rgb color = (this->*illuminate_)(hit, *s.m, s.colours, s.normal, s.ray->direction, rng);
  return finish_surface(s, hit, color, depth, weight, rng);
}

[[gnu::always_inline]] inline bool Tracer::find_surface(const Ray& ray_in, bool found, Hit& hit,
                                                        RayKind kind, const MediumStack& media_in,
                                                        SampleStream& rng, Surface& s,
                                                        Rgb& background) {
  poll_interrupt();
  const Scene& scene = scene_.scene();
  const SceneGlobals& g = scene.globals;
  const EffectSet& effects = effects_;

  // The ray itself until it passes a false interface, then its continuation. Not copied up
  // front: its caller has just written its origin a component at a time, and a copy reads it
  // two at a time, which waits for those stores to reach the cache (store forwarding fails).
  s.ray = &ray_in;
  s.continued.reset();
  s.media = media_in;
  s.travelled = 0;
  for (int skipped = 0;; ++skipped) {
    if (!found) {
      if (kind == RayKind::Reflected) {
        background = Rgb{};  // eq. 4.2
      } else {
        background = effects.has(Effect::SkyGradient)
                         ? g.sky->colour(unit_or_zero(s.ray->direction))
                         : g.background;
      }
      return false;
    }
    s.travelled += hit.world.t;
    s.m = &scene.objects[hit.world.object].material;
    if (!effects.has(Effect::Refraction) || !(s.m->transparency > g.min_transparency)) break;
    s.crossing = cross_interface(*s.ray, hit, s.media);
    s.m = &scene.objects[hit.world.object].material;
    // A transparent surface whose crossing leaves the governing medium unchanged is a false
    // interface: it neither shades nor refracts.
    if (skipped == kMaxFalseInterfaces || !s.crossing.known ||
        s.crossing.after.top().instance != s.media.top().instance)
      break;
    s.media = s.crossing.after;
    // A whole Ray, made before emplace replaces what `s.ray` may point to (Clang 14 has no
    // parenthesized aggregate initialization either).
    s.ray = &s.continued.emplace(Ray{spawn_origin(hit, s.ray->direction, g.transparency_epsilon),
                                     s.ray->direction, s.ray->time});
    found = closest_hit(*s.ray, hit);
  }

  s.normal = hit.world.shading_normal;
  if (effects.has(Effect::SurfaceRoughness) && s.m->surface_roughness > 0)
    s.normal = perturb_normal(s.normal, s.m->surface_roughness, rng);

  s.colours = {s.m->ambient * g.global_ambient, s.m->diffuse};  // eq. 4.5
  if (scene_.textured()) {
    const ObjectTexture& texture = scene_.texture(hit.world.object);
    if (!texture.empty())
      s.colours =
          textured_colours(texture, scene_.instances()[hit.world.object], hit.world, s.colours);
  }
  return true;
}

[[gnu::always_inline]] inline Rgb Tracer::finish_surface(const Surface& s, const Hit& hit,
                                                         Rgb color, int depth, double weight,
                                                         SampleStream& rng) {
  const SceneGlobals& g = scene_.scene().globals;
  const EffectSet& effects = effects_;
  if (depth < g.max_recursion_depth) {
    if (effects.has(Effect::Reflection) && weight * s.m->reflectivity > g.min_reflectivity)
      color += reflection(*s.ray, hit, *s.m, s.normal, depth, weight, s.media, rng);
    if (effects.has(Effect::Refraction) && weight * s.m->transparency > g.min_transparency)
      color += transmission(*s.ray, hit, *s.m, s.normal, depth, weight, s.media, s.crossing, rng);
  }
  if (effects.has(Effect::AtmosphericAttenuation) || effects.has(Effect::Fog))
    color = apply_atmosphere(color, s.travelled);
  return color;
}

}  // namespace tessera
