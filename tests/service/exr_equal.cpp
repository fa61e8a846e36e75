// exr_equal A B: exit 0 when the two images have the same size and bit-identical float pixels
// (the service's promise against tessera-render), else print the first difference and exit 1.
#include <cstdio>
#include <cstring>
#include <exception>

#include "common/image/image.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: exr_equal A.exr B.exr\n");
    return 2;
  }
  try {
    const tessera::Image a = tessera::read_image(argv[1]);
    const tessera::Image b = tessera::read_image(argv[2]);
    if (a.width != b.width || a.height != b.height) {
      std::printf("sizes differ: %dx%d vs %dx%d\n", a.width, a.height, b.width, b.height);
      return 1;
    }
    for (std::size_t i = 0; i < a.rgb.size(); ++i)
      if (std::memcmp(&a.rgb[i], &b.rgb[i], sizeof(float)) != 0) {
        const std::size_t pixel = i / 3;
        std::printf("pixel (%zu, %zu) channel %zu differs: %.9g vs %.9g\n",
                    pixel % static_cast<std::size_t>(a.width),
                    pixel / static_cast<std::size_t>(a.width), i % 3, static_cast<double>(a.rgb[i]),
                    static_cast<double>(b.rgb[i]));
        return 1;
      }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
