// exr_equal A B [X0 Y0 X1 Y1]: exit 0 when the two images have the same size and bit-identical
// float pixels (the service's promise against tessera-render), else print the first difference
// and exit 1. With a region (half open, as the setting `region`), A is a render of only that
// region: its pixels inside equal B's and every pixel outside is black.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>

#include "common/image/image.h"

int main(int argc, char** argv) {
  if (argc != 3 && argc != 7) {
    std::fprintf(stderr, "usage: exr_equal A.exr B.exr [X0 Y0 X1 Y1]\n");
    return 2;
  }
  try {
    const tessera::Image a = tessera::read_image(argv[1]);
    const tessera::Image b = tessera::read_image(argv[2]);
    if (a.width != b.width || a.height != b.height) {
      std::printf("sizes differ: %dx%d vs %dx%d\n", a.width, a.height, b.width, b.height);
      return 1;
    }
    int region[4] = {0, 0, a.width, a.height};
    if (argc == 7)
      for (int i = 0; i < 4; ++i) region[i] = std::atoi(argv[3 + i]);
    constexpr float kBlack = 0.0f;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
      const std::size_t pixel = i / 3;
      const int x = static_cast<int>(pixel % static_cast<std::size_t>(a.width));
      const int y = static_cast<int>(pixel / static_cast<std::size_t>(a.width));
      const bool inside = x >= region[0] && x < region[2] && y >= region[1] && y < region[3];
      const float& expected = inside ? b.rgb[i] : kBlack;
      if (std::memcmp(&a.rgb[i], &expected, sizeof(float)) != 0) {
        std::printf("pixel (%d, %d) channel %zu differs: %.9g vs %.9g%s\n", x, y, i % 3,
                    static_cast<double>(a.rgb[i]), static_cast<double>(expected),
                    inside ? "" : " (outside the region)");
        return 1;
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
