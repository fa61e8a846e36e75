#include "common/render/tracer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <new>
#include <numbers>

#include "common/accel/bvh_traverse.h"
#include "common/math/float_error.h"
#include "common/math/portable_math.h"
#include "common/math/whole_power.h"
#include "common/render/cone.h"
#include "common/render/optics.h"
#include "common/render/render.h"

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
    cos_cutoff_.push_back(tessera::cos(light.spot.cutoff_degrees * std::numbers::pi / 180));
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

namespace {

// v, read a component at a time. ImageRays::directions_through stores each component alone, just
// before find_packet_hits copies them; the copy's 16-byte load of x and y could not take its
// data from those two 8-byte stores (store forwarding fails) and waited until they reached the
// cache. The empty asm keeps the components in registers of their own: GCC otherwise merges the
// loads again.
[[gnu::always_inline]] inline Vec3 read_by_component(const Vec3& v) {
  double x = v.x, y = v.y, z = v.z;
#if defined(__SSE2__)
  asm("" : "+x"(x), "+x"(y), "+x"(z));
#endif
  return {x, y, z};
}

}  // namespace

void Tracer::find_packet_hits(const Vec3& eye, const Vec3* directions, int count) {
  const std::vector<Instance>& instances = scene_.instances();
  double t_max[kPacketLanes];
  // All four lanes in straight-line code, not a loop over `count`; lanes past it repeat its
  // last ray and are not walked.
  for (int l = 0; l < kPacketLanes; ++l) {
    packet_rays_[l].direction = read_by_component(directions[std::min(l, count - 1)]);
    packet_found_[l] = false;
    packet_hits_[l].time = 0;
    t_max[l] = kInfinity;
  }
  // The rays' origins and times, like the object origins, only when the eye moves: a render's
  // packets share one.
  if (packet_object_origins_.empty() || !same_bits(eye, packet_eye_)) {
    for (Ray& ray : packet_rays_) {
      ray.origin = eye;
      ray.time = 0;
    }
    packet_eye_ = eye;
    packet_object_origins_.resize(instances.size());
    for (std::size_t i = 0; i < instances.size(); ++i)
      packet_object_origins_[i] = object_origin(instances[i], eye);
  }
  static_assert(kPacketLanes == 4);  // intersect_instance_packet's lanes
  WorldHit* const world_hits[kPacketLanes] = {&packet_hits_[0].world, &packet_hits_[1].world,
                                              &packet_hits_[2].world, &packet_hits_[3].world};
  // The leaf visit of closest_hit's traverse_bvh, for the rays that reach the leaf together: each
  // shape is tested for them together (intersect_instance_packet), each ray's limit shrinking with
  // its hits as its own visit's would.
  traverse_bvh_packet_leaves(
      scene_.bvh(), PacketRays(packet_rays_, count), t_max, stats_.intersections.bvh_nodes,
      [&](unsigned lanes, std::uint32_t first, std::uint32_t size) {
        for (std::uint32_t i = first; i < first + size; ++i) {
          const std::uint32_t index = scene_.bvh().primitive_order[i];
          for (unsigned m = intersect_instance_packet(instances[index], packet_rays_, lanes,
                                                      packet_object_origins_[index], t_max,
                                                      world_hits, stats_.intersections);
               m != 0; m &= m - 1) {
            const int l = std::countr_zero(m);
            packet_hits_[l].instance = index;
            packet_found_[l] = true;
            t_max[l] = packet_hits_[l].world.t;
          }
        }
      });
}

std::optional<WorldHit> Tracer::first_hit(const Ray& ray) {
  Hit hit;
  if (!closest_hit(ray, hit)) return std::nullopt;
  return hit.world;
}

double Tracer::shadow_factor(const Feeler& feeler) {
  ++stats_.shadow_rays;
  poll_interrupt();
  const Ray& ray = feeler.ray;
  const std::vector<Instance>& instances = scene_.instances();
  const std::vector<SceneObject>& objects = scene_.scene().objects;
  double factor = 1;
  // Each object counts once, however often the feeler crosses its surface (eq. 4.24).
  traverse_bvh(
      scene_.bvh(), ray, feeler.t_max, stats_.intersections.bvh_nodes,
      [&](std::uint32_t index, double t_limit) {
        std::uint32_t object = 0;
        if (!occluded_instance(instances[index], ray, t_limit, object, stats_.intersections))
          return t_limit;
        factor *= objects[object].material.transparency;
        return factor > 0 ? t_limit : -1.0;
      });
  return factor;
}

// Forced inline into point_shadow, its one caller: as a call it cost the demo's render 0.65 % of
// its instructions (the call, and the candidates spilled around it).
[[gnu::always_inline]] inline bool Tracer::leaves_own_hull(const Hit& hit, const Vec3& d,
                                                           double d_squared) const {
  // A convex solid cannot block a feeler that leaves it outward: the feeler starts on the outer
  // side of the plane that touches the solid there (the offset put it beyond the hit's
  // rounding) and moves away from it; the margin on the angle covers the normal's rounding.
  // A torus's outer half (rho >= R) lies on the boundary of its convex hull, with the same
  // normal: a feeler leaving it outward leaves the hull. Which of these the object is comes from
  // the prepared scene: deciding it here (a bit of a vector<bool>, then the shape's variant)
  // cost the tori's render 0.24 % of its instructions.
  constexpr double kLeastCosine = 1e-6;
  const double along = dot(hit.world.normal, d);
  if (!(along > 0 && along * along > kLeastCosine * kLeastCosine * d_squared)) return false;
  const OwnHull& hull = scene_.own_hull(hit.instance);
  if (hull.kind == OwnHull::Kind::Convex) return true;
  if (hull.kind != OwnHull::Kind::TorusOuterHalf) return false;
  const Vec3& p = hit.world.object_point;
  return p.x * p.x + p.y * p.y > hull.torus_radius_squared * (1 + kLeastCosine);
}

// Forced inline into local_illumination, its one caller: as a call it cost its saved registers
// and arguments on every feeler.
[[gnu::always_inline]] inline double Tracer::point_shadow(const Feeler& feeler, const Hit& hit,
                                                          std::size_t light) {
  const LightBuffer* buffer = scene_.light_buffer(light);
  if (!buffer) return shadow_factor(feeler);
  const LightBuffer::Candidates candidates = buffer->candidates(feeler.ray.origin);
  if (candidates.walk) return shadow_factor(feeler);
  ++stats_.shadow_rays;
  // No other object can block the feeler: each candidate's own test is all the walk would
  // have found, and with at most two factors their product does not depend on their order.
  // The two are tested one after the other, not in a loop over `candidates.ids`: the loop kept
  // the candidates in memory and cost its own counter and bound. Forced inline: as a call of its
  // own it cost more than the loop.
  const auto factor_of = [&](std::uint32_t index) __attribute__((always_inline)) {
    // The lookup's squared distance is dot(d, d) bit for bit: the buffer's light is the
    // feeler's target, Light::position, and d = light - origin is the exact negation of the
    // lookup's origin - light.
    if (index == hit.instance && leaves_own_hull(hit, feeler.ray.direction, candidates.squared))
      return 1.0;
    std::uint32_t object = 0;
    if (!occluded_instance(scene_.instances()[index], feeler.ray, feeler.t_max, object,
                           stats_.intersections))
      return 1.0;
    return scene_.scene().objects[object].material.transparency;
  };
  // An opaque object blocks it: the walk's product would hold a factor 0.
  double factor = 0;
  if (!candidates.blocked) {
    // 1 * first is first, so the walk's product from 1 is first, then first * second.
    factor = candidates.count == 0 ? 1 : factor_of(candidates.ids[0]);
    if (candidates.count == 2 && factor > 0) factor *= factor_of(candidates.ids[1]);
  }
  // Polled last: before the tests, the candidates stayed in memory across its rare call.
  poll_interrupt();
  return factor;
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

template <ShadowMode kShadows, bool kDirectionalLights>
Rgb Tracer::local_illumination(const Hit& hit, const Material& m, const SurfaceColours& colours,
                               const Vec3& normal, const Vec3& view_dir, SampleStream& rng) {
  const Scene& scene = scene_.scene();
  const SceneGlobals& g = scene.globals;
  const double opacity = 1 - m.transparency;  // eq. 4.6, 4.10, 4.11

  Rgb color = m.emissive;  // eq. 4.4
  Rgb ambient = colours.ambient_term;
  if (!m.retain_ambient_color) ambient *= opacity;
  color += ambient;
  if (!colours.lit) return color;
  // Every feeler leaves the hit by the same offset; only its side depends on the light.
  Vec3 feeler_offset;
  if constexpr (kShadows != ShadowMode::None)
    feeler_offset = spawn_offset(hit, g.shadow_feeler_epsilon);

  const double diffuse_scale = m.retain_diffuse_color ? 1 : opacity;
  const double specular_scale = m.retain_specular_reflection ? 1 : opacity;
  const bool has_specular = !m.specular.is_zero() && specular_scale > 0;
  for (std::size_t index = 0; index < scene.lights.size(); ++index) {
    const Light& light = scene.lights[index];
    const bool directional = kDirectionalLights && light.is_directional;
    if (directional && !light.lights(hit.world.object)) continue;
    Vec3 l;
    double distance = 0;
    if (!towards_light(light, directional, hit.world.point, l, distance)) continue;

    // Spotlight: zero outside the cut-off, cos^exponent inside (§4.1.3); the power is taken
    // below, once the point is known to be lit.
    double cos_alpha = 1;
    if (light.is_spot) {
      cos_alpha = std::clamp(dot(-l, light.spot.direction), -1.0, 1.0);
      if (cos_alpha < cos_cutoff_[index]) continue;
    }

    const double n_dot_l = facing(dot(normal, l), m.light_back_faces);
    double n_dot_h = 0;
    if (has_specular) {
      // The halfway vector -V + L vanishes when light and view are opposite: no highlight.
      const Vec3 h = normalize_or(l - view_dir, Vec3{});
      n_dot_h = facing(dot(normal, h), m.light_back_faces);
    }
    if (n_dot_l <= 0 && n_dot_h <= 0) continue;

    double attenuation = 1;  // eq. 4.12
    if (effects_.has(Effect::LightAttenuation) && !directional) {
      if (distance > light.radius) continue;
      const LightAttenuation& a = light.attenuation ? *light.attenuation : g.light_attenuation;
      const double denominator =
          a.constant + a.linear * distance + a.quadratic * distance * distance;
      if (denominator > 1) attenuation = 1 / denominator;
    }

    double shadow = 1;  // eq. 4.24-4.26: the share of the light that reaches the hit
    if constexpr (kShadows == ShadowMode::Hard) {
      if (light.casts_shadows)
        shadow = directional ? shadow_factor(feeler(hit, feeler_offset, true, l, light.position))
                             : point_shadow(feeler(hit, feeler_offset, false, l, light.position),
                                            hit, index);
    } else if constexpr (kShadows == ShadowMode::Soft) {
      if (light.casts_shadows)
        shadow = soft_visibility(hit, feeler_offset, light, l, distance, rng);
    }
    if (shadow <= 0) continue;
    const double cone = light.is_spot && light.spot.exponent != 0
                            ? shading_power(std::max(cos_alpha, 0.0), light.spot.exponent)
                            : 1;

    Rgb contribution = colours.diffuse * light.color * (n_dot_l * diffuse_scale);  // eq. 4.8
    if (n_dot_h > 0)                                                               // eq. 4.9
      contribution +=
          m.specular * light.color * (shading_power(n_dot_h, m.specular_exponent) * specular_scale);
    color += contribution * (attenuation * shadow * cone);  // eq. 4.7
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
    const double f =
        fog->exponential
            ? (distance < fog->end ? tessera::exp(-distance / (fog->end - distance)) : 0.0)
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
  if (!closest_hit(ray_in, hit)) {
    poll_interrupt();
    return missed(ray_in.direction, kind);
  }
  return trace_from_hit(ray_in, hit, kind, depth, weight, media_in, rng);
}

Rgb Tracer::trace_from_hit(const Ray& ray_in, Hit& hit, RayKind kind, int depth, double weight,
                           const MediumStack& media_in, SampleStream& rng) {
  poll_interrupt();
  const Scene& scene = scene_.scene();
  const SceneGlobals& g = scene.globals;
  const EffectSet& effects = effects_;

  // The ray itself until it passes a false interface, then its continuation. Not copied up
  // front: its caller has just written its origin a component at a time, and a copy reads it
  // two at a time, which waits for those stores to reach the cache (store forwarding fails).
  const Ray* ray = &ray_in;
  std::optional<Ray> continued;
  MediumStack media = media_in;
  double travelled = 0;
  const Material* m = nullptr;
  Crossing crossing;
  bool found = true;
  for (int skipped = 0;; ++skipped) {
    if (!found) return missed(ray->direction, kind);
    travelled += hit.world.t;
    m = &scene.objects[hit.world.object].material;
    if (!effects.has(Effect::Refraction) || !(m->transparency > g.min_transparency)) break;
    crossing = cross_interface(*ray, hit, media);
    m = &scene.objects[hit.world.object].material;
    // A transparent surface whose crossing leaves the governing medium unchanged is a false
    // interface: it neither shades nor refracts.
    if (skipped == kMaxFalseInterfaces || !crossing.known ||
        crossing.after.top().instance != media.top().instance)
      break;
    media = crossing.after;
    // A whole Ray, made before emplace replaces what `ray` may point to (Clang 14 has no
    // parenthesized aggregate initialization either).
    ray = &continued.emplace(
        Ray{spawn_origin(hit, ray->direction, g.transparency_epsilon), ray->direction, ray->time});
    found = closest_hit(*ray, hit);
  }

  Vec3 normal = hit.world.shading_normal;
  if (effects.has(Effect::SurfaceRoughness) && m->surface_roughness > 0)
    normal = perturb_normal(normal, m->surface_roughness, rng);

  SurfaceColours colours{m->ambient * g.global_ambient, m->diffuse};  // eq. 4.5
  if (scene_.textured()) {
    const ObjectTexture& texture = scene_.texture(hit.world.object);
    if (!texture.empty())
      colours = textured_colours(texture, scene_.instances()[hit.world.object], hit.world, colours);
  }
  Rgb color = (this->*illuminate_)(hit, *m, colours, normal, ray->direction, rng);
  if (depth < g.max_recursion_depth) {
    if (effects.has(Effect::Reflection) && weight * m->reflectivity > g.min_reflectivity)
      color += reflection(*ray, hit, *m, normal, depth, weight, media, rng);
    if (effects.has(Effect::Refraction) && weight * m->transparency > g.min_transparency)
      color += transmission(*ray, hit, *m, normal, depth, weight, media, crossing, rng);
  }
  if (effects.has(Effect::AtmosphericAttenuation) || effects.has(Effect::Fog))
    color = apply_atmosphere(color, travelled);
  return color;
}

}  // namespace tessera
