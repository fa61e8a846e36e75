// The settings the accuracy report measures: each accuracy knob the scene uses, one at a time
// from a cheap base, and the converged reference they are all compared with (issue 5).
#pragma once

#include <string>
#include <vector>

#include "common/scene/scene.h"
#include "common/settings/render_settings.h"

namespace tessera {

struct Variant {
  std::string knob;   // the curve it belongs to, e.g. "anti-aliasing (regular)"
  std::string label;  // e.g. "aa 5"
  RenderSettings settings;
  int max_depth = 0;  // maxRecursionDepth the render uses
};

struct Sweep {
  Variant reference;                   // high settings: what "converged" means for this scene
  std::vector<Variant> variants;       // grouped by knob, cheapest first within a knob
  std::vector<std::string> not_swept;  // knobs left out, each with the reason
};

// `base` gives the image size and seed; the scene's maxRecursionDepth is the depth of every
// variant but the depth sweep's.
Sweep make_sweep(const Scene& scene, const RenderSettings& base);

}  // namespace tessera
