// The image-file functions of image.h for a program without an image library: the worker,
// whose textures arrive decoded by the coordinator (decoded_texture.h). Only decoding is
// defined, to refuse with a clear message; nothing in the worker writes or reads image files.
#include <stdexcept>

#include "common/image/image.h"

namespace tessera {

namespace {

[[noreturn]] void refuse(const std::string& name) {
  throw std::runtime_error("cannot read " + name +
                           ": this program reads only textures decoded by the coordinator");
}

}  // namespace

Image decode_image(std::string_view, const std::string& name, std::size_t) { refuse(name); }

std::string encode_image(const Image&, const std::string& format) {
  throw std::runtime_error("cannot encode " + format + ": this program has no image library");
}

int image_channels(std::string_view, const std::string& name) { refuse(name); }
std::size_t image_pixels(std::string_view, const std::string& name) { refuse(name); }

}  // namespace tessera
