#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/image/image.h"

namespace tessera {

namespace {

bool is_float_format(const std::string& path) {
  std::string ext = path.substr(path.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == "exr" || ext == "hdr" || ext == "pfm";
}

}  // namespace

void write_image(const Image& image, const std::string& path) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error("cannot write " + path + ": " + OIIO::geterror());
  const bool as_float = is_float_format(path);
  OIIO::ImageSpec spec(image.width, image.height, 3,
                       as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  std::vector<float> data = image.rgb;
  if (!as_float)  // 8-bit formats hold [0, 1]; out-of-range intensities clip as in OpenGL
    for (float& v : data) v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, data.data()) ||
      !out->close())
    throw std::runtime_error("cannot write " + path + ": " + out->geterror());
}

Image read_image(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error("cannot read " + path + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const int channels = spec.nchannels;
  std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw std::runtime_error("cannot read " + path + ": " + in->geterror());
  Image image(spec.width, spec.height);
  for (std::size_t p = 0; p < static_cast<std::size_t>(spec.width) * spec.height; ++p)
    for (int c = 0; c < 3; ++c)
      image.rgb[3 * p + c] =
          pixels[p * channels + static_cast<std::size_t>(std::min(c, channels - 1))];
  return image;
}

}  // namespace tessera
