#include "common/image/image_metrics.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tessera {

namespace {

constexpr float kEightBitStep = 1.0f / 255.0f;

OIIO::ImageBuf displayed(const Image& image) {
  OIIO::ImageBuf buffer(OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT));
  std::vector<float> values(image.rgb.begin(), image.rgb.end());
  for (float& v : values) v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
  buffer.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, values.data());
  return buffer;
}

}  // namespace

ImageError compare_images(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw std::invalid_argument("cannot compare a " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " image with a " +
                                std::to_string(reference.width) + "x" +
                                std::to_string(reference.height) + " reference");
  const OIIO::ImageBufAlgo::CompareResults r = OIIO::ImageBufAlgo::compare(
      displayed(image), displayed(reference), kEightBitStep, kEightBitStep);
  ImageError error;
  error.rmse = r.rms_error;
  error.psnr =
      r.rms_error > 0 ? 20 * std::log10(1 / r.rms_error) : std::numeric_limits<double>::infinity();
  error.max_error = r.maxerror;
  const double pixels = static_cast<double>(image.width) * image.height;
  error.share_off_by_step = pixels > 0 ? static_cast<double>(r.nfail) / pixels : 0;
  return error;
}

}  // namespace tessera
