// Images as HTTP bodies: PNG (8-bit, clamped like tessera-render's PNG) for the page and EXR
// (linear float) for download, encoded in memory with OpenImageIO.
#pragma once

#include <string>

#include "common/image/image.h"

namespace tessera {

// `format` is "png" or "exr"; throws std::runtime_error with OpenImageIO's message.
std::string encode_image(const Image& image, const std::string& format);

}  // namespace tessera
