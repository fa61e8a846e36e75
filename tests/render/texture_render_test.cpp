// Textures in rendered pixels (§4.3): a solid texture and a modulating flat texture scale the
// Lambertian value of the lighting tests; a decal shows the texture as it is, with no light;
// and an image written to a BMP file comes back through the loader and the renderer.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/loaders/sdl_loader.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

constexpr int kSize = 65;
constexpr int kCentre = 32;  // looks along the view axis at the cube's front point (0, 0, 1)

// A cube facing the camera, lit head-on from far away: N.L = 1 at the centre.
Scene cube_scene(const Material& m) {
  Scene scene;
  scene.camera = camera_on_z();
  scene.globals.global_ambient = {0.1, 0.1, 0.1};
  scene.objects.push_back(object(Cube{}, Affine::identity(), m));
  scene.lights.push_back(point_light({0, 0, 1e7}, {1, 1, 1}));
  return scene;
}

Material lambertian() {
  Material m = black_material();
  m.ambient = {0.5, 0.5, 0.5};
  m.diffuse = {0.8, 0.6, 0.4};
  return m;
}

// Radial colours with equal inside and outside: the constant colour k everywhere.
FlatTexture constant_flat(const Rgb& k, bool decal) {
  FlatTexture f;
  f.kind = FlatTexture::Kind::Procedural;
  f.procedural_type = 2;
  f.params = {k.r, k.g, k.b, k.r, k.g, k.b};
  f.decal = decal;
  return f;
}

TEST(TextureRender, ModulatingFlatTextureScalesAmbientAndDiffuse) {
  const Rgb k{0.2, 0.5, 1.0};
  Material m = lambertian();
  m.flat_texture = constant_flat(k, false);
  const Scene scene = cube_scene(m);
  RenderStats stats;
  const Rgb c = render(scene, settings(kSize, kSize), &stats).get(kCentre, kCentre);
  // (ambient x globalAmbient + diffuse x N.L) x k
  expect_rgb(c, {(0.05 + 0.8) * 0.2, (0.05 + 0.6) * 0.5, (0.05 + 0.4) * 1.0});
  EXPECT_GT(stats.shadow_rays, 0u);
}

TEST(TextureRender, DecalShowsTheTextureWithoutLight) {
  const Rgb k{0.2, 0.5, 0.9};
  Material m = lambertian();
  m.emissive = {0.05, 0, 0};
  m.specular = {1, 1, 1};
  m.flat_texture = constant_flat(k, true);
  const Scene scene = cube_scene(m);
  RenderStats stats;
  const Rgb c = render(scene, settings(kSize, kSize), &stats).get(kCentre, kCentre);
  expect_rgb(c, {0.05 + 0.2, 0.5, 0.9});  // emissive + texture: no diffuse, no highlight
  EXPECT_EQ(stats.shadow_rays, 0u);       // nothing is lit, so no shadow feelers
}

TEST(TextureRender, SolidTexturesAlwaysModulate) {
  Material m = lambertian();
  // Marble along z with no turbulence: (1 + sin(2 pi z)) / 2 = 1/2 at z = 1, times the weights.
  m.solid_texture = {8, {2, 0, 1, 0.5, 0.2}};
  const Rgb k{0.5, 0.25, 0.1};
  const Scene scene = cube_scene(m);
  expect_rgb(render(scene, settings(kSize, kSize)).get(kCentre, kCentre),
             {(0.05 + 0.8) * k.r, (0.05 + 0.6) * k.g, (0.05 + 0.4) * k.b});
  // With a modulating flat texture as well, both factors apply.
  Scene both = scene;
  both.objects[0].material.flat_texture = constant_flat({0.5, 0.5, 0.5}, false);
  expect_rgb(render(both, settings(kSize, kSize)).get(kCentre, kCentre),
             {(0.05 + 0.8) * k.r / 2, (0.05 + 0.6) * k.g / 2, (0.05 + 0.4) * k.b / 2});
}

TEST(TextureRender, TexturesAreEffectsOnlyWhereUsed) {
  Scene scene = cube_scene(lambertian());
  {
    const PreparedScene plain(scene, BvhMode::Sah);
    EXPECT_FALSE(plain.textured());
    EXPECT_EQ(plain.effects().names(), std::vector<std::string>{"hard_shadows"});
  }
  scene.objects[0].material.solid_texture = {9, {0.5}};
  scene.objects.push_back(scene.objects[0]);
  scene.objects[1].material.flat_texture = constant_flat({1, 1, 1}, false);
  const PreparedScene textured(scene, BvhMode::Sah);
  EXPECT_TRUE(textured.textured());
  EXPECT_TRUE(textured.unsupported().empty());
  EXPECT_EQ(textured.effects().names(),
            (std::vector<std::string>{"hard_shadows", "solid_texture", "procedural_texture"}));
}

class ImageTextureFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("tessera_texture_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void write_text(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
  }
  std::filesystem::path dir_;
};

// 4x4 texels in four 2x2 quadrants: between the centres of a quadrant's texels the bilinear
// filter returns the quadrant's colour exactly.
Image quadrant_image() {
  const Rgb top_left{1, 0, 0}, top_right{0, 1, 0}, bottom_left{0, 0, 1};
  const Rgb bottom_right{51 / 255.0, 102 / 255.0, 204 / 255.0};
  Image image(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      image.set(x, y,
                y < 2 ? (x < 2 ? top_left : top_right) : (x < 2 ? bottom_left : bottom_right));
  return image;
}

TEST_F(ImageTextureFile, BmpRoundTripThroughLoaderAndRenderer) {
  write_image(quadrant_image(), (dir_ / "quadrants.bmp").string());
  write_text("scene.sdl", "viewAngle 30\nimageTexture quadrants.bmp 0 1 1\ncube\n");
  const Scene scene = load_sdl_file(dir_ / "scene.sdl");
  ASSERT_EQ(scene.images.size(), 1u);
  const PreparedScene prepared(scene, BvhMode::Sah);
  EXPECT_EQ(prepared.effects().names(), std::vector<std::string>{"image_texture"});
  RenderStats stats;
  const Image image = render_image(prepared, settings(64, 64), 1, stats);
  // The +z face seen from the front: the image upright, its top-left texels at the top left.
  expect_rgb(image.get(17, 17), {1, 0, 0});
  expect_rgb(image.get(46, 17), {0, 1, 0});
  expect_rgb(image.get(17, 46), {0, 0, 1});
  expect_rgb(image.get(46, 46), {51 / 255.0, 102 / 255.0, 204 / 255.0});
}

TEST_F(ImageTextureFile, UnreadableImageIsASceneErrorNamingFileAndLine) {
  write_text("broken.png", "this is not a PNG file");
  write_text("scene.sdl", "sphere\nimageTexture broken.png 1 1 1 sphere\n");
  const Scene scene = load_sdl_file(dir_ / "scene.sdl");
  try {
    const PreparedScene prepared(scene, BvhMode::Sah);
    FAIL() << "expected a scene error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.where().line, 2);
    EXPECT_EQ(e.where().column, 14);
    EXPECT_NE(e.message().find("broken.png"), std::string::npos) << e.message();
  }
}

}  // namespace
}  // namespace tessera::test
