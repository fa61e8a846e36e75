// Scene sources: path resolution, MemorySource, DirectorySource and load_sdl_file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/loaders/scene_loader.h"
#include "tests/loaders/vrml_test_util.h"

namespace tessera::test {
namespace {

namespace fs = std::filesystem;

TEST(ResolveScenePath, RelativeToTheFolderOfTheFile) {
  EXPECT_EQ(resolve_scene_path("scene.sdl", "a.sdl"), "a.sdl");
  EXPECT_EQ(resolve_scene_path("scene.sdl", "sub/a.obj"), "sub/a.obj");
  EXPECT_EQ(resolve_scene_path("sub/scene.sdl", "a.obj"), "sub/a.obj");
  EXPECT_EQ(resolve_scene_path("sub/deep/s.sdl", "../a.obj"), "sub/a.obj");
  EXPECT_EQ(resolve_scene_path("sub/s.sdl", "../a.obj"), "a.obj");
  EXPECT_EQ(resolve_scene_path("s.sdl", "./x/./y//z.obj"), "x/y/z.obj");
  EXPECT_EQ(resolve_scene_path("s.sdl", "x/../y.obj"), "y.obj");
  EXPECT_EQ(resolve_scene_path("", "y.obj"), "y.obj");
}

TEST(ResolveScenePath, KeepsWhatClimbsOutOfTheRootForTheSourceToJudge) {
  EXPECT_EQ(resolve_scene_path("s.sdl", "../a.obj"), "../a.obj");
  EXPECT_EQ(resolve_scene_path("sub/s.sdl", "../../t/a.obj"), "../t/a.obj");
  EXPECT_EQ(resolve_scene_path("s.sdl", "x/../../a.obj"), "../a.obj");
  EXPECT_EQ(resolve_scene_path("../w/s.wrl", "../t/y.jpg"), "../t/y.jpg");
  EXPECT_EQ(resolve_scene_path("s.sdl", "/etc/passwd"), "/etc/passwd");
  EXPECT_EQ(resolve_scene_path("/a/s.sdl", "../../../b.obj"), "/b.obj");
  EXPECT_EQ(resolve_scene_path("s.sdl", ""), std::nullopt);
  EXPECT_EQ(resolve_scene_path("s.sdl", "."), std::nullopt);  // the root is not a file
  EXPECT_EQ(resolve_scene_path("s.sdl", std::string("a\0b", 3)), std::nullopt);
}

TEST(SceneSource, AdmitsOnlyPathsInsideTheRoot) {
  const MemorySource memory;
  EXPECT_TRUE(memory.admits("a/b.obj"));
  EXPECT_FALSE(memory.admits("../a.obj"));
  EXPECT_FALSE(memory.admits("/etc/passwd"));
  EXPECT_EQ(why_unreadable(memory, "a.obj"), "not found");
  EXPECT_EQ(why_unreadable(memory, "../a.obj"), "is outside the scene's root");
  EXPECT_TRUE(DirectorySource("/tmp/r").admits("../r/a.obj"));
  EXPECT_FALSE(DirectorySource("/tmp/r").admits("../q/a.obj"));
  EXPECT_TRUE(DirectorySource("/tmp/r", /*confined=*/false).admits("../q/a.obj"));
}

TEST(MemorySource, ReadsWhatWasAdded) {
  MemorySource source(Files{{"a.sdl", "sphere"}});
  source.add("sub/b.obj", "v 0 0 0");
  EXPECT_EQ(source.read("a.sdl"), "sphere");
  EXPECT_EQ(source.read("sub/b.obj"), "v 0 0 0");
  EXPECT_EQ(source.read("b.obj"), std::nullopt);
  EXPECT_EQ(source.read("A.sdl"), std::nullopt);
}

// A scratch folder: root/ holds the scene, outside/ is next to it.
class DirectorySourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = fs::temp_directory_path() /
            ("tessera_loaders_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(base_);
    fs::create_directories(root() / "sub");
    fs::create_directories(base_ / "outside");
  }
  void TearDown() override { fs::remove_all(base_); }

  fs::path root() const { return base_ / "root"; }
  static void write(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
  }

  fs::path base_;
};

TEST_F(DirectorySourceTest, ReadsFilesUnderTheRoot) {
  write(root() / "a.sdl", "sphere");
  write(root() / "sub" / "b.sdl", std::string("cu\0be", 5));
  const DirectorySource source(root());
  EXPECT_EQ(source.read("a.sdl"), "sphere");
  EXPECT_EQ(source.read("sub/b.sdl"), std::string("cu\0be", 5));
  EXPECT_EQ(source.read("missing.sdl"), std::nullopt);
  EXPECT_EQ(source.read("sub"), std::nullopt);  // a folder is not a file
  EXPECT_EQ(source.read(""), std::nullopt);
}

TEST_F(DirectorySourceTest, RefusesPathsOutsideTheRoot) {
  write(base_ / "outside" / "secret.sdl", "secret");
  const DirectorySource source(root());
  EXPECT_EQ(source.read("../outside/secret.sdl"), std::nullopt);
  EXPECT_EQ(source.read((base_ / "outside" / "secret.sdl").string()), std::nullopt);
  // Even when the name goes out and back in, it is refused only if it ends outside.
  write(root() / "a.sdl", "sphere");
  EXPECT_EQ(source.read("../root/a.sdl"), "sphere");
}

TEST_F(DirectorySourceTest, RefusesSymbolicLinksThatLeaveTheRoot) {
  write(base_ / "outside" / "secret.sdl", "secret");
  write(root() / "real.sdl", "sphere");
  fs::create_symlink(base_ / "outside" / "secret.sdl", root() / "link.sdl");
  fs::create_directory_symlink(base_ / "outside", root() / "sub" / "out");
  fs::create_symlink("real.sdl", root() / "inner.sdl");
  const DirectorySource source(root());
  EXPECT_EQ(source.read("link.sdl"), std::nullopt);
  EXPECT_EQ(source.read("sub/out/secret.sdl"), std::nullopt);
  EXPECT_EQ(source.read("inner.sdl"), "sphere");  // a link that stays inside is fine
}

TEST_F(DirectorySourceTest, LoadSdlFileUsesTheFilesFolderAsRoot) {
  write(root() / "scene.sdl", "include sub/part.sdl\nmesh sub/tri.obj 1");
  write(root() / "sub" / "part.sdl", "sphere\nbad 1");
  write(root() / "sub" / "tri.obj", kTriangleObj);
  try {
    load_sdl_file(root() / "scene.sdl");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "sub/part.sdl:2:1: unknown keyword 'bad'");
  }
  write(root() / "sub" / "part.sdl", "sphere");
  const Scene scene = load_sdl_file(root() / "scene.sdl");
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.meshes.at(0).source, "sub/tri.obj");
  EXPECT_EQ(scene.objects[0].where.file, "sub/part.sdl");
}

TEST_F(DirectorySourceTest, LoadSdlFileRefusesIncludesOutsideTheFolder) {
  write(base_ / "outside" / "x.sdl", "sphere");
  write(root() / "scene.sdl", "include ../outside/x.sdl");
  try {
    load_sdl_file(root() / "scene.sdl");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "scene.sdl:1:9: include '../outside/x.sdl' leaves the scene's folder");
  }
  fs::create_symlink(base_ / "outside" / "x.sdl", root() / "x.sdl");
  write(root() / "scene.sdl", "include x.sdl");
  try {
    load_sdl_file(root() / "scene.sdl");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "scene.sdl:1:9: included file 'x.sdl' not found");
  }
}

// The command line reads what its user can read: `../` leads out of the scene's folder,
// unless --root confines it.
TEST_F(DirectorySourceTest, LoadSceneFileFollowsDotDotUnlessARootConfinesIt) {
  fs::create_directories(base_ / "textures");
  std::ofstream(base_ / "textures" / "y.ppm", std::ios::binary) << kTinyPpm;
  write(root() / "x.wrl",
        "#VRML V2.0 utf8\nShape { appearance Appearance { texture ImageTexture {\n"
        "  url \"../textures/y.ppm\" } } geometry Box {} }\n"
        "Inline { url \"../outside/part.wrl\" }\n");
  write(base_ / "outside" / "part.wrl", "#VRML V2.0 utf8\nShape { geometry Sphere {} }\n");
  LoadBudget strict;
  strict.strict = true;
  const Scene scene = load_scene_file(root() / "x.wrl", strict);
  EXPECT_EQ(scene.objects.size(), 2u);
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.images[0].path, "../textures/y.ppm");
  // --root at the common folder: the same files, named from there.
  const Scene rooted = load_scene_file(root() / "x.wrl", strict, base_);
  ASSERT_EQ(rooted.images.size(), 1u);
  EXPECT_EQ(rooted.images[0].path, "textures/y.ppm");
  // --root at the scene's own folder: outside it, and said so (not "not found").
  try {
    load_scene_file(root() / "x.wrl", strict, root());
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(),
                 "x.wrl:2:41: ImageTexture: '../textures/y.ppm' is outside the scene's root: the "
                 "shape is drawn untextured");
  }
  EXPECT_THROW(load_scene_file(root() / "x.wrl", strict, base_ / "outside"), SceneError);
}

}  // namespace
}  // namespace tessera::test
