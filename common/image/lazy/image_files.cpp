// The image-file functions of image.h for tessera-render and the coordinator: PNG and EXR are
// written with libpng and OpenEXR (png/, exr/), a few small libraries, so that both programs
// start in milliseconds and load OpenImageIO's ~250 only for what else it does: decoding image
// textures, other formats (oiio/module.h).
#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "common/image/exr/encode_exr.h"
#include "common/image/image.h"
#include "common/image/oiio/module.h"
#include "common/image/png/encode_png.h"

namespace tessera {

namespace {

// The module from the lib/ folder beside the program's folder (the build's, and an install's
// bin/ and lib/), else from the program's own folder.
const ImageFileFunctions& openimageio() {
  static const ImageFileFunctions* functions = [] {
    std::error_code error;
    const auto folder = std::filesystem::read_symlink("/proc/self/exe", error).parent_path();
    std::string path;
    void* module = nullptr;
    for (const auto& candidate :
         {folder.parent_path() / "lib" / kImageModuleFile, folder / kImageModuleFile}) {
      path = candidate.string();
      if ((module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL))) break;
    }
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

std::string lowercase_extension(const std::string& path) {
  std::string ext = path.substr(path.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error("cannot write " + path + ": cannot open it");
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.close();
  if (!file) throw std::runtime_error("cannot write " + path + ": the disk refused it");
}

}  // namespace

void write_image(const Image& image, const std::string& path) {
  const std::string ext = lowercase_extension(path);
  if (ext == "png") return write_file(path, encode_png(image));
  if (ext == "exr") return write_file(path, encode_exr(image));
  openimageio().write_image(image, path);
}

std::string encode_image(const Image& image, const std::string& format) {
  if (format == "png") return encode_png(image);
  if (format == "exr") return encode_exr(image);
  return openimageio().encode_image(image, format);
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
