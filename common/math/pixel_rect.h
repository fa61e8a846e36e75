// Integer positions on the pixel grid: the one pixel and the one rectangle type of the tracer, the
// progressive plan, the settings and the wire. Kept in math/, the bottom layer, so that every
// other folder may use them without depending on the tracer (docs/ARCHITECTURE.md, "Layers").
#pragma once

namespace tessera {

// Pixel (x, y); y = 0 is the top row.
struct PixelCoord {
  int x = 0, y = 0;
  friend bool operator==(const PixelCoord&, const PixelCoord&) = default;
};

// A half-open rectangle of pixels [x0, x1) x [y0, y1), like every rectangle here; y = 0 is the
// top row, and [0, 0, width, height] is the whole image.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  long long area() const { return static_cast<long long>(width()) * height(); }
  friend bool operator==(const PixelRect&, const PixelRect&) = default;
};

}  // namespace tessera
