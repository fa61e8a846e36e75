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
#include "common/render/sample_lattice.h"
#include "common/render/tracer.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

namespace {

constexpr int kTileSize = 16;

// Whether a sample fits the float32 that the frame buffer, the wire and the image keep: a NaN,
// an infinity or a finite value beyond FLT_MAX (a light of intensity 1e300 gives one) would
// reach the image as an infinity or a NaN.
bool fits_float(const Rgb& c) {
  constexpr double kMax = std::numeric_limits<float>::max();
#if defined(__SSE2__)
  // r and g in one register: one compare and one branch where the scalar form takes two.
  const __m128d abs_mask = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffff));
  const __m128d rg = _mm_and_pd(_mm_set_pd(c.g, c.r), abs_mask);
  return _mm_movemask_pd(_mm_cmple_pd(rg, _mm_set1_pd(kMax))) == 3 && std::fabs(c.b) <= kMax;
#else
  return std::fabs(c.r) <= kMax && std::fabs(c.g) <= kMax && std::fabs(c.b) <= kMax;
#endif
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

// One camera sample, `trace(air)` for a ray that starts in air; a value the image cannot keep
// counts in stats.nan_samples and becomes black.
template <class Trace>
Rgb camera_sample(RenderStats& stats, Trace&& trace) {
  // Default-initialized, not MediumStack{}: value-initializing zeroes all its entries (264
  // bytes) for every sample.
  MediumStack air;
  ++stats.camera_rays;
  const Rgb c = trace(air);
  if (fits_float(c)) return c;
  ++stats.nan_samples;  // counted and reported, never written into the image
  return Rgb{};
}

// The camera sample along `ray`.
Rgb trace_camera_sample(Tracer& tracer, const Ray& ray, SampleStream& rng, RenderStats& stats) {
  return camera_sample(stats, [&](const MediumStack& air) {
    return tracer.trace(ray, RayKind::Camera, 0, 1.0, air, rng);
  });
}

// One pass of one pixel: the mean of sample(j, k), sample k at motion-blur time j, added in
// that order whoever traced them.
template <class Sample>
Rgb pixel_mean(std::uint32_t aa, int times, RenderStats& stats, Sample&& sample) {
  Rgb sum;
  for (int j = 0; j < times; ++j)
    for (std::uint32_t k = 0; k < aa; ++k) sum += sample(j, k);
  const std::size_t count = static_cast<std::size_t>(aa) * static_cast<std::size_t>(times);
  stats.samples += count;
  ++stats.pixels;
  return sum * (1.0 / static_cast<double>(count));
}

// What every pixel of one pass shares: the tracer, the camera, the sample grid.
struct PassContext {
  const PreparedScene& scene;
  const RenderSettings& settings;
  const ImageRays& camera;
  Tracer& tracer;
  int pass;
  RenderStats& stats;
  std::span<const SampleOffset> offsets;
};

// A pixel that traces its own samples. With T motion-blur times and A samples per pixel,
// sample k at time j of pass p has the global sample index (p * T + j) * A + k, which keys its
// random numbers (without motion blur T is 1: p * A + k).
Rgb trace_pixel(const PassContext& c, int x, int y) {
  const auto aa = static_cast<std::uint32_t>(c.offsets.size());
  const int times = time_samples(c.scene, c.settings);
  const bool moving = c.scene.effects().has(Effect::MotionBlur);
  const double shutter = c.scene.scene().globals.motion_blur_frame_length;
  return pixel_mean(aa, times, c.stats, [&](int j, std::uint32_t k) {
    const auto first = (static_cast<std::uint32_t>(c.pass) * static_cast<std::uint32_t>(times) +
                        static_cast<std::uint32_t>(j)) *
                       aa;
    SampleStream rng(c.settings.seed, static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                     first + k);
    double px = x + c.offsets[k].dx, py = y + c.offsets[k].dy;
    if (c.settings.stochastic) {
      px += (rng.next() - 0.5) * c.settings.jitter;
      py += (rng.next() - 0.5) * c.settings.jitter;
    }
    Ray ray = c.camera.through(px, py);
    if (moving) ray.time = shutter_time(shutter, j, times, c.settings.jitter, rng.next());
    return trace_camera_sample(c.tracer, ray, rng, c.stats);
  });
}

// Whether every pixel traces one sample, at the same offset, with no random number drawn before
// its camera ray (no jitter, no motion blur): then neighbours' rays may walk the BVH together.
bool one_fixed_sample(const PassContext& c) {
  return c.offsets.size() == 1 && !c.settings.stochastic && time_samples(c.scene, c.settings) == 1;
}

// The pixels of trace_pixel for one_fixed_sample, kPacketLanes at a time: their camera rays'
// nearest hits found by one walk of the scene BVH (common/accel/bvh_packet_traverse.h), then
// each pixel traced on from its hit, in order, as trace_pixel would (the same ray, random
// numbers and statistics, so the same value).
template <class CheckInterrupt>
void trace_packets(const PassContext& c, std::span<const PixelCoord> pixels, std::span<Rgb> out,
                   const CheckInterrupt& check_interrupt) {
  const SampleOffset offset = c.offsets[0];
  const auto lanes_from = [&](std::size_t i) {
    return static_cast<int>(std::min<std::size_t>(kPacketLanes, pixels.size() - i));
  };
  // The camera directions of the packet at pixel i.
  const auto aim = [&](std::size_t i, Vec3(&directions)[kPacketLanes]) {
    const int count = lanes_from(i);
    static_assert(kPacketLanes == 4, "ImageRays::directions_through takes four points");
    double px[kPacketLanes], py[kPacketLanes];
    for (int l = 0; l < kPacketLanes; ++l) {  // lanes past `count` repeat its last pixel
      const PixelCoord& p = pixels[i + static_cast<std::size_t>(std::min(l, count - 1))];
      px[l] = p.x + offset.dx;
      py[l] = p.y + offset.dy;
    }
    c.camera.directions_through(px, py, directions);
  };
  // Each packet's directions are found before the previous packet's pixels are traced: their
  // chain of divisions and square roots, which the walk waits on, then runs beside that work.
  // Out of the loop, where their initializers (zeroes) run once, not at every packet:
  // directions_through writes all four.
  Vec3 directions[2][kPacketLanes];
  if (!pixels.empty()) aim(0, directions[0]);
  for (std::size_t i = 0, k = 0; i < pixels.size(); i += kPacketLanes, k ^= 1) {
    const int count = lanes_from(i);
    check_interrupt();  // once a packet: four pixels are short enough between two looks
    c.tracer.find_packet_hits(c.camera.eye(), directions[k], count);
    if (i + kPacketLanes < pixels.size()) aim(i + kPacketLanes, directions[k ^ 1]);
    for (int l = 0; l < count; ++l) {
      const PixelCoord p = pixels[i + l];
      SampleStream rng(c.settings.seed, static_cast<std::uint32_t>(p.x),
                       static_cast<std::uint32_t>(p.y), static_cast<std::uint32_t>(c.pass));
      out[i + l] = pixel_mean(1, 1, c.stats, [&](int, std::uint32_t) {
        return camera_sample(c.stats, [&](const MediumStack& air) {
          return c.tracer.trace_packet_ray(l, air, rng);
        });
      });
    }
  }
}

// A pixel whose samples are points of `lattice`, traced by the first pixel that needs them.
// Only for samples that depend on their position alone, so no random number is drawn from the
// stream a sample is given.
Rgb shared_pixel(const PassContext& c, SampleLattice& lattice, int x, int y) {
  const auto aa = static_cast<std::uint32_t>(c.offsets.size());
  return pixel_mean(aa, 1, c.stats, [&](int, std::uint32_t k) {
    return lattice.at(x, y, c.offsets[k], [&](double px, double py) {
      SampleStream unused(c.settings.seed, static_cast<std::uint32_t>(x),
                          static_cast<std::uint32_t>(y), k);
      return trace_camera_sample(c.tracer, c.camera.through(px, py), unused, c.stats);
    });
  });
}

// The smallest rectangle that holds every pixel of `pixels`.
PixelRect bounds_of(std::span<const PixelCoord> pixels) {
  PixelRect r{pixels.front().x, pixels.front().y, pixels.front().x + 1, pixels.front().y + 1};
  for (const PixelCoord& p : pixels) {
    r.x0 = std::min(r.x0, p.x);
    r.y0 = std::min(r.y0, p.y);
    r.x1 = std::max(r.x1, p.x + 1);
    r.y1 = std::max(r.y1, p.y + 1);
  }
  return r;
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
  std::vector<PixelCoord> pixels;
  pixels.reserve(static_cast<std::size_t>(rect.area()));
  for (int y = rect.y0; y < rect.y1; ++y)
    for (int x = rect.x0; x < rect.x1; ++x) pixels.push_back({x, y});
  render_pixels(scene, settings, pixels, pass, out, stats, interrupt);
}

void render_pixels(const PreparedScene& scene, const RenderSettings& settings,
                   std::span<const PixelCoord> pixels, int pass, std::span<Rgb> out,
                   RenderStats& stats, const RenderInterrupt& interrupt) {
  if (pixels.empty()) return;
  // One tracer for all the pixels: building it (it works out the render's effects) per pixel
  // cost 0.5 % of a render at one sample per pixel.
  Tracer tracer(scene, settings, stats, interrupt);
  const ImageRays camera(scene.camera(), settings.width, settings.height);
  const PassContext context{
      scene, settings, camera, tracer, pass, stats, regular_sample_offsets(settings.aa_samples)};
  // Checked before each pixel starts, on the packet path before each packet (the tracer also
  // looks during long pixels).
  const auto check_interrupt = [&] {
    if (interrupt.armed() && interrupt.requested()) throw RenderInterrupted();
  };
  // The pixels' bounds only with more than one sample a pixel, without which worth_a_lattice
  // is false: a pass over the pixels (13 instructions each) spent for nothing otherwise.
  if (settings.aa_samples > 1 &&
      samples_depend_on_position_only(render_effects(scene, settings), settings)) {
    const PixelRect bounds = bounds_of(pixels);
    if (worth_a_lattice(static_cast<long long>(pixels.size()), bounds.area(),
                        settings.aa_samples)) {
      SampleLattice lattice(bounds);
      for (std::size_t i = 0; i < pixels.size(); ++i) {
        check_interrupt();
        out[i] = shared_pixel(context, lattice, pixels[i].x, pixels[i].y);
      }
      return;
    }
  }
  if (one_fixed_sample(context)) {
    trace_packets(context, pixels, out, check_interrupt);
    return;
  }
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    check_interrupt();
    out[i] = trace_pixel(context, pixels[i].x, pixels[i].y);
  }
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

  // Tiles own disjoint pixels, so threads write the image without locking. Each thread
  // averages a tile's passes in a tile-sized frame buffer, in pass order as on the coordinator,
  // and writes their means into the image when the tile is done. A frame buffer of the whole
  // image cost more: a page fault for every 4 kB of it first written (14 bytes a pixel, freshly
  // mapped) and, after the threads, a pass over it on one (docs/PERFORMANCE.md, "The second
  // thread").
  Image image(settings.width, settings.height);
  std::atomic<long long> next{0}, done{0};
  std::mutex stats_mutex;
  // The first exception of any thread (RenderInterrupted, or running out of memory): the
  // others take no further tile, and it is rethrown once they have all stopped.
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  auto work = [&] {
    RenderStats local;
    std::vector<Rgb> values(kTileSize * kTileSize);
    FrameBuffer tile(kTileSize, kTileSize);
    try {
      for (long long t; !failed && (t = next.fetch_add(1)) < tile_count;) {
        const int tx = static_cast<int>(t % tiles_x), ty = static_cast<int>(t / tiles_x);
        const PixelRect rect{area.x0 + tx * kTileSize, area.y0 + ty * kTileSize,
                             std::min(area.x1, area.x0 + (tx + 1) * kTileSize),
                             std::min(area.y1, area.y0 + (ty + 1) * kTileSize)};
        if (settings.passes == 1) {
          // One pass is its own mean: written straight into the image, as the tile's buffer
          // would give it back (its float sum of the one value, from +0, divided by 1).
          render_pass(scene, settings, rect, 0, values, local, interrupt);
          std::size_t i = 0;
          for (int y = rect.y0; y < rect.y1; ++y)
            for (int x = rect.x0; x < rect.x1; ++x, ++i) {
              const std::size_t at = image.index(x, y);
              image.rgb[at] = 0.0f + static_cast<float>(values[i].r);
              image.rgb[at + 1] = 0.0f + static_cast<float>(values[i].g);
              image.rgb[at + 2] = 0.0f + static_cast<float>(values[i].b);
            }
        } else {
          tile.clear();
          for (int pass = 0; pass < settings.passes; ++pass) {
            render_pass(scene, settings, rect, pass, values, local, interrupt);
            std::size_t i = 0;
            for (int y = 0; y < rect.height(); ++y)
              for (int x = 0; x < rect.width(); ++x, ++i) {
                const float rgb[3] = {static_cast<float>(values[i].r),
                                      static_cast<float>(values[i].g),
                                      static_cast<float>(values[i].b)};
                tile.add_pass(x, y, rgb);
              }
          }
          for (int y = 0; y < rect.height(); ++y)
            for (int x = 0; x < rect.width(); ++x)
              image.set(rect.x0 + x, rect.y0 + y, tile.mean(x, y));
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
  if (settings.normalize_colors) post_normalize(image, settings.normalize_brightness);
  stats.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return image;
}

}  // namespace tessera
