// PNG with libpng: 8-bit RGB, as OpenImageIO writes it (the same values, no colour chunks), for
// programs that should not load OpenImageIO to write one.
#pragma once

#include <string>

#include "common/image/image.h"

namespace tessera {

// The PNG of `image`, each value to_8bit() of the intensity (infinities and NaN as 0), at
// zlib's `level` (0-9). Throws std::runtime_error on failure.
std::string encode_png(const Image& image, int level);

}  // namespace tessera
