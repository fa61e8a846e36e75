// The pixel bytes of a tile record (GET /api/jobs/{id}/tiles, docs/SERVICE.md "Tiles"): one
// 8-bit RGB value per pixel of a unit, as a PNG of the image stores it, in expand() order, each
// byte the difference from the same channel of the pixel before (mod 256, the first pixel as it
// is), so that smooth images compress well.
#pragma once

#include <span>
#include <string>

#include "common/progressive/unit_pixels.h"
#include "common/render/frame_buffer.h"

namespace tessera {

// Appends the bytes of `values` (3 floats a pixel): an area preview's values, which no frame
// buffer holds.
void append_tile_values(std::string& out, std::span<const float> values);

// Appends the bytes of the unit's pixels' means so far in `pixels`: what every other record
// shows. Made when a page asks, not when the unit merges, so that merging does no per-pixel
// work for previews.
void append_tile_means(std::string& out, const UnitPixels& unit, const FrameBuffer& pixels);

}  // namespace tessera
