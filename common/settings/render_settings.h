// How to render: the accuracy knobs users set per render (CLI flags, job settings). Their
// names, ranges and help are in settings_schema.h.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "common/math/pixel_rect.h"
#include "common/scene/camera.h"
#include "common/scene/motion.h"  // kMaxTimeSamples
#include "common/settings/bvh_mode.h"

namespace tessera {

// shadowComputationMode (§4.2.1): no shadow feelers, one feeler per light, or a cone of them.
enum class ShadowMode { None, Hard, Soft };

// "none", "hard", "soft": the names of CLI flags and job settings.
const char* to_string(ShadowMode mode);
std::optional<ShadowMode> parse_shadow_mode(std::string_view name);

struct RenderSettings {
  int width = 640;
  int height = 480;
  int aa_samples = 1;       // 1, 5 or 9 samples per pixel per pass (§4.4)
  bool stochastic = false;  // jitter the sample positions (§4.4.2)
  double jitter = 1.0;      // jitter strength, in pixels (eq. 4.52 with block size 1)
  std::uint64_t seed = 0;   // keys every random number (render/sampler.h)
  int passes = 1;           // sample passes; the image is the mean of all passes
  int time_samples = 0;     // motion-blur times per camera sample (1..kMaxTimeSamples); 0: the
                            // scene's motionBlur count
  BvhMode bvh = BvhMode::Sah;
  ShadowMode shadows = ShadowMode::Hard;
  // nrOfConeSamples (§4.1.4): rays per gloss, translucency and soft-shadow cone, the central
  // one included; the central ray and eight around it, as in the manual's figure 4.1.
  int cone_samples = 9;
  // shadowFeelerJitterStrength (eq. 4.25): the soft-shadow cone's diameter one unit from the
  // point, so its radius r_c = strength / 2 (half-angle atan(r_c)).
  double shadow_jitter = 0.2;
  // Post-normalization (§4.6), a step on the finished image: when its highest component
  // exceeds 1 the image is scaled so that it becomes 1; then multiplied by the brightness.
  bool normalize_colors = false;
  double normalize_brightness = 1.0;
  // A rectangle of the image rendered alone (POV-Ray's +SC/+EC). Unset renders the whole image;
  // set, only these pixels, each bit for bit as in the whole image, in a frame of the full size
  // whose other pixels are black.
  std::optional<PixelRect> region = std::nullopt;
};

// The scene globals a job may override (the page's controls, Glazer §4.4.2): unset keeps the
// scene's value. Coordinator and worker apply them to the same parsed scene.
struct SceneOverrides {
  std::optional<int> max_depth;      // maxRecursionDepth
  std::optional<double> min_weight;  // minReflectivity and minTransparency
  // The camera setting: eye, look_at, up and view_angle (the format's own angle: SDL's
  // vertical viewAngle, VRML's fieldOfView on the smaller side). The loader puts it in place
  // of the scene's, so that a VRML headlight and Billboards follow it (load_scene).
  std::optional<Camera> camera;
  friend bool operator==(const SceneOverrides&, const SceneOverrides&) = default;
};

}  // namespace tessera
