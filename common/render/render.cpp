#include "common/render/render.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>

#include "common/render/frame_buffer.h"
#include "common/render/pixel_samples.h"
#include "common/render/post_normalization.h"
#include "common/render/tracer.h"

namespace tessera {

namespace {

constexpr int kTileSize = 16;

// Whether a sample fits the float32 that the frame buffer, the wire and the image keep: a NaN,
// an infinity or a finite value beyond FLT_MAX (a light of intensity 1e300 gives one) would
// reach the image as an infinity or a NaN.
bool fits_float(const Rgb& c) {
  constexpr double kMax = std::numeric_limits<float>::max();
  return std::fabs(c.r) <= kMax && std::fabs(c.g) <= kMax && std::fabs(c.b) <= kMax;
}

// Motion-blur times per camera sample: the settings' count, else the scene's; 1 when nothing
// moves.
int time_samples(const PreparedScene& scene, const RenderSettings& settings) {
  if (!scene.effects().has(Effect::MotionBlur)) return 1;
  return settings.time_samples > 0 ? settings.time_samples
                                   : scene.scene().globals.motion_blur_time_samples;
}

// Time sample j of `count` over a shutter of `length` frames centred on 0 (eq. 4.53-4.54):
// the middle of the j-th of `count` equal stretches, jittered within it by `jitter` times
// `u` - 1/2. The seeds jitter the times by the render's jitter strength, a share of a block
// (eq. 4.52) that may exceed 1 for positions; a time's block is its stretch, so the strength
// is capped at 1 here: the times stay stratified and inside the shutter.
double shutter_time(double length, int j, int count, double jitter, double u) {
  return length * ((j + 0.5 + std::min(jitter, 1.0) * (u - 0.5)) / count - 0.5);
}

// One pass of one pixel: the mean of its samples. With T motion-blur times and A samples per
// pixel, sample k at time j of pass p has the global sample index (p * T + j) * A + k, which
// keys its random numbers (without motion blur T is 1: p * A + k). `tracer` counts into `stats`.
// Throws RenderInterrupted when `interrupt` (null when the render has none) has fired by the
// time the pixel starts.
Rgb trace_pixel(const PreparedScene& scene, const RenderSettings& settings, const ImageRays& camera,
                Tracer& tracer, int x, int y, int pass, RenderStats& stats,
                const RenderInterrupt* interrupt) {
  if (interrupt && interrupt->requested()) throw RenderInterrupted();
  const std::span<const SampleOffset> offsets = regular_sample_offsets(settings.aa_samples);
  const auto aa = static_cast<std::uint32_t>(offsets.size());
  const int times = time_samples(scene, settings);
  const bool moving = scene.effects().has(Effect::MotionBlur);
  const double shutter = scene.scene().globals.motion_blur_frame_length;
  // Camera rays start in air. Default-initialized, not MediumStack{}: value-initializing zeroes
  // all its entries (264 bytes) for every sample.
  MediumStack air;
  Rgb sum;
  for (int j = 0; j < times; ++j) {
    const auto first = (static_cast<std::uint32_t>(pass) * static_cast<std::uint32_t>(times) +
                        static_cast<std::uint32_t>(j)) *
                       aa;
    for (std::uint32_t k = 0; k < aa; ++k) {
      SampleStream rng(settings.seed, static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                       first + k);
      double px = x + offsets[k].dx, py = y + offsets[k].dy;
      if (settings.stochastic) {
        px += (rng.next() - 0.5) * settings.jitter;
        py += (rng.next() - 0.5) * settings.jitter;
      }
      Ray ray = camera.through(px, py);
      if (moving) ray.time = shutter_time(shutter, j, times, settings.jitter, rng.next());
      ++stats.camera_rays;
      Rgb c = tracer.trace(ray, RayKind::Camera, 0, 1.0, air, rng);
      if (!fits_float(c)) {
        ++stats.nan_samples;  // counted and reported, never written into the image
        c = Rgb{};
      }
      sum += c;
    }
  }
  const std::size_t count = static_cast<std::size_t>(aa) * static_cast<std::size_t>(times);
  stats.samples += count;
  ++stats.pixels;
  return sum * (1.0 / static_cast<double>(count));
}

}  // namespace

EffectSet render_effects(const PreparedScene& scene, const RenderSettings& settings) {
  EffectSet effects = scene.effects();
  if (settings.aa_samples > 1 || (settings.stochastic && settings.passes > 1))
    effects.add(Effect::AntiAliasing);
  // A cone of one ray, or of radius 0, is the single ray it would replace.
  const bool cones = settings.cone_samples > 1;
  if (!cones) {
    effects.remove(Effect::Gloss);
    effects.remove(Effect::Translucency);
  }
  if (settings.shadows == ShadowMode::None) {
    effects.remove(Effect::HardShadows);
  } else if (settings.shadows == ShadowMode::Soft && cones && settings.shadow_jitter > 0 &&
             effects.has(Effect::HardShadows)) {
    effects.remove(Effect::HardShadows);
    effects.add(Effect::SoftShadows);
  }
  return effects;
}

void render_pass(const PreparedScene& scene, const RenderSettings& settings, const PixelRect& rect,
                 int pass, std::span<Rgb> out, RenderStats& stats,
                 const RenderInterrupt& interrupt) {
  // One tracer for all the pixels: building it (it works out the render's effects) per pixel
  // cost 0.5 % of a render at one sample per pixel.
  Tracer tracer(scene, settings, stats, interrupt);
  const ImageRays camera(scene.camera(), settings.width, settings.height);
  const RenderInterrupt* per_pixel = interrupt.armed() ? &interrupt : nullptr;
  std::size_t i = 0;
  for (int y = rect.y0; y < rect.y1; ++y)
    for (int x = rect.x0; x < rect.x1; ++x)
      out[i++] = trace_pixel(scene, settings, camera, tracer, x, y, pass, stats, per_pixel);
}

void render_pixels(const PreparedScene& scene, const RenderSettings& settings,
                   std::span<const PixelCoord> pixels, int pass, std::span<Rgb> out,
                   RenderStats& stats, const RenderInterrupt& interrupt) {
  Tracer tracer(scene, settings, stats, interrupt);
  const ImageRays camera(scene.camera(), settings.width, settings.height);
  const RenderInterrupt* per_pixel = interrupt.armed() ? &interrupt : nullptr;
  for (std::size_t i = 0; i < pixels.size(); ++i)
    out[i] = trace_pixel(scene, settings, camera, tracer, pixels[i].x, pixels[i].y, pass, stats,
                         per_pixel);
}

Image render_image(const PreparedScene& scene, const RenderSettings& settings, int threads,
                   RenderStats& stats, const ProgressFn& progress,
                   const RenderInterrupt& interrupt) {
  const auto start = std::chrono::steady_clock::now();
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // The region's pixels, or the whole image's; the frame keeps the full size either way.
  const PixelRect area = settings.region.value_or(PixelRect{0, 0, settings.width, settings.height});
  const int tiles_x = (area.width() + kTileSize - 1) / kTileSize;
  const int tiles_y = (area.height() + kTileSize - 1) / kTileSize;
  const long long tile_count = static_cast<long long>(tiles_x) * tiles_y;

  // Tiles own disjoint pixels, so threads add to the frame buffer without locking; each
  // pixel receives its passes in pass order, as on the coordinator.
  FrameBuffer frame(settings.width, settings.height);
  std::atomic<long long> next{0}, done{0};
  std::mutex stats_mutex;
  // The first exception of any thread (RenderInterrupted, or running out of memory): the
  // others take no further tile, and it is rethrown once they have all stopped.
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  auto work = [&] {
    RenderStats local;
    std::vector<Rgb> values(kTileSize * kTileSize);
    try {
      for (long long t; !failed && (t = next.fetch_add(1)) < tile_count;) {
        const int tx = static_cast<int>(t % tiles_x), ty = static_cast<int>(t / tiles_x);
        const PixelRect rect{area.x0 + tx * kTileSize, area.y0 + ty * kTileSize,
                             std::min(area.x1, area.x0 + (tx + 1) * kTileSize),
                             std::min(area.y1, area.y0 + (ty + 1) * kTileSize)};
        for (int pass = 0; pass < settings.passes; ++pass) {
          render_pass(scene, settings, rect, pass, values, local, interrupt);
          std::size_t i = 0;
          for (int y = rect.y0; y < rect.y1; ++y)
            for (int x = rect.x0; x < rect.x1; ++x, ++i) {
              const float rgb[3] = {static_cast<float>(values[i].r),
                                    static_cast<float>(values[i].g),
                                    static_cast<float>(values[i].b)};
              frame.add_pass(x, y, rgb);
            }
        }
        const long long finished = done.fetch_add(1) + 1;
        if (progress) progress(finished, tile_count);
      }
    } catch (...) {
      failed = true;
      const std::lock_guard lock(stats_mutex);
      if (!failure) failure = std::current_exception();
    }
    const std::lock_guard lock(stats_mutex);
    stats += local;
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  Image image = frame.resolve();
  if (settings.normalize_colors) post_normalize(image, settings.normalize_brightness);
  stats.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return image;
}

}  // namespace tessera
