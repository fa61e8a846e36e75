// The page's tile deltas (GET /api/jobs/{id}/tiles, coordinator/http/tile_deltas.h): decoded
// and painted as the page paints them (one layer per block side, finer layers over coarser),
// they show exactly the 8-bit image the coordinator would encode, at every point of a job; the
// log is bounded; the 8-bit values are the PNG's.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>

#include "common/image/image.h"
#include "common/image/to_8bit.h"
#include "coordinator/http/tile_deltas.h"
#include "coordinator/jobs/job.h"

namespace tessera {
namespace {

template <class T>
T take(const std::string& bytes, std::size_t& at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));
  at += sizeof(T);
  return value;
}

struct Answer {
  std::uint32_t next = 0, count = 0, flags = 0, pixels = 0;
};

using Rgb8 = std::array<std::uint8_t, 3>;

// The page's layers: per block side, one optional value per block.
struct Layers {
  int width, height;
  std::map<int, std::map<std::pair<int, int>, Rgb8>> by_step;

  // Paints every record of an answer; returns its header.
  Answer paint(const std::string& body) {
    Answer a;
    EXPECT_EQ(body.substr(0, 4), "TSD1");
    std::size_t at = 4;
    a.next = take<std::uint32_t>(body, at);
    a.count = take<std::uint32_t>(body, at);
    a.flags = take<std::uint32_t>(body, at);
    for (std::uint32_t r = 0; r < a.count; ++r) {
      const int x0 = take<std::uint16_t>(body, at), y0 = take<std::uint16_t>(body, at);
      const int x1 = take<std::uint16_t>(body, at), y1 = take<std::uint16_t>(body, at);
      const int step = take<std::uint16_t>(body, at);
      take<std::uint8_t>(body, at);  // level
      take<std::uint8_t>(body, at);  // pass
      const int flags = take<std::uint8_t>(body, at);
      take<std::uint8_t>(body, at);
      take<std::uint16_t>(body, at);  // stage
      take<std::uint32_t>(body, at);  // worker
      const std::uint32_t pixels = take<std::uint32_t>(body, at);
      take<double>(body, at);
      a.pixels += pixels;
      if (pixels == 0) continue;
      Rgb8 value{0, 0, 0};
      std::uint32_t seen = 0;
      for (int y = y0; y < y1; y += step)
        for (int x = x0; x < x1; x += step) {
          if ((flags & 1) && x % (2 * step) == 0 && y % (2 * step) == 0) continue;
          for (int c = 0; c < 3; ++c)
            value[c] = static_cast<std::uint8_t>(value[c] + static_cast<std::uint8_t>(body[at++]));
          by_step[step][{x / step, y / step}] = value;
          ++seen;
        }
      EXPECT_EQ(seen, pixels);
    }
    EXPECT_EQ(at, body.size());
    return a;
  }

  // What the stacked layers show at (x, y): the finest layer that has a value there.
  Rgb8 shown(int x, int y) const {
    for (const auto& [step, cells] : by_step)  // ascending: finest first
      if (auto it = cells.find({x / step, y / step}); it != cells.end()) return it->second;
    return {0, 0, 0};
  }
};

Job make_job(int w, int h, int passes) {
  JobSpec spec;
  spec.settings.width = w;
  spec.settings.height = h;
  spec.settings.passes = passes;
  PlanOptions plan{.width = w, .height = h, .passes = passes, .unit_pixels = 8};
  return Job(1, Bundle{"scene.sdl", "sdl", {{"scene.sdl", "sphere"}}}, spec, plan, 1);
}

// Values in [-0.1, 1.1], so that clamping is exercised, distinct per pixel and pass.
std::vector<float> values_for(const Job& job, int unit) {
  std::vector<float> v;
  const int pass = job.plan.stages[job.plan.units[unit].stage].pass;
  for (PixelCoord p : expand(job.plan.units[unit].pixels))
    for (int c = 0; c < 3; ++c)
      v.push_back(static_cast<float>((p.x * 37 + p.y * 91 + pass * 53 + c * 17) % 120) / 100.0f -
                  0.1f);
  return v;
}

void expect_shows_the_image(const Layers& layers, const Job& job) {
  const Image image = job.snapshot().image();
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Rgb c = image.get(x, y);
      const Rgb8 expected{to_8bit(static_cast<float>(c.r)), to_8bit(static_cast<float>(c.g)),
                          to_8bit(static_cast<float>(c.b))};
      ASSERT_EQ(layers.shown(x, y), expected) << x << "," << y;
    }
}

TEST(TileDeltas, PaintedAsThePageDoesTheyShowTheImageAtEveryStep) {
  Job job = make_job(13, 9, 3);  // levels of side 8, 4, 2, 1, then passes 1 and 2
  job.record_dispatch(0, Clock::now());
  // Levels overlap across workers: merge pass 0's units in a shuffled order, then the passes.
  std::vector<int> order;
  for (int u = 0; u < static_cast<int>(job.plan.units.size()); ++u) order.push_back(u);
  const auto levels_end = std::find_if(order.begin(), order.end(), [&](int u) {
    return job.plan.stages[job.plan.units[u].stage].level == 0;
  });
  std::shuffle(order.begin(), levels_end, std::mt19937(7));
  Layers layers{13, 9, {}};
  std::size_t since = 0;
  for (int u : order) {
    job.apply_result(u, values_for(job, u), RenderStats{}, Job::ResultSource{4, "w", Clock::now()});
    const Answer a = layers.paint(encode_tiles(job, since));
    EXPECT_EQ(a.count, 1u);
    EXPECT_EQ(a.flags, 0u);
    since = a.next;
    expect_shows_the_image(layers, job);
  }
  EXPECT_EQ(since, job.plan.units.size());
}

TEST(TileDeltas, APageBehindTheLogLoadsTheWholeImage) {
  Job job = make_job(16, 16, 1);
  job.record_dispatch(0, Clock::now());
  job.delta_log_bytes = 3 * 64;  // the newest units' 64 pixels
  for (int u = 0; u < static_cast<int>(job.plan.units.size()); ++u)
    job.apply_result(u, values_for(job, u), RenderStats{});
  ASSERT_GT(job.delta_first(), 0u);
  EXPECT_LE(job.delta_bytes(), job.delta_log_bytes);
  Layers layers{16, 16, {}};
  const Answer behind = layers.paint(encode_tiles(job, 0));
  EXPECT_EQ(behind.flags & 1, 1u);  // whole
  EXPECT_EQ(behind.pixels, 0u);     // the records' places, for the worker overlay, no pixels
  EXPECT_EQ(behind.count, job.tiles_next());
  const Answer recent = layers.paint(encode_tiles(job, job.delta_first()));
  EXPECT_EQ(recent.flags & 1, 0u);
  EXPECT_EQ(recent.pixels * 3, job.delta_bytes());
}

TEST(TileDeltas, AFinishedJobKeepsOnlyItsNewestDeltasUntilItsImageIsEncoded) {
  Job job = make_job(16, 16, 2);
  job.record_dispatch(0, Clock::now());
  job.delta_log_bytes = 3 * 64;
  for (int u = 0; u < static_cast<int>(job.plan.units.size()); ++u)
    job.apply_result(u, values_for(job, u), RenderStats{});
  const std::size_t next = job.tiles_next();
  job.finish(JobState::Done, "", Clock::now());
  EXPECT_EQ(job.frame_buffer().width(), 0);
  EXPECT_EQ(job.tiles_next(), next);
  EXPECT_LT(job.tiles().size(), next);  // only the records that give pixels stay
  EXPECT_EQ(job.tiles_first(), job.delta_first());
  Layers layers{16, 16, {}};
  const Answer last = layers.paint(encode_tiles(job, next - 1));
  EXPECT_EQ(last.flags, 2u);  // finished, not whole: read from the final pixels
  EXPECT_EQ(last.count, 1u);
  EXPECT_GT(last.pixels, 0u);
  EXPECT_EQ(layers.paint(encode_tiles(job, 0)).flags, 3u);  // too far behind: the PNG
  job.keep_encodings({});  // the final image is encoded: its pixels are gone
  EXPECT_EQ(layers.paint(encode_tiles(job, next - 1)).flags, 3u);
  EXPECT_EQ(layers.paint(encode_tiles(job, next)).flags, 2u);  // caught up: nothing to load
  job.free_buffers();  // what the coordinator does 30 s later
  EXPECT_TRUE(job.tiles().empty());
  EXPECT_EQ(job.tiles_next(), next);
}

TEST(TileDeltas, APageThatAsksRarelyShowsTheImageAsItIsNow) {
  Job job = make_job(13, 9, 4);
  job.record_dispatch(0, Clock::now());
  Layers layers{13, 9, {}};
  std::size_t since = 0;
  for (int u = 0; u < static_cast<int>(job.plan.units.size()); ++u) {
    job.apply_result(u, values_for(job, u), RenderStats{});
    if (u % 7 != 6) continue;  // several merges between two answers
    const Answer a = layers.paint(encode_tiles(job, since));
    EXPECT_EQ(a.count, job.tiles_next() - since);
    since = a.next;
    expect_shows_the_image(layers, job);
  }
}

TEST(TileDeltas, AnAreaPreviewShowsItsOwnValues) {
  JobSpec spec;
  spec.settings.width = 16;
  spec.settings.height = 16;
  Job job(1, Bundle{"scene.sdl", "sdl", {{"scene.sdl", "sphere"}}}, spec,
          PlanOptions{.width = 16, .height = 16, .preview = PreviewMode::Area, .unit_pixels = 8},
          1);
  job.record_dispatch(0, Clock::now());
  ASSERT_TRUE(job.plan.stages[job.plan.units[0].stage].preview_only);
  const std::vector<float> values = values_for(job, 0);
  job.apply_result(0, values, RenderStats{});
  Layers layers{16, 16, {}};
  const Answer a = layers.paint(encode_tiles(job, 0));
  ASSERT_EQ(a.pixels, values.size() / 3);
  // Its pixels are the blocks' centres, painted as the multiples of step that start the blocks.
  const UnitPixels& unit = job.plan.units[0].pixels;
  std::size_t i = 0;
  for (int y = first_multiple_at_or_after(unit.rect.y0, unit.step); y < unit.rect.y1;
       y += unit.step)
    for (int x = first_multiple_at_or_after(unit.rect.x0, unit.step); x < unit.rect.x1;
         x += unit.step, ++i) {
      const Rgb8 expected{to_8bit(values[3 * i]), to_8bit(values[3 * i + 1]),
                          to_8bit(values[3 * i + 2])};
      EXPECT_EQ(layers.by_step.at(unit.step).at({x / unit.step, y / unit.step}), expected);
    }
  EXPECT_EQ(i, values.size() / 3);
}

TEST(TileDeltas, TheLogGrowsWithTheImage) {
  EXPECT_EQ(make_job(64, 64, 1).delta_log_bytes, kDeltaLogBytes);
  JobSpec spec;
  spec.settings.width = 2500;
  spec.settings.height = 2400;
  const Job large(1, Bundle{"scene.sdl", "sdl", {{"scene.sdl", "sphere"}}}, spec,
                  PlanOptions{.width = 2500, .height = 2400}, 1);
  EXPECT_EQ(large.delta_log_bytes, 2500u * 2400u * 3 / 2);  // over 8 MiB: 1.5 bytes a pixel
}

TEST(TileDeltas, EightBitValuesAreThePngs) {
  Image image(256, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 256; ++x) {
      const double v = (x + 256 * y) / 700.0 - 0.2;  // -0.2 .. 1.26, every rounding boundary
      image.set(x, y, {v, v + 0.5 / 255, v - 0.25 / 255});
    }
  const std::string png = encode_image(image, "png");
  const auto path = std::filesystem::temp_directory_path() / "tessera_to_8bit_test.png";
  std::ofstream(path, std::ios::binary) << png;
  const Image decoded = read_image(path.string());
  std::filesystem::remove(path);
  for (std::size_t i = 0; i < image.rgb.size(); ++i)
    ASSERT_EQ(to_8bit(image.rgb[i]), static_cast<int>(std::lround(decoded.rgb[i] * 255.0f)))
        << image.rgb[i];
}

}  // namespace
}  // namespace tessera
