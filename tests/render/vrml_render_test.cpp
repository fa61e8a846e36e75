// VRML worlds in rendered pixels, with analytic expectations: a Box face under a
// DirectionalLight has its Lambertian value, a Sphere seen from a Viewpoint covers the area of
// its silhouette, the headlight lights what the camera sees head-on, point lights attenuate
// by their own factors within their radius, linear and exponential fog keep their share, and a
// world with no Viewpoint is framed by its bounding sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/loaders/scene_source.h"
#include "common/loaders/vrml_loader.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

Scene world(const std::string& body) {
  MemorySource source;
  source.add("world.wrl", "#VRML V2.0 utf8\n" + body);
  return load_vrml(source, "world.wrl");
}

int covered_pixels(const Image& image, const Rgb& background) {
  int count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) count += image.get(x, y) == background ? 0 : 1;
  return count;
}

TEST(VrmlRender, BoxFaceUnderADirectionalLightHasItsLambertianValue) {
  const Scene scene = world(
      "NavigationInfo { headlight FALSE }\n"
      "Viewpoint { position 0 0 5 }\n"
      "DirectionalLight { direction 0 -0.6 -0.8 intensity 0.5 }\n"
      "Shape { appearance Appearance { material Material { diffuseColor 0.5 0.25 1 } }\n"
      "        geometry Box {} }\n");
  RenderStats stats;
  const Rgb c = render(scene, settings(33, 33), &stats).get(16, 16);
  // diffuse x intensity x cos: the front face's normal is +z, so cos = 0.8; no ambient light.
  EXPECT_NEAR(c.r, 0.5 * 0.5 * 0.8, 1e-6);
  EXPECT_NEAR(c.g, 0.25 * 0.5 * 0.8, 1e-6);
  EXPECT_NEAR(c.b, 1.0 * 0.5 * 0.8, 1e-6);
  EXPECT_GT(stats.shadow_rays, 0u);
  const PreparedScene prepared(scene, BvhMode::Sah);
  EXPECT_TRUE(prepared.effects().has(Effect::DirectionalLight));
}

TEST(VrmlRender, PointLightsAttenuateEachByItsOwnFactorsAndReachOnlyTheirRadius) {
  // The Box's front face (z = 1) seen head-on, lit by point lights on the view axis at z = 3:
  // distance 2 and N.L = 1 at the centre pixel.
  const std::string view =
      "NavigationInfo { headlight FALSE }\n"
      "Viewpoint { position 0 0 5 }\n"
      "Shape { appearance Appearance { material Material { diffuseColor 1 1 1 } }\n"
      "        geometry Box {} }\n";
  const auto centre = [&](const std::string& lights) {
    return render(world(view + lights), settings(33, 33)).get(16, 16).r;
  };
  EXPECT_NEAR(centre("PointLight { location 0 0 3 intensity 0.9 }"), 0.9, 1e-6);
  // 1 / (1 + 0.5 * 2 + 0.25 * 4) = 1/3, for this light only; the other keeps its full value.
  EXPECT_NEAR(centre("PointLight { location 0 0 3 intensity 0.9 attenuation 1 0.5 0.25 }"), 0.3,
              1e-6);
  EXPECT_NEAR(centre("PointLight { location 0 0 3 intensity 0.3 attenuation 0 0 1 }\n"
                     "PointLight { location 0 0 3 intensity 0.4 }"),
              0.3 / 4 + 0.4, 1e-6);
  // Beyond its radius a light lights nothing; the radius scales with the light's transform.
  EXPECT_EQ(centre("PointLight { location 0 0 3 radius 1.9 }"), 0.0);
  EXPECT_NEAR(
      centre("Transform { scale 2 2 2 children PointLight { location 0 0 1.5 radius 1.1 } }"), 1.0,
      1e-6);
}

TEST(VrmlRender, LinearAndExponentialFogKeepTheirShareOfTheColour) {
  // A glowing box face 4 units from the eye, black fog with visibilityRange 8.
  const auto centre = [&](const std::string& fog_type) {
    const Scene scene = world(
        "NavigationInfo { headlight FALSE }\n"
        "Viewpoint { position 0 0 5 }\n"
        "Fog { color 0 0 0 visibilityRange 8 fogType \"" +
        fog_type +
        "\" }\n"
        "Shape { appearance Appearance { material Material { diffuseColor 0 0 0 "
        "emissiveColor 1 1 1 } } geometry Box {} }\n");
    return render(scene, settings(33, 33)).get(16, 16).r;
  };
  EXPECT_NEAR(centre("LINEAR"), (8.0 - 4) / 8, 1e-6);
  EXPECT_NEAR(centre("EXPONENTIAL"), std::exp(-4.0 / (8 - 4)), 1e-6);
}

TEST(VrmlRender, DirectionalLightsCastShadowsWithoutEnd) {
  // A plate far above the box, between it and a light shining straight down.
  const Scene scene = world(
      "NavigationInfo { headlight FALSE }\n"
      "Viewpoint { position 0 10 0 orientation 1 0 0 -1.5707963267948966 }\n"
      "DirectionalLight { direction 0 -1 0 }\n"
      "Shape { appearance Appearance { material Material {} } geometry Box { size 4 2 4 } }\n"
      "Transform { translation 2 1000 0 children Shape { geometry Box { size 4 0.1 4 } } }\n");
  const Image image = render(scene, settings(41, 41));
  EXPECT_NEAR(image.get(12, 20).r, 0.8, 1e-6);  // x < 0: lit, N.L = 1
  EXPECT_EQ(image.get(28, 20).r, 0);            // x > 0: under the plate
}

TEST(VrmlRender, DirectionalLightLightsOnlyItsSiblingsButShadowsAll) {
  // Two boxes seen from above, x in [-3, -1] and [1, 3], under a light shining straight down
  // that is a sibling of the left one only. A plate far above the left box's left half, outside
  // the light's group, still casts its shadow. Both glow a little, to tell them from the sky.
  const Scene scene = world(
      "NavigationInfo { headlight FALSE }\n"
      "Viewpoint { position 0 10 0 orientation 1 0 0 -1.5707963267948966 }\n"
      "Transform { translation -2 0 0 children [\n"
      "  DirectionalLight { direction 0 -1 0 intensity 0.8 }\n"
      "  DEF Glow Shape { appearance Appearance { material Material { emissiveColor 0.1 0.1 0.1 } "
      "}\n"
      "                  geometry Box {} } ] }\n"
      "Transform { translation 2 0 0 children USE Glow }\n"
      "Transform { translation -2.75 1000 0 children Shape { geometry Box { size 1.5 0.1 4 } } "
      "}\n");
  const Image image = render(scene, settings(81, 41));
  // 9 units below the eye, a 45 degree view 41 pixels high spans 0.18 units a pixel.
  EXPECT_NEAR(image.get(32, 20).r, 0.1 + 0.8 * 0.8, 1e-6);  // left box, x = -1.5: N.L = 1
  EXPECT_NEAR(image.get(25, 20).r, 0.1, 1e-6);              // left box, x = -2.7: under the plate
  EXPECT_NEAR(image.get(51, 20).r, 0.1, 1e-6);              // right box: outside the light's scope
}

TEST(VrmlRender, BackgroundGradientColoursEachPixelByItsAngle) {
  // An empty world seen level from the origin: a pixel in the middle column, row j of 41, looks
  // up at the elevation e with tan e = (1 - 2 (j + 1/2) / 41) tan(22.5 degrees). The sky runs
  // from blue straight up to white at the horizon, the ground from black straight down to
  // green there.
  const std::string body =
      "Viewpoint { position 0 0 0 fieldOfView 0.7853981633974483 }\n"
      "Background { skyColor [0 0 1, 1 1 1] skyAngle 1.5707963267948966\n"
      "             groundColor [0 0 0, 0 1 0] groundAngle 1.5707963267948966 }\n";
  const Scene scene = world(body);
  const Image image = render(scene, settings(41, 41));
  for (const int j : {0, 7, 19, 21, 33, 40}) {
    SCOPED_TRACE(j);
    const double e = std::atan((1 - 2 * (j + 0.5) / 41) * std::tan(std::numbers::pi / 8));
    const double f = 1 - std::abs(e) / (std::numbers::pi / 2);  // towards the horizon
    const Rgb expected = e > 0 ? Rgb{f, f, 1} : Rgb{0, f, 0};
    const Rgb got = image.get(20, j);
    EXPECT_NEAR(got.r, expected.r, 1e-6);
    EXPECT_NEAR(got.g, expected.g, 1e-6);
    EXPECT_NEAR(got.b, expected.b, 1e-6);
  }
  EXPECT_TRUE(PreparedScene(scene, BvhMode::Sah).effects().has(Effect::SkyGradient));
  // One sky colour is no gradient: the background costs what SDL's does.
  const Scene plain = world("Background { skyColor 0.2 0.3 0.4 }\n");
  EXPECT_FALSE(PreparedScene(plain, BvhMode::Sah).effects().has(Effect::SkyGradient));
  expect_rgb(render(plain, settings(9, 9)).get(4, 4), {0.2, 0.3, 0.4});
}

TEST(VrmlRender, SphereFromAViewpointCoversItsSilhouette) {
  const double r = 1, d = 6, fov = 0.6;
  const Scene scene = world(
      "Viewpoint { position 0 0 6 fieldOfView 0.6 }\n"
      "Background { skyColor 0 0 1 }\n"
      "Shape { geometry Sphere { radius 1 } }\n");
  const int size = 200;
  const Image image = render(scene, settings(size, size));
  // The silhouette is a circle of angular radius asin(r / d); on the image plane its radius is
  // tan(asin(r / d)) against tan(fov / 2) for half the image.
  const double radius_px = std::tan(std::asin(r / d)) / std::tan(fov / 2) * size / 2;
  const double expected = std::numbers::pi * radius_px * radius_px;
  EXPECT_NEAR(covered_pixels(image, {0, 0, 1}), expected, 2 * std::numbers::pi * radius_px);
}

TEST(VrmlRender, HeadlightLightsWhatTheCameraSeesHeadOn) {
  const std::string sphere =
      "Viewpoint { position 0 0 5 }\n"
      "Shape { appearance Appearance { material Material { diffuseColor 0.6 0.4 0.2 } }\n"
      "        geometry Sphere {} }\n";
  const Rgb on = render(world(sphere), settings(33, 33)).get(16, 16);
  EXPECT_NEAR(on.r, 0.6, 1e-6);  // N.L = 1 at the centre, intensity 1, no ambient light
  EXPECT_NEAR(on.g, 0.4, 1e-6);
  EXPECT_NEAR(on.b, 0.2, 1e-6);
  const Rgb off =
      render(world("NavigationInfo { headlight FALSE }\n" + sphere), settings(33, 33)).get(16, 16);
  EXPECT_EQ(off, (Rgb{0, 0, 0}));
}

TEST(VrmlRender, WorldWithoutViewpointIsFramedByItsBoundingSphere) {
  // The unit sphere's bounding sphere is itself: its silhouette is the disc inscribed in the
  // image's smaller side, whichever side that is.
  const Scene scene = world(
      "Background { skyColor 0 0 1 }\n"
      "Transform { translation 3 -2 7 children Shape { geometry Sphere {} } }\n");
  EXPECT_EQ(scene.camera.look_at, (Vec3{3, -2, 7}));
  for (const auto& [w, h] : {std::pair{160, 160}, std::pair{200, 120}, std::pair{120, 200}}) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    const Image image = render(scene, settings(w, h));
    const double side = std::min(w, h);
    const double expected = std::numbers::pi * side * side / 4;
    EXPECT_NEAR(covered_pixels(image, {0, 0, 1}), expected, 2 * std::numbers::pi * side / 2);
    // It touches the frame: covered pixels in the middle row (column) reach the short sides.
    const bool wide = w >= h;
    const Rgb edge = wide ? image.get(w / 2, 0) : image.get(0, h / 2);
    EXPECT_NE(edge, (Rgb{0, 0, 1}));
  }
}

}  // namespace
}  // namespace tessera::test
