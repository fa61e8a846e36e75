#include "common/render/zeroed_allocator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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
