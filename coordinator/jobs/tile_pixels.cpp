#include "coordinator/jobs/tile_pixels.h"

#include <algorithm>
#include <cstdint>

#include "common/image/to_8bit.h"

namespace tessera {

namespace {

// Pixels converted at a time (on the stack).
constexpr std::size_t kChunk = 256;

// Writes `count` pixels' bytes (3 floats a pixel at `values`, at most kChunk pixels) at `out`,
// which has room for them; `previous` carries the last pixel's values from one call to the next.
void put_differences(char* out, std::uint8_t previous[3], const float* values, std::size_t count) {
  std::uint8_t now[3 * kChunk];
  const std::size_t n = 3 * count;
  to_8bit_run(values, n, now);
  for (std::size_t j = 0; j < 3; ++j)
    out[j] = static_cast<char>(static_cast<std::uint8_t>(now[j] - previous[j]));
  for (std::size_t j = 3; j < n; ++j)
    out[j] = static_cast<char>(static_cast<std::uint8_t>(now[j] - now[j - 3]));
  for (int c = 0; c < 3; ++c) previous[c] = now[n - 3 + c];
}

// Room for `bytes` more at the end of `out`: where to write them.
char* grow(std::string& out, std::size_t bytes) {
  const std::size_t at = out.size();
  out.resize(at + bytes);
  return out.data() + at;
}

}  // namespace

void append_tile_values(std::string& out, std::span<const float> values) {
  const std::size_t pixels = values.size() / 3;
  char* delta = grow(out, 3 * pixels);
  std::uint8_t previous[3] = {0, 0, 0};
  for (std::size_t done = 0; done < pixels; done += kChunk)
    put_differences(delta + 3 * done, previous, values.data() + 3 * done,
                    std::min(kChunk, pixels - done));
}

void append_tile_means(std::string& out, const UnitPixels& unit, const FrameBuffer& pixels) {
  char* delta = grow(out, 3 * static_cast<std::size_t>(pixel_count(unit)));
  std::uint8_t previous[3] = {0, 0, 0};
  for_each_run(unit, [&](PixelCoord first, int count, int stride) {
    for (int done = 0; done < count; done += static_cast<int>(kChunk)) {
      const int n = std::min(static_cast<int>(kChunk), count - done);
      float mean[3 * kChunk];
      pixels.mean_run({first.x + done * stride, first.y}, n, stride, mean);
      put_differences(delta, previous, mean, static_cast<std::size_t>(n));
      delta += 3 * static_cast<std::size_t>(n);
    }
  });
}

}  // namespace tessera
