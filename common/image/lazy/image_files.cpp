// The image-file functions of image.h for tessera-render: PNG is written with libpng
// (png/write_png.h), so that a render that reads no texture and writes a PNG starts in
// milliseconds; anything else goes to OpenImageIO, loaded on first use (oiio/module.h).
#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "common/image/image.h"
#include "common/image/oiio/module.h"
#include "common/image/png/write_png.h"

namespace tessera {

namespace {

// The module beside the running program (the build puts it there).
const ImageFileFunctions& openimageio() {
  static const ImageFileFunctions* functions = [] {
    std::error_code error;
    const auto program = std::filesystem::read_symlink("/proc/self/exe", error);
    const auto path = (program.parent_path() / kImageModuleFile).string();
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module)
      throw std::runtime_error(std::string("cannot load OpenImageIO for image files: ") +
                               dlerror());
    using Entry = const ImageFileFunctions* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(module, kImageModuleEntry));
    if (!entry) throw std::runtime_error(path + " is not Tessera's OpenImageIO module");
    return entry();
  }();
  return *functions;
}

bool is_png(const std::string& path) {
  std::string ext = path.substr(path.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == "png";
}

}  // namespace

void write_image(const Image& image, const std::string& path) {
  if (is_png(path)) return write_png(image, path);
  openimageio().write_image(image, path);
}

Image read_image(const std::string& path) { return openimageio().read_image(path); }

Image decode_image(std::string_view bytes, const std::string& name, std::size_t max_pixels) {
  return openimageio().decode_image(bytes, name, max_pixels);
}

int image_channels(std::string_view bytes, const std::string& name) {
  return openimageio().image_channels(bytes, name);
}

std::size_t image_pixels(std::string_view bytes, const std::string& name) {
  return openimageio().image_pixels(bytes, name);
}

}  // namespace tessera
