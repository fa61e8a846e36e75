#include "common/image/png/write_png.h"

#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "common/image/to_8bit.h"

namespace tessera {

namespace {

// libpng reports errors by longjmp to the setjmp in write_rows: only C frames and objects
// made before that setjmp lie on the way, so nothing is skipped that needs destroying.
void on_error(png_structp png, png_const_charp message) {
  std::snprintf(static_cast<char*>(png_get_error_ptr(png)), 256, "%s", message);
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

// Writes the rows to an open file; false with `error` filled on failure.
bool write_rows(std::FILE* file, int width, int height, std::vector<png_bytep>& rows,
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
  png_init_io(png, file);
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

void write_png(const Image& image, const std::string& path) {
  std::vector<png_byte> bytes(image.rgb.size());
  // Infinities too become 0, as OpenImageIO's writer (oiio/image_io.cpp) makes them.
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = std::isfinite(image.rgb[i]) ? to_8bit(image.rgb[i]) : 0;
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y)
    rows[static_cast<std::size_t>(y)] =
        bytes.data() + static_cast<std::size_t>(y) * image.width * 3;
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) throw std::runtime_error("cannot write " + path + ": cannot open it");
  char error[256] = "";
  const bool written = write_rows(file, image.width, image.height, rows, error);
  const bool closed = std::fclose(file) == 0;
  if (!written) throw std::runtime_error("cannot write " + path + ": " + error);
  if (!closed) throw std::runtime_error("cannot write " + path + ": the disk refused it");
}

}  // namespace tessera
