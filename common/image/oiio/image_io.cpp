#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

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
  std::vector<float> data(image.rgb.begin(), image.rgb.end());
  if (!as_float)  // 8-bit formats hold [0, 1]; out-of-range intensities clip as in OpenGL
    for (float& v : data) v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, data.data()) ||
      !out->close())
    throw std::runtime_error("cannot write " + path + ": " + out->geterror());
}

std::string encode_image(const Image& image, const std::string& format) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  const std::string name = "image." + format;
  auto out = OIIO::ImageOutput::create(name, &memory);
  if (!out) throw std::runtime_error("no image writer for " + format);
  OIIO::ImageSpec spec(image.width, image.height, 3,
                       format == "exr" ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (format == "png") spec.attribute("png:compressionLevel", 3);
  if (format == "exr") spec.attribute("compression", "zip");
  if (!out->open(name, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, image.rgb.data()) ||
      !out->close())
    throw std::runtime_error("encoding " + format + ": " + out->geterror());
  return std::string(bytes.begin(), bytes.end());
}

namespace {

// The first three channels as RGB; one or two channels (gray, gray and alpha) as gray.
Image read_opened(OIIO::ImageInput& in, const std::string& name, std::size_t max_pixels) {
  const OIIO::ImageSpec& spec = in.spec();
  const std::size_t count = static_cast<std::size_t>(spec.width) * spec.height;
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw std::runtime_error("cannot read " + name + ": it holds no pixels");
  if (count > max_pixels)
    throw std::runtime_error("cannot read " + name + ": " + std::to_string(spec.width) + "x" +
                             std::to_string(spec.height) + " pixels is more than " +
                             std::to_string(max_pixels));
  // Read straight into the image's floats, with no buffer of all the file's channels (a
  // 4096x4096 RGBA texture would take 256 MB more): RGB as it is, gray into every third float.
  const int read = spec.nchannels < 3 ? 1 : 3;
  Image image(spec.width, spec.height);
  if (!in.read_image(0, 0, 0, read, OIIO::TypeDesc::FLOAT, image.rgb.data(), 3 * sizeof(float)))
    throw std::runtime_error("cannot read " + name + ": " + in.geterror());
  if (read == 1)
    for (std::size_t p = 0; p < count; ++p)
      image.rgb[3 * p + 1] = image.rgb[3 * p + 2] = image.rgb[3 * p];
  return image;
}

// Opens a file held in memory and hands it to `read`.
template <typename Read>
auto read_memory(std::string_view bytes, const std::string& name, Read&& read) {
  OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
  // The name's extension picks the format first; OpenImageIO then tries the others.
  auto in = OIIO::ImageInput::open(name, nullptr, &memory);
  if (!in) throw std::runtime_error("cannot read " + name + ": " + OIIO::geterror());
  return read(*in);
}

}  // namespace

Image read_image(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error("cannot read " + path + ": " + OIIO::geterror());
  return read_opened(*in, path, static_cast<std::size_t>(-1));
}

Image decode_image(std::string_view bytes, const std::string& name, std::size_t max_pixels) {
  return read_memory(bytes, name,
                     [&](OIIO::ImageInput& in) { return read_opened(in, name, max_pixels); });
}

int image_channels(std::string_view bytes, const std::string& name) {
  return read_memory(bytes, name, [](OIIO::ImageInput& in) { return in.spec().nchannels; });
}

std::size_t image_pixels(std::string_view bytes, const std::string& name) {
  return read_memory(bytes, name, [](OIIO::ImageInput& in) {
    const OIIO::ImageSpec& spec = in.spec();
    return spec.width > 0 && spec.height > 0 ? static_cast<std::size_t>(spec.width) * spec.height
                                             : std::size_t{0};
  });
}

}  // namespace tessera
