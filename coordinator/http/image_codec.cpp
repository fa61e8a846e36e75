#include "coordinator/http/image_codec.h"

#include <stdexcept>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace tessera {

std::string encode_image(const Image& image, const std::string& format) {
  namespace OIIO = OIIO_NAMESPACE;
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  const std::string name = "image." + format;
  auto out = OIIO::ImageOutput::create(name, &memory);
  if (!out) throw std::runtime_error("no image writer for " + format);
  OIIO::ImageSpec spec(image.width, image.height, 3,
                       format == "exr" ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (format == "png") spec.attribute("png:compressionLevel", 3);  // speed over size, for polling
  // Lossless, and what a done job keeps in memory: about half the size of raw floats.
  if (format == "exr") spec.attribute("compression", "zip");
  if (!out->open(name, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, image.rgb.data()) ||
      !out->close())
    throw std::runtime_error("encoding " + format + ": " + out->geterror());
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace tessera
