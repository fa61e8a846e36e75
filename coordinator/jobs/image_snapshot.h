// A job's frame buffer at one version and what its image is made of, so that the image is made
// on an intake thread rather than on the io thread: resolving or previewing a large image
// passes over every pixel (a 2048² done job's resolve was 28 % of the io thread's time). The
// io thread only shares a done job's frame buffer (moved out of the job when it finished) or
// copies a running job's (Job::snapshot).
#pragma once

#include <memory>

#include "common/image/image.h"
#include "common/render/frame_buffer.h"

namespace tessera {

struct ImageSnapshot {
  std::shared_ptr<const FrameBuffer> pixels;  // never changed once shared
  // Done: each pixel's mean of its passes. Running: what is known so far, each pixel showing
  // the finest anchor merged over it among the plan's `levels` (area previews are only in the
  // tile records).
  bool final = false;
  int levels = 0;
  // Post-normalization needs the whole image (§4.6): applied here, never to units.
  bool normalize = false;
  double normalize_brightness = 1.0;

  // The image the API serves, bit-identical to tessera-render's once final. Any thread.
  Image image() const;
};

}  // namespace tessera
