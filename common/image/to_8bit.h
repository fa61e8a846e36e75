// The 8-bit value a PNG stores for an intensity.
#pragma once

#include <cstdint>

namespace tessera {

// Clamped to [0, 1] and rounded, exactly as OpenImageIO converts float to 8 bits, so that the
// PNG written here (png/write_png.h), OpenImageIO's and the page's tile deltas agree bit for bit.
inline std::uint8_t to_8bit(float v) {
  float s = v * 255.0f;
  s += s < 0 ? -0.5f : 0.5f;
  if (!(s >= 0.0f)) s = 0.0f;  // NaN too
  if (s > 255.0f) s = 255.0f;
  return static_cast<std::uint8_t>(s);
}

}  // namespace tessera
