#include "common/render/frame_buffer.h"

#include "common/progressive/plan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>
#include <vector>

#include <unistd.h>

namespace tessera {
namespace {

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Runs of every stride, merged with add_run, leave the frame buffer as add_pass a pixel at a
// time does, bit for bit; mean_run shows mean() rounded to float.
TEST(FrameBuffer, RunsMergeAndShowAsSinglePixelsDo) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> value(-0.25f, 4.0f);
  constexpr int kWidth = 67, kHeight = 9;
  FrameBuffer by_run(kWidth, kHeight), by_pixel(kWidth, kHeight);
  for (int round = 0; round < 3000; ++round) {
    const int stride = 1 + round % 5, y = round % kHeight;
    const int x = static_cast<int>(rng() % 7);
    const int count = 1 + static_cast<int>(rng() % ((kWidth - 1 - x) / stride + 1));
    std::vector<float> rgb(3 * static_cast<std::size_t>(count));
    for (float& v : rgb) v = value(rng);
    by_run.add_run({x, y}, count, stride, rgb.data());
    for (int i = 0; i < count; ++i) by_pixel.add_pass(x + i * stride, y, &rgb[3 * i]);

    std::vector<float> shown(3 * static_cast<std::size_t>(count));
    by_run.mean_run({x, y}, count, stride, shown.data());
    for (int i = 0; i < count; ++i) {
      const Rgb mean = by_pixel.mean(x + i * stride, y);
      ASSERT_TRUE(same_bits(shown[3 * i], static_cast<float>(mean.r))) << round << " " << i;
      ASSERT_TRUE(same_bits(shown[3 * i + 1], static_cast<float>(mean.g)));
      ASSERT_TRUE(same_bits(shown[3 * i + 2], static_cast<float>(mean.b)));
    }
  }
  const Image a = by_run.resolve(), b = by_pixel.resolve();
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      ASSERT_EQ(by_run.passes_at(x, y), by_pixel.passes_at(x, y));
      ASSERT_EQ(a.get(x, y), b.get(x, y)) << x << "," << y;
    }
}

// The float quotient mean_run takes equals the double one rounded to float for every pass
// count, also for sums whose quotient lies near a rounding boundary.
TEST(FrameBuffer, MeanOfAnyPassCountRoundsAsTheDoubleQuotientDoes) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<std::uint32_t> bits(0x3a000000u, 0x46000000u);  // 5e-4 .. 8192
  for (int passes = 1; passes <= 300; ++passes) {
    FrameBuffer frame(1, 1);
    for (int p = 0; p < passes; ++p) {
      float rgb[3];
      for (float& v : rgb) {
        const std::uint32_t b = bits(rng);
        std::memcpy(&v, &b, sizeof v);
        v /= static_cast<float>(passes);
      }
      frame.add_pass(0, 0, rgb);
    }
    float shown[3];
    frame.mean_run({0, 0}, 1, 1, shown);
    const Rgb mean = frame.mean(0, 0);
    EXPECT_TRUE(same_bits(shown[0], static_cast<float>(mean.r))) << passes;
    EXPECT_TRUE(same_bits(shown[1], static_cast<float>(mean.g))) << passes;
    EXPECT_TRUE(same_bits(shown[2], static_cast<float>(mean.b))) << passes;
  }
}

TEST(FrameBuffer, ARunWithAFullPixelAddsNothing) {
  FrameBuffer frame(4, 1);
  const float one[3] = {1, 1, 1};
  for (std::uint32_t p = 0; p < FrameBuffer::kMaxPasses; ++p) frame.add_pass(2, 0, one);
  const float run[12] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  EXPECT_THROW(frame.add_run({0, 0}, 4, 1, run), std::length_error);
  EXPECT_EQ(frame.passes_at(0, 0), 0u);
  EXPECT_EQ(frame.passes_at(1, 0), 0u);
  float shown[3];
  frame.mean_run({0, 0}, 1, 1, shown);
  EXPECT_EQ(shown[0], 0.0f);  // no passes: black
}

// A cleared frame buffer is a new one: passes added after clear() average as if none came
// before (render_image reuses one for tile after tile).
TEST(FrameBuffer, ClearedIsLikeNew) {
  FrameBuffer reused(3, 2), fresh(3, 2);
  const float before[3] = {5, -7, 9}, after[3] = {0.25f, 0.5f, 2};
  for (int p = 0; p < 3; ++p) reused.add_pass(1, 1, before);
  reused.add_pass(2, 0, before);
  reused.clear();
  EXPECT_EQ(reused.passes_at(1, 1), 0u);
  EXPECT_EQ(reused.mean(2, 0), Rgb{});
  reused.add_pass(1, 1, after);
  fresh.add_pass(1, 1, after);
  EXPECT_EQ(reused.passes_at(1, 1), 1u);
  EXPECT_EQ(reused.resolve(), fresh.resolve());
}

// A job's units merged with their whole-image passes counted by cell (the plan's pass tiles)
// and pass 0 over the levels by level tile leave the frame buffer as counting every pass by
// pixel does, bit for bit, while they merge and at the end: whole images and regions (whose
// clipped tiles are not tiles), both previews. A whole image's units are all counted by tile,
// so its buffer never takes the per-pixel counts (12 bytes a pixel); a region's takes them at
// its first clipped tile. A run counted by pixel after all of them takes them, zeroed, too.
TEST(FrameBuffer, PassesCountedByTileAverageAsByPixel) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> value(-0.25f, 4.0f);
  struct Case {
    PlanOptions options;
    bool by_pixel;  // some units counted by pixel: the per-pixel counts taken
  };
  const Case cases[] = {
      {{.width = 300, .height = 170, .passes = 4, .unit_pixels = 900}, false},
      {{.width = 300, .height = 170, .passes = 3, .preview = PreviewMode::Area, .unit_pixels = 700},
       false},
      {{.width = 300, .height = 170, .passes = 3, .progressive = false, .unit_pixels = 1024},
       false},
      {{.width = 300,
        .height = 170,
        .passes = 3,
        .unit_pixels = 400,
        .region = PixelRect{17, 30, 250, 160}},
       true},
      {{.width = 300, .height = 170, .passes = 1, .unit_pixels = 64}, false},
  };
  for (const auto& [options, takes_counts] : cases) {
    const Plan plan = make_plan(options);
    // As a coordinator job's: deferred, its memory taken at its first merge.
    FrameBuffer by_cell = FrameBuffer::deferred(plan.width, plan.height);
    FrameBuffer by_pixel(plan.width, plan.height);
    by_cell.count_by_units(plan);
    by_cell.take_memory();
    const std::size_t pixels = static_cast<std::size_t>(plan.width) * plan.height;
    EXPECT_EQ(by_cell.bytes(), 12 * pixels);
    for (const WorkUnit& unit : plan.units) {
      if (plan.stages[unit.stage].preview_only) continue;
      std::vector<float> rgb(3 * static_cast<std::size_t>(unit.cost));
      for (float& v : rgb) v = value(rng);
      by_cell.add_unit(unit.pixels, rgb.data());
      by_pixel.add_unit(unit.pixels, rgb.data());
      const PixelCoord probe = expand(unit.pixels).back();
      ASSERT_EQ(by_cell.passes_at(probe.x, probe.y), by_pixel.passes_at(probe.x, probe.y));
      const PixelCoord corner{unit.pixels.rect.x0, unit.pixels.rect.y0};
      const int shown = std::min(8, plan.width - corner.x);
      std::vector<float> a(3 * static_cast<std::size_t>(shown)), b(a.size());
      by_cell.mean_run(corner, shown, 1, a.data());
      by_pixel.mean_run(corner, shown, 1, b.data());
      ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
    }
    for (int y = 0; y < plan.height; ++y)
      for (int x = 0; x < plan.width; ++x)
        ASSERT_EQ(by_cell.passes_at(x, y), by_pixel.passes_at(x, y)) << x << "," << y;
    EXPECT_EQ(by_cell.resolve(), by_pixel.resolve());
    EXPECT_EQ(by_cell.bytes(), (takes_counts ? 14 : 12) * pixels);
    EXPECT_EQ(by_pixel.bytes(), 14 * pixels);
    std::vector<float> row(3 * static_cast<std::size_t>(plan.width) / 2);
    for (float& v : row) v = value(rng);
    by_cell.add_run({1, 60}, plan.width / 2, 2, row.data());
    by_pixel.add_run({1, 60}, plan.width / 2, 2, row.data());
    EXPECT_EQ(by_cell.bytes(), 14 * pixels);
    for (int y = 0; y < plan.height; ++y)
      for (int x = 0; x < plan.width; ++x)
        ASSERT_EQ(by_cell.passes_at(x, y), by_pixel.passes_at(x, y)) << x << "," << y;
    EXPECT_EQ(by_cell.resolve(), by_pixel.resolve());
  }
}

// Every unit of a progressive plan but the region's clipped ones is counted once for its tile
// (a cell or a level's), touching no pixel's count: a pixel with the most passes it can count
// by pixel still takes its unit's pass.
TEST(FrameBuffer, UnitsCountedByTileLeaveThePixelsCounts) {
  const Plan plan = make_plan({.width = 300, .height = 170, .passes = 2, .unit_pixels = 500});
  FrameBuffer frame(plan.width, plan.height);
  frame.count_by_units(plan);
  const float one[3] = {1.0f, 1.0f, 1.0f};
  std::vector<bool> full(static_cast<std::size_t>(plan.width) * plan.height);
  for (const WorkUnit& unit : plan.units) {
    const PixelCoord p = expand(unit.pixels).back();
    if (!full[static_cast<std::size_t>(p.y) * plan.width + p.x]) {
      for (std::uint32_t n = 0; n < FrameBuffer::kMaxPasses; ++n) frame.add_pass(p.x, p.y, one);
      full[static_cast<std::size_t>(p.y) * plan.width + p.x] = true;
    }
    const std::uint32_t before = frame.passes_at(p.x, p.y);
    const std::vector<float> rgb(3 * static_cast<std::size_t>(unit.cost), 1.0f);
    ASSERT_NO_THROW(frame.add_unit(unit.pixels, rgb.data())) << unit.stage;
    ASSERT_EQ(frame.passes_at(p.x, p.y), before + 1) << unit.stage;
  }
}

// The process's mapped and resident memory in bytes (Linux).
struct Memory {
  long mapped = -1, resident = -1;
};
Memory memory() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  Memory m;
  if (f == nullptr || std::fscanf(f, "%ld %ld", &m.mapped, &m.resident) != 2) m = {};
  if (f != nullptr) std::fclose(f);
  const long page = sysconf(_SC_PAGESIZE);
  return {m.mapped * page, m.resident * page};
}
long resident_bytes() { return memory().resident; }

// A new frame buffer's zeros cost nothing until its pixels are written: the coordinator creates
// one per job on its io thread (56 MB at 2048x2048).
TEST(FrameBuffer, ANewFrameBufferTakesMemoryOnlyWhereItIsWritten) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's allocator touches what it allocates";
#endif
  const long before = resident_bytes();
  ASSERT_GT(before, 0);
  FrameBuffer frame(4096, 4096);  // 192 MiB of sums; 32 more of counts at the first add_run
  EXPECT_LT(resident_bytes() - before, 16l << 20);
  EXPECT_EQ(frame.passes_at(4095, 4095), 0u);
  EXPECT_EQ(frame.mean(17, 3000).r, 0.0);
  const std::vector<float> row(3 * 4096, 1.0f);
  frame.add_run({0, 100}, 4096, 1, row.data());
  EXPECT_EQ(frame.mean(4095, 100).g, 1.0);
  EXPECT_EQ(frame.mean(4095, 101).g, 0.0);
}

// A deferred frame buffer (a coordinator job's) maps nothing before it takes its memory, which
// a queued job would otherwise hold, taken from the pool: until then it reads as black.
TEST(FrameBuffer, ADeferredFrameBufferMapsNothingUntilItTakesItsMemory) {
  const long before = memory().mapped;
  ASSERT_GT(before, 0);
  std::vector<FrameBuffer> frames(8, FrameBuffer::deferred(2048, 2048));  // 8 x 56 MiB
  EXPECT_LT(memory().mapped - before, 16l << 20);
  FrameBuffer& frame = frames.front();
  EXPECT_FALSE(frame.has_memory());
  EXPECT_EQ(frame.passes_at(2047, 2047), 0u);
  EXPECT_EQ(frame.mean(17, 2000).r, 0.0);
  std::vector<float> shown(3 * 5, 1.0f);
  frame.mean_run({10, 20}, 5, 2, shown.data());
  EXPECT_TRUE(std::all_of(shown.begin(), shown.end(), [](float v) { return v == 0.0f; }));
  const Image image = FrameBuffer::deferred(3, 2).resolve();
  EXPECT_EQ(image.get(2, 1).b, 0.0);
  frame.take_memory();
  EXPECT_TRUE(frame.has_memory());
  const float one[3] = {1, 1, 1};
  frame.add_pass(2047, 2047, one);
  EXPECT_EQ(frame.mean(2047, 2047).g, 1.0);
}

}  // namespace
}  // namespace tessera
