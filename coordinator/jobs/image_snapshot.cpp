#include "coordinator/jobs/image_snapshot.h"

#include <algorithm>

#include "common/progressive/plan.h"
#include "common/progressive/unit_pixels.h"
#include "common/render/post_normalization.h"

namespace tessera {

namespace {

Image known_so_far(const FrameBuffer& frame_buffer, int levels) {
  const int w = frame_buffer.width(), h = frame_buffer.height();
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // The finest anchor merged over the pixel: the pixel itself once it has a pass, else
      // the anchor of its block at each coarser level (levels overlap across workers).
      for (int level = std::max(levels, 1); level >= 1; --level) {
        const int side = levels > 0 ? block_side(levels, level) : 1;
        const PixelCoord a = block_of({x, y}, side);
        if (frame_buffer.passes_at(a.x, a.y) == 0) continue;
        image.set(x, y, frame_buffer.mean(a.x, a.y));
        break;
      }
    }
  return image;
}

}  // namespace

Image ImageSnapshot::image() const {
  Image image = final ? pixels->resolve() : known_so_far(*pixels, levels);
  if (normalize) post_normalize(image, normalize_brightness);
  return image;
}

}  // namespace tessera
