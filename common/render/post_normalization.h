// Post-normalization of the colours (§4.6): a step on the finished image, never on a pixel or
// a unit, because it needs the whole image's highest intensity. The CLI applies it to
// render_image's result and the coordinator to the job's image when it serves it, so both
// give the same bits; workers never see it.
#pragma once

#include "common/image/image.h"

namespace tessera {

// When the image's highest component exceeds 1, scales every component so that it becomes 1;
// then multiplies every component by `brightness`.
void post_normalize(Image& image, double brightness);

}  // namespace tessera
