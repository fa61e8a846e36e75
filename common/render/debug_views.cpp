#include "common/render/debug_views.h"

#include <algorithm>
#include <vector>

#include "common/render/render.h"
#include "common/render/tracer.h"

namespace tessera {

namespace {

// Black → red → yellow → white as `x` goes from 0 to 1.
Rgb heat(double x) {
  return {std::clamp(3 * x, 0.0, 1.0), std::clamp(3 * x - 1, 0.0, 1.0),
          std::clamp(3 * x - 2, 0.0, 1.0)};
}

}  // namespace

Image render_normals(const PreparedScene& scene, const RenderSettings& settings) {
  Image image(settings.width, settings.height);
  RenderStats stats;
  Tracer tracer(scene, settings, stats);
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const Ray ray = scene.camera().ray_through(x + 0.5, y + 0.5, settings.width, settings.height);
      if (const auto hit = tracer.first_hit(ray)) {
        const Vec3 c = (hit->shading_normal + Vec3{1, 1, 1}) * 0.5;
        image.set(x, y, {c.x, c.y, c.z});
      }
    }
  return image;
}

Image render_cost(const PreparedScene& scene, const RenderSettings& settings,
                  std::uint64_t& largest) {
  std::vector<std::uint64_t> counts;
  counts.reserve(static_cast<std::size_t>(settings.width) * settings.height);
  Rgb value;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      RenderStats stats;
      render_pass(scene, settings, {x, y, x + 1, y + 1}, 0, {&value, 1}, stats);
      const IntersectionCounters& c = stats.intersections;
      counts.push_back(c.shape_tests + c.triangle_tests + c.bvh_nodes);
    }
  largest = counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
  Image image(settings.width, settings.height);
  std::size_t i = 0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x, ++i)
      image.set(
          x, y,
          heat(largest > 0 ? static_cast<double>(counts[i]) / static_cast<double>(largest) : 0.0));
  return image;
}

}  // namespace tessera
