#include "common/image/png/encode_png.h"

#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "common/image/to_8bit.h"

namespace tessera {

namespace {

// libpng reports errors by longjmp to the setjmp in encode_rows: only C frames and objects
// made before that setjmp lie on the way, so nothing is skipped that needs destroying.
void on_error(png_structp png, png_const_charp message) {
  std::snprintf(static_cast<char*>(png_get_error_ptr(png)), 256, "%s", message);
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

void append(png_structp png, png_bytep data, png_size_t length) {
  static_cast<std::string*>(png_get_io_ptr(png))
      ->append(reinterpret_cast<const char*>(data), length);
}

void flush(png_structp) {}

// Encodes the rows into `out`; false with `error` filled on failure.
bool encode_rows(std::string& out, int width, int height, std::vector<png_bytep>& rows,
                 char (&error)[256]) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    std::snprintf(error, sizeof error, "out of memory");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &out, append, flush);
  png_set_compression_level(png, 3);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

std::string encode_png(const Image& image) {
  std::vector<png_byte> bytes(image.rgb.size());
  // Infinities too become 0, as OpenImageIO's writer (oiio/image_io.cpp) makes them.
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = std::isfinite(image.rgb[i]) ? to_8bit(image.rgb[i]) : 0;
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y)
    rows[static_cast<std::size_t>(y)] =
        bytes.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) * 3;
  std::string out;
  char error[256] = "";
  if (!encode_rows(out, image.width, image.height, rows, error))
    throw std::runtime_error(std::string("encoding png: ") + error);
  return out;
}

}  // namespace tessera
