// EXR with OpenEXR itself: 32-bit float R, G, B, zip-compressed, as OpenImageIO writes it, for
// programs that should not load OpenImageIO to write one.
#pragma once

#include <string>

#include "common/image/image.h"

namespace tessera {

// The EXR of `image`, its intensities exactly. Throws std::runtime_error on failure.
std::string encode_exr(const Image& image);

}  // namespace tessera
