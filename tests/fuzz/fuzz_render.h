// What the scene fuzz targets do with a scene that loaded: prepare it and render 3x2 pixels.
#pragma once

#include "common/render/prepared_scene.h"
#include "common/render/render.h"

namespace tessera::fuzz {

inline void prepare_and_render(const Scene& scene) {
  const PreparedScene prepared(scene, BvhMode::Sah);
  RenderSettings settings;
  settings.width = 3;
  settings.height = 2;
  RenderStats stats;
  render_image(prepared, settings, 1, stats);
}

}  // namespace tessera::fuzz
