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
  // few of its 30 ms would otherwise predict the job several times too slow. Its deadline, a
  // guard on the request's wall time, stays on the wall clock.
  using Clock = ThreadCpuClock;
  const auto seconds_between = [](Clock::time_point from, Clock::time_point to) {
    return std::chrono::duration<double>(to - from).count();
  };
  CostProbe probe;
  RenderStats stats;
  Rgb value;
  const std::vector<PixelCoord> order =
      probe_pixel_order(settings.width, settings.height, budget.max_pixels);
  const RenderInterrupt interrupt{
      .deadline = std::chrono::steady_clock::now() +
                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double>(budget.max_total_seconds))};
  const auto begin = Clock::now();
  // The first rays through a freshly prepared scene pay its page faults and cold caches, which
  // a worker pays once per job, not per pixel: a few pixels warm them up untimed.
  constexpr std::size_t kWarmUpPixels = 16;
  const std::size_t warm_up = std::min(kWarmUpPixels, order.size());
  long long finished = 0;  // warm-up included, for a probe cut short
  auto pixel_start = begin;
  try {
    for (std::size_t i = 0; i < warm_up; ++i, ++finished) {
      pixel_start = Clock::now();
      render_pixels(scene, settings, {&order[i], 1}, 0, {&value, 1}, stats, interrupt);
    }
    const auto start = Clock::now();
    for (const PixelCoord& pixel : order) {
      pixel_start = Clock::now();
      render_pixels(scene, settings, {&pixel, 1}, 0, {&value, 1}, stats, interrupt);
      ++finished;
      ++probe.pixels;
      probe.seconds = seconds_between(start, Clock::now());
      if (probe.seconds > budget.max_seconds) break;
    }
  } catch (const RenderInterrupted&) {
    const auto now = Clock::now();
    probe.cut_short = true;
    probe.pixels = finished;
    probe.seconds = seconds_between(begin, now);
    probe.unfinished_pixel_seconds = seconds_between(pixel_start, now);
  }
  return probe;
}

std::optional<double> predict_render_seconds(double seconds_per_pixel_pass, long long pixel_passes,
                                             int threads) {
  if (threads <= 0) return std::nullopt;
  return seconds_per_pixel_pass * static_cast<double>(pixel_passes) / threads;
}

}  // namespace tessera
