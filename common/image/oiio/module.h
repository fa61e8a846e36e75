// OpenImageIO as a module loaded on first use (lazy/image_files.cpp): its ~250 shared libraries
// take a program 0.25 s and more to load, which tessera-render spends only on a texture or an
// image format other than PNG. The module (libtessera_image_oiio.so, which the build puts in
// its lib/ folder) exports one C function that hands out the functions of oiio/image_io.cpp.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "common/image/image.h"

namespace tessera {

struct ImageFileFunctions {
  void (*write_image)(const Image&, const std::string&);
  std::string (*encode_image)(const Image&, const std::string&);
  Image (*read_image)(const std::string&);
  Image (*decode_image)(std::string_view, const std::string&, std::size_t);
  int (*image_channels)(std::string_view, const std::string&);
  std::size_t (*image_pixels)(std::string_view, const std::string&);
};

inline constexpr const char* kImageModuleFile = "libtessera_image_oiio.so";
inline constexpr const char* kImageModuleEntry = "tessera_image_file_functions";

}  // namespace tessera
