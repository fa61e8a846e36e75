// Tar bundles: archives written by libarchive's own writer in each format a user's tar may
// produce, and hand-made damaged ones.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <archive.h>
#include <archive_entry.h>

#include "coordinator/http/tar_reader.h"

namespace tessera {
namespace {

struct Entry {
  std::string name, data;
  unsigned type = AE_IFREG;
  std::string link;  // for symbolic links
};
Entry file(std::string name, std::string data) {
  return {std::move(name), std::move(data), AE_IFREG, ""};
}
Entry directory(std::string name) { return {std::move(name), "", AE_IFDIR, ""}; }
Entry symlink(std::string name, std::string target) {
  return {std::move(name), "", AE_IFLNK, std::move(target)};
}

// An archive in `format` (ARCHIVE_FORMAT_TAR_USTAR, _PAX_RESTRICTED, _GNUTAR) of `entries`.
std::string write_tar(int format, const std::vector<Entry>& entries) {
  std::unique_ptr<archive, decltype(&archive_write_free)> a(archive_write_new(),
                                                            archive_write_free);
  archive_write_set_format(a.get(), format);
  std::vector<char> buffer(1 << 20);
  std::size_t used = 0;
  EXPECT_EQ(archive_write_open_memory(a.get(), buffer.data(), buffer.size(), &used), ARCHIVE_OK);
  for (const Entry& e : entries) {
    std::unique_ptr<archive_entry, decltype(&archive_entry_free)> h(archive_entry_new(),
                                                                    archive_entry_free);
    archive_entry_set_pathname(h.get(), e.name.c_str());
    archive_entry_set_filetype(h.get(), e.type);
    archive_entry_set_perm(h.get(), 0644);
    archive_entry_set_size(h.get(), static_cast<la_int64_t>(e.data.size()));
    if (!e.link.empty()) archive_entry_set_symlink(h.get(), e.link.c_str());
    EXPECT_EQ(archive_write_header(a.get(), h.get()), ARCHIVE_OK) << archive_error_string(a.get());
    if (!e.data.empty()) {
      EXPECT_EQ(archive_write_data(a.get(), e.data.data(), e.data.size()),
                static_cast<la_ssize_t>(e.data.size()));
    }
  }
  EXPECT_EQ(archive_write_close(a.get()), ARCHIVE_OK);
  return std::string(buffer.data(), used);
}

// Over the 100 characters of a tar header's name field: ustar splits it into its prefix field,
// PAX and GNU write extra header entries.
const std::string kLongName =
    "textures/" + std::string(60, 'd') + "/" + std::string(60, 'n') + ".ppm";

class TarFormats : public ::testing::TestWithParam<int> {};

TEST_P(TarFormats, ReadsRegularFilesAndSkipsTheRest) {
  const std::string archive = write_tar(
      GetParam(), {file("scene.sdl", "sphere"), directory("meshes"),
                   file("meshes/b.obj", "v 0 0 0"), file("./c.sdl", std::string(5000, 'c')),
                   symlink("link.sdl", "scene.sdl"), file(kLongName, "P3")});
  const auto files = read_tar(archive);
  ASSERT_EQ(files.size(), 4u);
  EXPECT_EQ(files.at("scene.sdl"), "sphere");
  EXPECT_EQ(files.at("meshes/b.obj"), "v 0 0 0");
  EXPECT_EQ(files.at("c.sdl"), std::string(5000, 'c'));  // "./" dropped
  EXPECT_EQ(files.at(kLongName), "P3");
}

INSTANTIATE_TEST_SUITE_P(TarReader, TarFormats,
                         ::testing::Values(ARCHIVE_FORMAT_TAR_USTAR,
                                           ARCHIVE_FORMAT_TAR_PAX_RESTRICTED,
                                           ARCHIVE_FORMAT_TAR_GNUTAR));

TEST(TarReader, RefusesADamagedHeaderChecksum) {
  std::string archive = write_tar(ARCHIVE_FORMAT_TAR_USTAR, {file("a.sdl", "sphere")});
  ASSERT_NO_THROW(read_tar(archive));
  archive[0] = 'b';  // the name changes; the stored checksum no longer matches
  EXPECT_THROW(read_tar(archive), std::runtime_error);
}

TEST(TarReader, RefusesATruncatedArchive) {
  const std::string archive =
      write_tar(ARCHIVE_FORMAT_TAR_USTAR, {file("a.sdl", std::string(600, 'x'))});
  EXPECT_THROW(read_tar(archive.substr(0, 700)), std::runtime_error);
}

TEST(TarReader, RefusesWhatIsNotATarArchive) {
  EXPECT_THROW(read_tar("camera { }"), std::runtime_error);
  EXPECT_THROW(read_tar(std::string(100, '\x1f')), std::runtime_error);
}

TEST(TarReader, AnEmptyArchiveHoldsNoFiles) {
  EXPECT_TRUE(read_tar(write_tar(ARCHIVE_FORMAT_TAR_USTAR, {})).empty());
}

}  // namespace
}  // namespace tessera
