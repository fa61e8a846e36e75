// Image texture lookup (SDL §4.3.2): bilinear interpolation between the four texels around a
// point, so that an enlarged image shows no blocks. The image repeats in both directions, as
// tiling and the offset's wrap-around make texture space periodic.
#pragma once

#include "common/image/image.h"
#include "common/scene/rgb.h"

namespace tessera {

// The largest image a texture may have (4096 x 4096 texels): 192 MiB as float RGB.
inline constexpr std::size_t kMaxTexturePixels = std::size_t{1} << 24;

// The colour at texture position (u, v), taken modulo 1: u left to right, v bottom to top.
// Texel (i, j) (row j from the top) has its centre at ((i + 1/2) / width, 1 - (j + 1/2) / height).
// A clamped direction (VRML's repeatS or repeatT FALSE) does not repeat: beyond [0, 1] its edge
// texels go on.
Rgb bilinear_lookup(const Image& image, double u, double v, bool clamp_u = false,
                    bool clamp_v = false);

}  // namespace tessera
