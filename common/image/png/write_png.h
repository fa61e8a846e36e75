// PNG files with libpng: 8-bit RGB, as OpenImageIO writes them (the same values, no colour
// chunks), for a program that should not load OpenImageIO to write one.
#pragma once

#include <string>

#include "common/image/image.h"

namespace tessera {

// Writes `image` as 8-bit RGB, each value to_8bit() of the intensity. Throws
// std::runtime_error naming `path` on failure.
void write_png(const Image& image, const std::string& path);

}  // namespace tessera
