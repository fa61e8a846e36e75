#include "common/protocol/bundle.h"

#include <gtest/gtest.h>

namespace tessera {
namespace {

Bundle sample() {
  Bundle b;
  b.main = "scene.sdl";
  b.files["scene.sdl"] = "sphere";
  b.files["meshes/bunny.obj"] = std::string("v 0 0 0\n\0binary", 15);
  return b;
}

TEST(Bundle, RoundTrips) {
  nlohmann::json header;
  std::string payload;
  encode_bundle(sample(), header, payload);
  EXPECT_EQ(decode_bundle(header, payload), sample());
}

TEST(Bundle, HashFollowsContent) {
  Bundle b = sample();
  EXPECT_EQ(content_hash(b), content_hash(sample()));
  b.files["scene.sdl"] += " ";
  EXPECT_NE(content_hash(b), content_hash(sample()));
  Bundle moved = sample();
  moved.main = "meshes/bunny.obj";
  EXPECT_NE(content_hash(moved), content_hash(sample()));
}

TEST(Bundle, RefusesBadSizesAndPaths) {
  nlohmann::json header;
  std::string payload;
  encode_bundle(sample(), header, payload);
  EXPECT_THROW(decode_bundle(header, payload + "x"), ProtocolError);
  EXPECT_THROW(decode_bundle(header, payload.substr(1)), ProtocolError);
  nlohmann::json escaping = header;
  escaping["files"][0]["path"] = "../etc/passwd";
  EXPECT_THROW(decode_bundle(escaping, payload), ProtocolError);
  nlohmann::json no_main = header;
  no_main["main"] = "other.sdl";
  EXPECT_THROW(decode_bundle(no_main, payload), ProtocolError);
  EXPECT_THROW(decode_bundle(nlohmann::json::object(), payload), ProtocolError);
}

TEST(Bundle, PlainRelativePaths) {
  EXPECT_TRUE(is_plain_relative_path("a/b.obj"));
  EXPECT_FALSE(is_plain_relative_path("/a"));
  EXPECT_FALSE(is_plain_relative_path("a/../b"));
  EXPECT_FALSE(is_plain_relative_path("a//b"));
  EXPECT_FALSE(is_plain_relative_path("./a"));
  EXPECT_FALSE(is_plain_relative_path(""));
}

}  // namespace
}  // namespace tessera
