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

}  // namespace
}  // namespace tessera::test
