// Debug views (issue 3): images that show what the tracer sees and what it costs instead of
// the shaded render, for finding wrong normals and expensive regions.
#pragma once

#include <cstdint>

#include "common/image/image.h"
#include "common/render/prepared_scene.h"
#include "common/settings/render_settings.h"

namespace tessera {

// One camera ray through each pixel's centre; the shading normal of its first hit as a colour,
// (n + 1) / 2 per axis (so +x is red, +y green, +z blue), black where it meets nothing.
Image render_normals(const PreparedScene& scene, const RenderSettings& settings);

// The intersection work of each pixel's first pass with every sample and secondary ray (shape
// tests, triangle tests and BVH nodes visited, added up) as a heat ramp from black through red
// and yellow to white at the image's largest count, which `largest` receives.
Image render_cost(const PreparedScene& scene, const RenderSettings& settings,
                  std::uint64_t& largest);

}  // namespace tessera
