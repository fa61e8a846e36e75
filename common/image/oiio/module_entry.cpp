// The entry of the OpenImageIO module (module.h); the module's other symbols stay hidden.
#include "common/image/oiio/module.h"

extern "C" __attribute__((visibility("default"))) const tessera::ImageFileFunctions*
tessera_image_file_functions() {
  static const tessera::ImageFileFunctions functions{
      &tessera::write_image,  &tessera::encode_image,   &tessera::read_image,
      &tessera::decode_image, &tessera::image_channels, &tessera::image_pixels};
  return &functions;
}
