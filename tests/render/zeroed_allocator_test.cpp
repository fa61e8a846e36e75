#include "common/render/zeroed_allocator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace tessera {
namespace {

template <typename T>
using ZeroedVector = std::vector<T, ZeroedAllocator<T>>;

TEST(ZeroedAllocator, SmallAndLargeBuffersStartAsZerosAndKeepWhatIsWritten) {
  for (const std::size_t n : {std::size_t{2}, std::size_t{1000}, std::size_t{3} << 20}) {
    ZeroedVector<float> values(n);
    ASSERT_TRUE(std::all_of(values.begin(), values.end(), [](float v) { return v == 0.0f; }))
        << n << " floats";
    values.front() = 1.5f;
    values.back() = 2.5f;
    EXPECT_EQ(values.front(), 1.5f);
    EXPECT_EQ(values.back(), 2.5f);
  }
}

TEST(ZeroedAllocator, RefusesACountWhoseBytesOverflow) {
  ZeroedAllocator<std::uint64_t> allocator;
  EXPECT_THROW(static_cast<void>(allocator.allocate(SIZE_MAX / 4)), std::bad_alloc);
}

#if defined(__linux__)
std::string file_text(const char* path) {
  std::ifstream in(path);
  std::string all((std::istreambuf_iterator<char>(in)), {});
  return all;
}

// The kilobytes of huge pages backing the mapping that holds `address` (/proc/self/smaps).
long anon_huge_kb_at(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  const auto at = reinterpret_cast<std::uintptr_t>(address);
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= at && at < hi;
    } else if (inside && line.rfind("AnonHugePages:", 0) == 0) {
      return std::stol(line.substr(line.find(':') + 1));
    }
  }
  return -1;
}

// The pages of [data, data + bytes) that are resident (mincore).
std::size_t resident_pages(const void* data, std::size_t bytes) {
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  std::vector<unsigned char> resident((bytes + page - 1) / page);
  EXPECT_EQ(mincore(const_cast<void*>(data), bytes, resident.data()), 0);
  return static_cast<std::size_t>(
      std::count_if(resident.begin(), resident.end(), [](unsigned char r) { return r & 1; }));
}

TEST(ZeroedAllocator, PopulatingMakesEveryPageOfTheRangeWithoutChangingIt) {
  ZeroedVector<float> buffer(std::size_t{4} << 20);  // 16 MB, mapped: no page until written
  const std::size_t pages =
      buffer.size() * sizeof(float) / static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  EXPECT_EQ(resident_pages(buffer.data(), buffer.size() * sizeof(float)), 0u);
  buffer[1000] = 7.0f;
  populate_for_writing({buffer.data() + 100, (buffer.size() - 100) * sizeof(float)});
  EXPECT_EQ(resident_pages(buffer.data(), buffer.size() * sizeof(float)), pages);
  EXPECT_EQ(buffer[1000], 7.0f);
  EXPECT_EQ(buffer[999], 0.0f);
  EXPECT_EQ(buffer.back(), 0.0f);
}

// Large buffers ask for transparent huge pages: a frame buffer's first writes then fault once
// per 2 MB, not twice per 4 kB (zeroed_allocator.h). Only where the kernel grants them on advice.
TEST(ZeroedAllocator, LargeBuffersGetHugePagesWhereTheKernelGrantsThemOnAdvice) {
  const std::string mode = file_text("/sys/kernel/mm/transparent_hugepage/enabled");
  if (mode.find("[madvise]") == std::string::npos)
    GTEST_SKIP() << "transparent huge pages are not in madvise mode here: " << mode;
  ZeroedVector<char> buffer(std::size_t{16} << 20);
  for (std::size_t i = 0; i < buffer.size(); i += 4096) buffer[i] = 1;
  EXPECT_GT(anon_huge_kb_at(buffer.data() + buffer.size() / 2), 0)
      << "a 16 MB buffer written throughout has no huge page";
}
#endif

}  // namespace
}  // namespace tessera
