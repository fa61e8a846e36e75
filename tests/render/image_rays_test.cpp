// The packet path's camera directions, four at a time (ImageRays::directions_through, SSE2),
// must be direction_through's bit for bit: random camera frames and image sizes (portrait ones
// widened), image points inside the image, on its edges and beyond it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/geometry/instance.h"
#include "common/render/prepared_scene.h"

namespace tessera {
namespace {

Vec3 unit(const Vec3& v) { return v / length(v); }

TEST(ImageRays, FourDirectionsAreDirectionThroughBitForBit) {
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> coordinate(-1, 1), angle(0.01, 1.5);
  std::uniform_int_distribution<int> size(1, 4000);
  int compared = 0;
  for (int frame_index = 0; frame_index < 2000; ++frame_index) {
    CameraFrame frame;
    frame.eye = {coordinate(rng) * 100, coordinate(rng) * 100, coordinate(rng) * 100};
    frame.forward = unit({coordinate(rng), coordinate(rng), coordinate(rng)});
    frame.right = unit(cross(frame.forward, {coordinate(rng), coordinate(rng), coordinate(rng)}));
    frame.up = cross(frame.right, frame.forward);
    frame.tan_half_height = std::tan(angle(rng) / 2);
    frame.angle_on_smaller_side = frame_index % 2 == 1;
    const int width = size(rng), height = size(rng);
    const ImageRays camera(frame, width, height);
    std::uniform_real_distribution<double> px(-0.5 * width, 1.5 * width),
        py(-0.5 * height, 1.5 * height);
    for (int packet = 0; packet < 50; ++packet) {
      double x[4], y[4];
      for (int k = 0; k < 4; ++k) {
        // Pixel centres, the image's corners and edges, and anywhere around it.
        switch ((packet + k) % 4) {
          case 0:
            x[k] = std::floor(px(rng)) + 0.5, y[k] = std::floor(py(rng)) + 0.5;
            break;
          case 1:
            x[k] = (k % 2) * width, y[k] = (k / 2) * height;
            break;
          default:
            x[k] = px(rng), y[k] = py(rng);
        }
      }
      Vec3 four[4];
      camera.directions_through(x, y, four);
      for (int k = 0; k < 4; ++k) {
        const Vec3 one = camera.direction_through(x[k], y[k]);
        ASSERT_TRUE(same_bits(four[k], one))
            << "frame " << frame_index << ", point (" << x[k] << ", " << y[k] << ") of " << width
            << "x" << height << ": " << four[k].x << " " << four[k].y << " " << four[k].z
            << " against " << one.x << " " << one.y << " " << one.z;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 400000);
}

}  // namespace
}  // namespace tessera
