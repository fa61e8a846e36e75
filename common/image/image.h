// A float RGB frame buffer and its files. Values are the lighting model's intensities as
// computed (linear, not gamma-encoded): EXR keeps them as float; PNG and other 8-bit formats
// clamp them to [0, 1] and quantize.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "common/image/calloc_allocator.h"
#include "common/scene/rgb.h"

namespace tessera {

struct Image {
  int width = 0;
  int height = 0;
  // Row-major, top row first, 3 floats per pixel. From calloc: a new image is black without a
  // pass over its pixels, and its pages are faulted in by whoever first writes them.
  std::vector<float, CallocAllocator<float>> rgb;

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3) {}
  std::size_t index(int x, int y) const { return (static_cast<std::size_t>(y) * width + x) * 3; }
  void set(int x, int y, const Rgb& c) {
    const std::size_t i = index(x, y);
    rgb[i] = static_cast<float>(c.r);
    rgb[i + 1] = static_cast<float>(c.g);
    rgb[i + 2] = static_cast<float>(c.b);
  }
  Rgb get(int x, int y) const {
    const std::size_t i = index(x, y);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
  friend bool operator==(const Image&, const Image&) = default;
};

// Image files, through OpenImageIO (common/image/oiio/), linked in or, for tessera-render,
// loaded on first use while PNG is written with libpng (common/image/lazy/). The worker has none
// (its target sets TESSERA_IMAGE_FILES to `none`, common/CMakeLists.txt): its decode_image and
// image_channels refuse, for it gets textures decoded by the coordinator (decoded_texture.h).

// Writes by extension: .exr as 32-bit float, anything else as 8-bit (clamped to [0, 1],
// to_8bit.h).
// Throws std::runtime_error naming the file, with the library's message, on failure.
void write_image(const Image& image, const std::string& path);
// Encodes in memory as `format`, "png" (8-bit as above, zlib level 3: speed over size, for
// pages that poll) or "exr" (32-bit float, zip: lossless, about half the raw floats). Throws
// std::runtime_error on failure.
std::string encode_image(const Image& image, const std::string& format);
// Reads any format OpenImageIO reads into RGB float (alpha dropped, gray expanded).
Image read_image(const std::string& path);
// Decodes a file held in memory (`name` for its format and messages), with at most
// `max_pixels` pixels, the same way. Throws std::runtime_error naming `name` on failure.
Image decode_image(std::string_view bytes, const std::string& name, std::size_t max_pixels);
// The number of channels of a file held in memory, from its header alone.
int image_channels(std::string_view bytes, const std::string& name);
// Its width times height, from its header alone: what decoding it would make.
std::size_t image_pixels(std::string_view bytes, const std::string& name);

}  // namespace tessera
