// The format dispatcher: a job's format names and a file's name pick the loader.
#include <gtest/gtest.h>

#include "common/loaders/scene_loader.h"

namespace tessera::test {
namespace {

TEST(SceneLoader, FormatNames) {
  EXPECT_EQ(scene_format_named("sdl"), SceneFormat::Sdl);
  EXPECT_EQ(scene_format_named("vrml"), SceneFormat::Vrml);
  EXPECT_FALSE(scene_format_named("VRML"));
  EXPECT_FALSE(scene_format_named("obj"));
}

TEST(SceneLoader, FileNamesPickTheFormat) {
  EXPECT_EQ(scene_format_of("a/world.wrl"), SceneFormat::Vrml);
  EXPECT_EQ(scene_format_of("WORLD.WRL.GZ"), SceneFormat::Vrml);
  EXPECT_EQ(scene_format_of("world.wrz"), SceneFormat::Vrml);
  EXPECT_EQ(scene_format_of("scene.sdl"), SceneFormat::Sdl);
  EXPECT_EQ(scene_format_of("notes.txt"), SceneFormat::Sdl);
}

TEST(SceneLoader, LoadsEachFormatWithItsLoader) {
  MemorySource source;
  source.add("scene.sdl", "sphere\n");
  source.add("world.wrl", "#VRML V2.0 utf8\nShape { geometry Box {} }\n");
  EXPECT_TRUE(std::holds_alternative<Sphere>(
      load_scene(source, "scene.sdl", SceneFormat::Sdl).objects.at(0).geometry));
  EXPECT_TRUE(std::holds_alternative<Cube>(
      load_scene(source, "world.wrl", SceneFormat::Vrml).objects.at(0).geometry));
  EXPECT_THROW(load_scene(source, "world.wrl", SceneFormat::Sdl), SceneError);
}

// The camera setting's fov is each format's own angle: SDL's vertical viewAngle, VRML's
// fieldOfView across the smaller side.
TEST(SceneLoader, ACameraReplacesTheScenesInTheFormatsOwnAngle) {
  MemorySource source;
  source.add("scene.sdl", "eyePoint 9 9 9\nviewAngle 60\nsphere\n");
  source.add("world.wrl", "#VRML V2.0 utf8\nViewpoint { position 9 9 9 }\n");
  Camera camera{{1, 2, 3}, {0, 0, 0}, {0, 0, 1}, 20};
  camera.view_angle_on_smaller_side = true;  // not the setting's to say
  const Scene sdl = load_scene(source, "scene.sdl", SceneFormat::Sdl, {}, camera);
  EXPECT_EQ(sdl.camera.eye, camera.eye);
  EXPECT_EQ(sdl.camera.up, camera.up);
  EXPECT_EQ(sdl.camera.view_angle, 20);
  EXPECT_FALSE(sdl.camera.view_angle_on_smaller_side);
  camera.view_angle_on_smaller_side = false;
  const Scene vrml = load_scene(source, "world.wrl", SceneFormat::Vrml, {}, camera);
  EXPECT_EQ(vrml.camera.look_at, camera.look_at);
  EXPECT_EQ(vrml.camera.view_angle, 20);
  EXPECT_TRUE(vrml.camera.view_angle_on_smaller_side);
}

}  // namespace
}  // namespace tessera::test
