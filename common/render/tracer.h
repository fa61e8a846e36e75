// Recursive ray tracing with the lighting model of `002_…` chapter 4 (eq. 4.1-4.24).
#pragma once

#include <cstdint>
#include <vector>

#include "common/accel/bvh_packet_traverse.h"
#include "common/render/interrupt.h"
#include "common/render/media.h"
#include "common/render/prepared_scene.h"
#include "common/render/sampler.h"
#include "common/settings/render_settings.h"
#include "common/stats/render_stats.h"

namespace tessera {

// How a ray came to be: the background rule (eq. 4.2) returns black for reflected rays.
enum class RayKind { Camera, Reflected, Refracted };

class Tracer {
 public:
  // The ray budget of one pixel sample: cones branch at every glossy, translucent or
  // soft-shadowed hit, so a sample could otherwise trace cone_samples^depth rays. Once a sample
  // has traced this many shadow, reflection and refraction rays since its first cone (before
  // it the path has not branched), every further cone of it is its central ray alone. The
  // count follows the sample's own depth-first order, so its value still depends only on the
  // scene, the settings and the pixel. The sample scenes, at the accuracy report's reference
  // settings, need at most 37,092 (docs/ARCHITECTURE.md).
  static constexpr std::uint64_t kMaxRaysPerSample = 1 << 20;
  // Rays between two looks at the RenderInterrupt: a few hundred microseconds of tracing.
  static constexpr int kPollRays = 256;

  // Renders with the effects render_effects(scene, settings) names; `settings` gives the
  // cone samples and the soft-shadow cone. `interrupt` is polled every kPollRays rays; when it
  // fires, trace() throws RenderInterrupted.
  Tracer(const PreparedScene& scene, const RenderSettings& settings, RenderStats& stats,
         const RenderInterrupt& interrupt = {});

  // The intensity arriving along `ray` (unit direction). `weight` is the product of the
  // reflectivities and transparencies along the path so far, compared with minReflectivity
  // and minTransparency; `depth` counts the reflections and refractions so far.
  Rgb trace(const Ray& ray, RayKind kind, int depth, double weight, const MediumStack& media,
            SampleStream& rng);

  // Camera rays of up to kPacketLanes neighbouring pixels, from `eye` along unit `directions`
  // at time 0 (ImageRays::through): their nearest hits, found by one walk of the scene BVH
  // (common/accel/bvh_packet_traverse.h) and kept for trace_packet_ray.
  void find_packet_hits(const Vec3& eye, const Vec3* directions, int count);
  // trace(ray, RayKind::Camera, 0, 1, media, rng) of ray `lane` of the last find_packet_hits,
  // bit for bit, its nearest hit already found.
  // Inline, so that a miss costs a pixel no call into the tracer beyond `missed`.
  Rgb trace_packet_ray(int lane, const MediumStack& media, SampleStream& rng) {
    // A miss (half the tori's camera rays) returns here, without trace_from_hit's frame and the
    // media and crossing it sets up for hits.
    if (!packet_found_[lane]) {
      poll_interrupt();
      return missed(packet_rays_[lane].direction, RayKind::Camera);
    }
    return trace_from_hit(packet_rays_[lane], packet_hits_[lane], RayKind::Camera, 0, 1.0, media,
                          rng);
  }

  // The nearest surface along `ray`, for the debug views; nothing when it meets none.
  std::optional<WorldHit> first_hit(const Ray& ray);

 private:
  // `instance` is the object the ray met, which media are keyed on; its surface's material and
  // texture are those of world.object (a child, for a boolean object).
  struct Hit {
    WorldHit world;
    std::uint32_t instance = 0;
    double time = 0;  // the ray's shutter time: rays leaving the hit keep it
  };
  // The media behind a transparent surface, and whether the ray was known to be inside the
  // object it leaves (it is not when the eye starts inside glass).
  struct Crossing {
    MediumStack after;
    bool known = true;
  };
  bool closest_hit(const Ray& ray, Hit& hit);
  // What a ray of `kind` along `direction` that meets nothing brings (eq. 4.2): black for a
  // reflected ray, else the sky or the background. Inline: as a call it cost each miss some 20
  // instructions, 0.5 % of the tori's.
  Rgb missed(const Vec3& direction, RayKind kind) const {
    if (kind == RayKind::Reflected) return Rgb{};  // eq. 4.2
    const SceneGlobals& g = scene_.scene().globals;
    return effects_.has(Effect::SkyGradient) ? g.sky->colour(unit_or_zero(direction))
                                             : g.background;
  }
  // trace() once closest_hit has found `hit` for `ray_in` (a miss is `missed`).
  Rgb trace_from_hit(const Ray& ray_in, Hit& hit, RayKind kind, int depth, double weight,
                     const MediumStack& media_in, SampleStream& rng);
  // Crosses the transparent surface at `hit`, together with every other transparent surface
  // that crosses the ray within rounding of it: coincident boundaries (the same sphere twice,
  // flush faces) are one interface, whichever of them closest_hit returned. `hit` becomes the
  // surface of the object that governs the interface, with an error bound covering them all,
  // so that rays leaving it start beyond every one.
  Crossing cross_interface(const Ray& ray, Hit& hit, const MediumStack& media);
  // A shadow feeler: for t in (0, t_max), 1 to a point light the ray's direction reaches,
  // infinite to a directional light.
  struct Feeler {
    Ray ray;
    double t_max;
  };
  // The feeler from the hit (at its time, pushed off its surface by `offset`, the hit's
  // spawn_offset for feelers) along unit `d` towards a light, directional or with `target` the
  // point on it the feeler aims at.
  Feeler feeler(const Hit& hit, const Vec3& offset, bool directional, const Vec3& d,
                const Vec3& target) const;
  // Eq. 4.24: the product of the transparencies of everything along the feeler.
  double shadow_factor(const Feeler& feeler);
  // shadow_factor of a hard shadow feeler from `hit` to Scene::lights[light], a point light or
  // spotlight, answered by the light's buffer where it can be (common/render/light_buffer.h):
  // without the walk when at most two objects can block it: their own tests alone, the hit's
  // own object's not even that when leaves_own_hull. The answer is shadow_factor's, bit for
  // bit; only the counts of BVH nodes and shape tests fall.
  double point_shadow(const Feeler& feeler, const Hit& hit, std::size_t light);
  // Whether the feeler along `d` (`d_squared` = dot(d, d)) from `hit` leaves the hit's object
  // outward, beyond a margin on the angle, where the object's surface is that of its convex hull
  // (a convex solid anywhere, a torus on its outer half): then that object cannot block it.
  bool leaves_own_hull(const Hit& hit, const Vec3& d, double d_squared) const;
  // Eq. 4.25-4.26: the share of `light` (unit direction `l`, `distance` away, infinite for a
  // directional light) that reaches the hit under soft shadows: the mean over a cone of feelers.
  // `offset` as for feeler().
  double soft_visibility(const Hit& hit, const Vec3& offset, const Light& light, const Vec3& l,
                         double distance, SampleStream& rng);
  // Eq. 4.4-4.12 and 4.24 at a hit: emissive, ambient, and every light's diffuse and specular.
  // `colours` are the material's after texturing (§4.3). Compiled for each shadow mode, and
  // for scenes with and without directional lights, so that the loop over the lights holds
  // no branch for an effect the render does not use (soft shadows, directional lights):
  // those branches cost a scene without them 0.5 % of its instructions.
  template <ShadowMode kShadows, bool kDirectionalLights>
  Rgb local_illumination(const Hit& hit, const Material& m, const SurfaceColours& colours,
                         const Vec3& normal, const Vec3& view_dir, SampleStream& rng);
  using Illumination = Rgb (Tracer::*)(const Hit&, const Material&, const SurfaceColours&,
                                       const Vec3&, const Vec3&, SampleStream&);
  static Illumination lighting_for(const EffectSet& effects);
  Rgb reflection(const Ray& ray, const Hit& hit, const Material& m, const Vec3& normal, int depth,
                 double weight, const MediumStack& media, SampleStream& rng);
  Rgb transmission(const Ray& ray, const Hit& hit, const Material& m, const Vec3& normal, int depth,
                   double weight, const MediumStack& media, const Crossing& crossing,
                   SampleStream& rng);
  // Eq. 4.20-4.23: depth cueing and fog over the distance the ray travelled.
  Rgb apply_atmosphere(const Rgb& color, double distance) const;
  // How far rays leave the hit's surface (surface_offset), at least `epsilon`, or a mesh's
  // epsilon when that is larger; and the origin of one such ray along `direction`.
  Vec3 spawn_offset(const Hit& hit, double epsilon) const;
  Vec3 spawn_origin(const Hit& hit, const Vec3& direction, double epsilon) const;
  std::uint64_t secondary_rays() const {
    return stats_.shadow_rays + stats_.reflection_rays + stats_.refraction_rays;
  }
  // Whether a cone may have all its rays: false once the sample has spent its ray budget,
  // when it also counts the pixel in stats_.ray_budget_pixels. trace_pixel raises
  // stats_.camera_rays once per sample and stats_.pixels once per pixel, after its samples:
  // they tell samples and pixels apart at no cost to renders without cones.
  bool cones_within_budget();
  // Counts a ray towards the next look at the interrupt.
  void poll_interrupt() {
    if (--poll_countdown_ == 0) check_interrupt();
  }
  void check_interrupt();

  const PreparedScene& scene_;
  RenderStats& stats_;
  EffectSet effects_;
  int cone_samples_;
  double shadow_cone_radius_;  // r_c of eq. 4.25
  Illumination illuminate_;    // local_illumination for the render's effects (lighting_for)
  // The cosine of each light's cut-off angle (used for spotlights), per Scene::lights: worked out
  // once here rather than at every hit a spotlight lights.
  std::vector<double> cos_cutoff_;
  RenderInterrupt interrupt_;
  int poll_countdown_ = kPollRays;
  static constexpr std::uint64_t kNone = ~std::uint64_t{0};
  std::uint64_t budget_sample_ = kNone;  // stats_.camera_rays of the sample being budgeted
  std::uint64_t budget_start_ = 0;       // secondary_rays() at that sample's first cone
  std::uint64_t budget_pixel_ = kNone;   // stats_.pixels of the last pixel counted as over it
  // The rays of the last find_packet_hits and their nearest hits.
  Ray packet_rays_[kPacketLanes];
  Hit packet_hits_[kPacketLanes];
  bool packet_found_[kPacketLanes] = {};
  // The eye of the last packets and, for each instance, that point in its object space
  // (object_origin): taken once, not at every shape test of a camera ray. `packet_eye_` is set
  // when packet_object_origins_ is not empty.
  Vec3 packet_eye_;
  std::vector<Vec3> packet_object_origins_;
};

}  // namespace tessera
