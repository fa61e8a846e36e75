// An allocator that leaves its elements unwritten, for a buffer that writes each value before
// it reads it: FrameBuffer's sums, whose pixels' first pass is stored rather than added
// (frame_buffer.h). A vector resized with it costs no pass over its bytes at all, not even the
// pool's memset of a reused mapping (56 MB of sums and counts for a 2048x2048 job, 48 MB of it
// sums; docs/SCALING.md). Buffers of 2 MB and more come from the mapping pool, as
// ZeroedAllocator's do, the smaller ones from malloc.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <limits>
#include <new>
#include <utility>

#include "common/render/mapping_pool.h"
#include "common/render/zeroed_allocator.h"

namespace tessera {

template <typename T>
struct UnfilledAllocator {
  using value_type = T;
  static constexpr std::size_t kMappedBytes = ZeroedAllocator<T>::kMappedBytes;

  UnfilledAllocator() = default;
  template <typename U>
  UnfilledAllocator(const UnfilledAllocator<U>&) {}

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_alloc();
    const std::size_t bytes = n * sizeof(T);
#if defined(__linux__)
    if (bytes >= kMappedBytes)
      return static_cast<T*>(MappingPool::shared().take(bytes, MappingPool::Clock::now(),
                                                        MappingPool::Fill::Unfilled));
#endif
    if (void* p = std::malloc(bytes == 0 ? 1 : bytes)) return static_cast<T*>(p);
    throw std::bad_alloc();
  }
  void deallocate(T* p, std::size_t n) {
#if defined(__linux__)
    if (n * sizeof(T) >= kMappedBytes) return MappingPool::shared().give(p, n * sizeof(T));
#endif
    std::free(p);
  }
  // A value-initialized element is left as the memory holds it.
  template <typename U>
  void construct(U*) {}
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  friend bool operator==(const UnfilledAllocator&, const UnfilledAllocator&) { return true; }
};

}  // namespace tessera
