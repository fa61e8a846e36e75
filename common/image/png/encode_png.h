// PNG with libpng: 8-bit RGB, as OpenImageIO writes it (the same values, no colour chunks), for
// programs that should not load OpenImageIO to write one.
#pragma once

#include <string>

#include "common/image/image.h"

namespace tessera {

// The PNG of `image`, each value to_8bit() of the intensity (infinities and NaN as 0).
// Compressed at zlib's level 3 with every row's filter "Sub": on rendered 640x480 images that
// takes a quarter of libpng's default (level 6, the best of five filters tried per row: 20 against
// 5 ms) for files about a fifth larger. Throws std::runtime_error on failure.
std::string encode_png(const Image& image);

}  // namespace tessera
