// VRML97's texture mapping of the primitives, in rendered pixels (issue 20, items 9-10): the
// side of a Sphere, Cylinder and Cone starts s = 0 at the back (-z) and wraps counter-clockwise
// seen from +y, so that +z shows s = 1/2 and -x s = 1/4 (§6.12, §6.17, §6.44); a top cap reads
// right side up seen from above with -z up, a bottom cap seen from below with +z up, as Box's
// faces do. The shapes have no Material, so a texel shows as it is.
#include <gtest/gtest.h>

#include <string>

#include "common/loaders/scene_source.h"
#include "common/loaders/vrml_loader.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

const Rgb kRed{1, 0, 0}, kGreen{0, 1, 0}, kBlue{0, 0, 1}, kWhite{1, 1, 1};

std::string ppm(int width, int height, const std::vector<Rgb>& texels) {
  std::string out = "P6\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
  for (const Rgb& c : texels)
    for (const double v : {c.r, c.g, c.b}) out += static_cast<char>(v > 0.5 ? 255 : 0);
  return out;
}

// Three bands along s: red, green, blue. s = 1/2 is the centre of the green texel, where the
// bilinear filter gives green exactly; s = 1/4 is 3/4 red and 1/4 green.
const std::string kBands = ppm(3, 1, {kRed, kGreen, kBlue});
// 4 x 4 texels in four 2 x 2 quadrants: red top left, green top right, blue bottom left, white
// bottom right.
const std::string kQuadrants = ppm(4, 4,
                                   {kRed, kRed, kGreen, kGreen,    //
                                    kRed, kRed, kGreen, kGreen,    //
                                    kBlue, kBlue, kWhite, kWhite,  //
                                    kBlue, kBlue, kWhite, kWhite});

constexpr int kSize = 41;  // odd: the centre pixel looks along the view's axis

// `geometry` textured with `image`, white sky, seen by `viewpoint`.
Image render_textured(const std::string& geometry, const std::string& image,
                      const std::string& viewpoint) {
  MemorySource source({{"t.ppm", image}});
  source.add("world.wrl",
             "#VRML V2.0 utf8\n" + viewpoint +
                 "\nBackground { skyColor 1 1 1 }\n"
                 "Shape { appearance Appearance { texture ImageTexture { url \"t.ppm\" } }\n"
                 "  geometry " +
                 geometry + " }\n");
  return render(load_vrml(source, "world.wrl"), settings(kSize, kSize));
}

// Looking down -z from z = 5, along +x from x = -5, up from below, down from above; the
// field of view shows [-1, 1] at distance 4 (the caps at y = -1 and 1 fill the image).
const std::string kFromFront = "Viewpoint { position 0 0 5 fieldOfView 1.5 }";
const std::string kFromLeft =
    "Viewpoint { position -5 0 0 orientation 0 1 0 -1.5707963267948966 fieldOfView 1.5 }";
const std::string kFromBelow =
    "Viewpoint { position 0 -5 0 orientation 1 0 0 1.5707963267948966 "
    "fieldOfView 0.4899573262537283 }";
const std::string kFromAbove =
    "Viewpoint { position 0 5 0 orientation 1 0 0 -1.5707963267948966 "
    "fieldOfView 0.4899573262537283 }";

TEST(VrmlTextureMapping, TheSidesShowTheMiddleOfTheImageTowardsPlusZ) {
  for (const char* shape : {"Sphere {}", "Cylinder {}", "Cone {}"}) {
    SCOPED_TRACE(shape);
    expect_rgb(render_textured(shape, kBands, kFromFront).get(kSize / 2, kSize / 2), kGreen);
    // -x: s = 1/4, a quarter of the way round from the back, counter-clockwise from +y.
    expect_rgb(render_textured(shape, kBands, kFromLeft).get(kSize / 2, kSize / 2),
               kRed * 0.75 + kGreen * 0.25);
  }
}

TEST(VrmlTextureMapping, CapsReadRightSideUpFromOutside) {
  // The pixel up and to the left of the centre shows the image's top left quadrant.
  const int near_corner = kSize / 4;
  expect_rgb(render_textured("Cylinder {}", kQuadrants, kFromAbove).get(near_corner, near_corner),
             kRed);
  for (const char* shape : {"Cylinder {}", "Cone {}"}) {
    SCOPED_TRACE(shape);
    const Image below = render_textured(shape, kQuadrants, kFromBelow);
    expect_rgb(below.get(near_corner, near_corner), kRed);
    expect_rgb(below.get(kSize - 1 - near_corner, kSize - 1 - near_corner), kWhite);
  }
}

}  // namespace
}  // namespace tessera::test
