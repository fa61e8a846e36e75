#include "common/render/time_prediction.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <vector>

#include "common/render/render.h"
#include "common/stats/thread_cpu_clock.h"

namespace tessera {

std::vector<PixelCoord> probe_pixel_order(int width, int height, int max_pixels) {
  // A side x side grid of cell centres, visited with a stride near the golden ratio of the
  // count (and coprime with it), so the first k pixels of the probe are spread over the image.
  const int side = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(max_pixels))));
  const int count = side * side;
  int stride = static_cast<int>(0.618034 * count) | 1;
  while (std::gcd(stride, count) != 1) ++stride;
  std::vector<PixelCoord> order;
  for (int k = 0; k < count; ++k) {
    const int cell = static_cast<int>((static_cast<long long>(k) * stride) % count);
    order.push_back({(2 * (cell % side) + 1) * width / (2 * side),
                     (2 * (cell / side) + 1) * height / (2 * side)});
  }
  return order;
}

CostProbe probe_render_cost(const PreparedScene& scene, const RenderSettings& settings,
                            const ProbeBudget& budget) {
  // The probe's figure is this thread's CPU time: on a shared machine a probe preempted for a
  // few of its 30 ms would otherwise predict the job several times too slow. It is read only
  // where the probe starts and ends, since reading it costs a system call (about 0.5 µs, as
  // much as a cheap pixel); the budgets are on the wall clock, read after every pixel.
  using Wall = std::chrono::steady_clock;
  const auto cpu_seconds_since = [](ThreadCpuClock::time_point since) {
    return std::chrono::duration<double>(ThreadCpuClock::now() - since).count();
  };
  CostProbe probe;
  RenderStats stats;
  Rgb value;
  const std::vector<PixelCoord> order =
      probe_pixel_order(settings.width, settings.height, budget.max_pixels);
  const auto cpu_begin = ThreadCpuClock::now();
  const RenderInterrupt interrupt{
      .deadline = Wall::now() + std::chrono::duration_cast<Wall::duration>(
                                    std::chrono::duration<double>(budget.max_total_seconds))};
  // The first rays through a freshly prepared scene pay its page faults and cold caches, which
  // a worker pays once per job, not per pixel: a few pixels warm them up untimed.
  constexpr std::size_t kWarmUpPixels = 16;
  const std::size_t warm_up = std::min(kWarmUpPixels, order.size());
  long long finished = 0;  // warm-up included, for a probe cut short
  try {
    for (std::size_t i = 0; i < warm_up; ++i, ++finished)
      render_pixels(scene, settings, {&order[i], 1}, 0, {&value, 1}, stats, interrupt);
    const auto cpu_start = ThreadCpuClock::now();
    const auto start = Wall::now();
    for (const PixelCoord& pixel : order) {
      render_pixels(scene, settings, {&pixel, 1}, 0, {&value, 1}, stats, interrupt);
      ++finished;
      ++probe.pixels;
      if (std::chrono::duration<double>(Wall::now() - start).count() > budget.max_seconds) break;
    }
    probe.seconds = cpu_seconds_since(cpu_start);
  } catch (const RenderInterrupted&) {
    probe.cut_short = true;
    probe.pixels = finished;
    probe.seconds = cpu_seconds_since(cpu_begin);
  }
  return probe;
}

std::optional<double> predict_render_seconds(double seconds_per_pixel_pass, long long pixel_passes,
                                             int threads) {
  if (threads <= 0) return std::nullopt;
  return seconds_per_pixel_pass * static_cast<double>(pixel_passes) / threads;
}

}  // namespace tessera
