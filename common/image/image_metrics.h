// How far an image is from a reference, as the accuracy report states it (issue 5): both are
// compared as they are displayed, intensities clamped to [0, 1].
#pragma once

#include "common/image/image.h"

namespace tessera {

struct ImageError {
  double rmse = 0;               // root mean square over every channel of every pixel
  double psnr = 0;               // 20 log10(1 / rmse) in dB; infinite for identical images
  double max_error = 0;          // largest difference of one channel
  double share_off_by_step = 0;  // share of pixels with a channel off by more than 1/255
};

// Computed with OpenImageIO's ImageBufAlgo::compare. Throws std::invalid_argument when the
// sizes differ.
ImageError compare_images(const Image& image, const Image& reference);

}  // namespace tessera
