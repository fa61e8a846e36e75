#include "bench/accuracy/sweep.h"

#include <algorithm>

#include "common/render/prepared_scene.h"

namespace tessera {

namespace {

constexpr int kReferenceAa = 9;
constexpr int kReferencePasses = 16;  // 144 jittered samples a pixel
constexpr int kReferenceDepthBonus = 4;
constexpr int kMaxDepth = 16;
constexpr int kReferenceTimes = 16;        // per pass: with 16 jittered passes, 256 distinct times
constexpr int kReferenceConeSamples = 33;  // beyond the sweep's 17, jittered anew each pass

Variant variant(const std::string& knob, const std::string& label, RenderSettings s, int depth) {
  return {knob, label, s, depth};
}

}  // namespace

Sweep make_sweep(const Scene& scene, const RenderSettings& base) {
  const PreparedScene prepared(scene, BvhMode::Sah);
  const EffectSet& effects = prepared.effects();
  const int depth = scene.globals.max_recursion_depth;
  Sweep sweep;

  RenderSettings cheap = base;
  cheap.aa_samples = 1;
  cheap.stochastic = false;
  cheap.passes = 1;

  RenderSettings reference = cheap;
  reference.aa_samples = kReferenceAa;
  reference.stochastic = true;
  reference.passes = kReferencePasses;
  const bool lit = effects.has(Effect::HardShadows);
  const bool soft = lit && base.shadows == ShadowMode::Soft;
  const bool cones = effects.has(Effect::Gloss) || effects.has(Effect::Translucency) || soft;
  if (cones) reference.cone_samples = kReferenceConeSamples;
  const bool recursive = effects.has(Effect::Reflection) || effects.has(Effect::Refraction);
  const int reference_depth = recursive ? std::min(kMaxDepth, depth + kReferenceDepthBonus) : depth;
  const bool moving = effects.has(Effect::MotionBlur);
  if (moving) reference.time_samples = kReferenceTimes;
  std::string reference_label = "aa 9 jittered x 16 passes";
  if (moving) reference_label += ", 16 times";
  if (cones) reference_label += ", cones of 33";
  sweep.reference = variant("reference", reference_label, reference, reference_depth);

  for (int aa : {1, 5, 9}) {
    RenderSettings s = cheap;
    s.aa_samples = aa;
    sweep.variants.push_back(
        variant("anti-aliasing (regular)", "aa " + std::to_string(aa), s, depth));
  }
  for (int aa : {1, 5, 9}) {
    RenderSettings s = cheap;
    s.aa_samples = aa;
    s.stochastic = true;
    sweep.variants.push_back(
        variant("anti-aliasing (jittered)", "aa " + std::to_string(aa) + " jittered", s, depth));
  }
  for (double jitter : {0.25, 0.5, 1.0, 1.5}) {
    RenderSettings s = cheap;
    s.aa_samples = 5;
    s.stochastic = true;
    s.jitter = jitter;
    char label[32];
    std::snprintf(label, sizeof label, "aa 5, jitter %.2g", jitter);
    sweep.variants.push_back(variant("jitter strength", label, s, depth));
  }
  for (int passes : {1, 2, 4, 8, 16}) {
    RenderSettings s = cheap;
    s.stochastic = true;
    s.passes = passes;
    sweep.variants.push_back(
        variant("sample passes", std::to_string(passes) + " jittered passes", s, depth));
  }
  if (recursive) {
    for (int d = 0; d <= reference_depth; d += d < 4 ? 1 : 2)
      sweep.variants.push_back(variant("recursion depth", "depth " + std::to_string(d), cheap, d));
  } else {
    sweep.not_swept.push_back("recursion depth: nothing in the scene reflects or refracts");
  }
  if (moving) {
    for (int times : {1, 2, 4, 8, 16}) {
      RenderSettings s = cheap;
      s.time_samples = times;
      sweep.variants.push_back(
          variant("motion-blur time samples", std::to_string(times) + " times", s, depth));
    }
  } else {
    sweep.not_swept.push_back("motion-blur time samples: nothing in the scene moves");
  }
  // One cone-sample count serves gloss, translucency and soft shadows, as in the manual.
  if (cones) {
    for (int n : {1, 5, 9, 17}) {
      RenderSettings s = cheap;
      s.cone_samples = n;
      sweep.variants.push_back(variant("cone samples (gloss, translucency, soft shadows)",
                                       "cones of " + std::to_string(n), s, depth));
    }
  } else {
    sweep.not_swept.push_back(
        "cone samples: nothing in the scene is glossy or translucent, and shadows are not soft");
  }
  if (lit) {
    for (const ShadowMode mode : {ShadowMode::None, ShadowMode::Hard, ShadowMode::Soft}) {
      RenderSettings s = cheap;
      s.shadows = mode;
      const std::string label =
          mode == ShadowMode::None ? "no shadows" : std::string(to_string(mode)) + " shadows";
      sweep.variants.push_back(variant("shadow mode", label, s, depth));
    }
  } else {
    sweep.not_swept.push_back("shadow mode: the scene has no lights");
  }
  return sweep;
}

}  // namespace tessera
