// Image textures as the coordinator sends them to workers: decoded once, at intake, into
// Tessera's own lossless form, so that workers need no image library (they start without
// loading OpenImageIO's ~250 shared libraries) and every program decodes a texture to the same
// floats. The form keeps the decoded RGB values bit for bit and the source file's channel count
// (VRML treats one- and two-channel images as intensity textures, §6.22).
//
// Layout: the 8-byte magic "TSTEX01\n", width and height (uint32, little endian), the source's
// channel count (uint8), the sample kind (uint8: 0 = bytes k standing for k * (1.0f / 255.0f), as
// OpenImageIO converts 8-bit samples,
// 1 = float32), then the samples (3 per pixel, row-major, top row first) compressed with zlib.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "common/image/image.h"

namespace tessera {

// True when `bytes` starts with the decoded-texture magic.
bool is_decoded_texture(std::string_view bytes);

// The decoded form of `image`, read from a file of `source_channels` channels. Eight-bit
// samples when every value is k * (1.0f / 255.0f) for an integer k, float32 otherwise.
std::string encode_decoded_texture(const Image& image, int source_channels);

// The pixels of a decoded texture. Throws std::runtime_error naming `name` when the bytes are
// not a well-formed decoded texture or hold more than `max_pixels` pixels.
Image decode_decoded_texture(std::string_view bytes, const std::string& name,
                             std::size_t max_pixels);
// Its source's channel count, from the header alone.
int decoded_texture_channels(std::string_view bytes, const std::string& name);

// What the renderer calls: a decoded texture as above, any other file through the program's
// image library (decode_image, image_channels in image.h; the worker has none and refuses).
Image decode_texture(std::string_view bytes, const std::string& name, std::size_t max_pixels);
int texture_channels(std::string_view bytes, const std::string& name);
// Width times height from the header alone (the loaders count what decoding will make).
std::size_t texture_pixels(std::string_view bytes, const std::string& name);

}  // namespace tessera
