#include "coordinator/http/tile_deltas.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>

#include "coordinator/jobs/tile_pixels.h"

namespace tessera {

static_assert(std::endian::native == std::endian::little, "the tiles format is little-endian");

namespace {

template <class T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

}  // namespace

std::string encode_tiles(const Job& job, std::size_t since) {
  const std::size_t next = job.tiles_next();
  since = std::min(since, next);
  // Behind the log, or a normalized job (whose shown values change with every merge).
  const bool whole = since < job.delta_first() || job.spec.settings.normalize_colors;
  const std::size_t first = std::max(since, job.tiles_first());
  std::string out = "TSD1";
  put<std::uint32_t>(out, 0);  // next and count, once known
  put<std::uint32_t>(out, 0);
  put<std::uint32_t>(out, (whole ? 1u : 0u) | (job.finished_state() ? 2u : 0u));
  std::size_t end = first, pixel_bytes = 0;
  for (; end < next && (pixel_bytes < kTilesAnswerBytes || end == first); ++end) {
    const TileRecord& t = job.tiles()[end - job.tiles_first()];
    const WorkUnit& unit = job.plan.units[static_cast<std::size_t>(t.unit)];
    const Stage& stage = job.plan.stages[unit.stage];
    const std::size_t pixels = whole ? 0 : static_cast<std::size_t>(unit.cost);
    put<std::uint16_t>(out, static_cast<std::uint16_t>(unit.pixels.rect.x0));
    put<std::uint16_t>(out, static_cast<std::uint16_t>(unit.pixels.rect.y0));
    put<std::uint16_t>(out, static_cast<std::uint16_t>(unit.pixels.rect.x1));
    put<std::uint16_t>(out, static_cast<std::uint16_t>(unit.pixels.rect.y1));
    put<std::uint16_t>(out, static_cast<std::uint16_t>(unit.pixels.step));
    put<std::uint8_t>(out, static_cast<std::uint8_t>(stage.level));
    put<std::uint8_t>(out, static_cast<std::uint8_t>(stage.pass));
    put<std::uint8_t>(out, static_cast<std::uint8_t>((unit.pixels.exclude > 0 ? 1u : 0u) |
                                                     (stage.preview_only ? 2u : 0u)));
    put<std::uint8_t>(out, 0);
    put<std::uint16_t>(out, static_cast<std::uint16_t>(unit.stage));
    put<std::uint32_t>(out, static_cast<std::uint32_t>(t.worker));
    put<std::uint32_t>(out, static_cast<std::uint32_t>(pixels));
    put<double>(out, t.merged_at_ms);
    if (pixels > 0) {
      if (stage.preview_only)
        out.append(t.preview_values);
      else
        append_tile_means(out, unit.pixels, job.tile_pixels());
    }
    pixel_bytes += 3 * pixels;
  }
  const std::uint32_t header[2] = {static_cast<std::uint32_t>(end),
                                   static_cast<std::uint32_t>(end - first)};
  std::memcpy(out.data() + 4, header, sizeof header);
  return out;
}

}  // namespace tessera
