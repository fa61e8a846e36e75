// An allocator for numbers whose zero is all zero bits, for large buffers that fill up as work
// arrives (a coordinator job's frame buffer: 14 bytes a pixel, 56 MB at 2048x2048). A new
// vector of zeros costs no pass over its bytes: memory comes zeroed from the kernel as it is
// first written, so it is paid for as pixels merge, not all at once when the job is created, and
// a region job never touches the rest.
//
// Buffers of 2 MB and more are mapped directly and advised to use transparent huge pages
// (Linux): one fault then zeroes 2 MB instead of 4 kB, and the merge's scattered rows miss the
// TLB far less. With 4 kB pages a first read maps the shared zero page and the first write
// faults again to copy it; that pair of faults per 4 kB was a fifth of the coordinator's merging
// time (docs/SCALING.md). Where huge pages are off the advice does nothing. A freed mapping is
// kept a little while for the next buffer that asks (mapping_pool.h): zeroing pages still mapped
// costs a hundredth of having the kernel make new ones. Smaller buffers come from calloc
// (CallocAllocator, whose construction this shares).
#pragma once

#include <cstddef>
#include <limits>
#include <new>

#include "common/image/calloc_allocator.h"
#include "common/render/mapping_pool.h"

namespace tessera {

template <typename T>
struct ZeroedAllocator : CallocAllocator<T> {
  // At and above this size a buffer is mapped, with the huge-page advice, through the pool.
  static constexpr std::size_t kMappedBytes = std::size_t{2} << 20;

  ZeroedAllocator() = default;
  template <typename U>
  ZeroedAllocator(const ZeroedAllocator<U>&) {}

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_alloc();
#if defined(__linux__)
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kMappedBytes) return static_cast<T*>(MappingPool::shared().take(bytes));
#endif
    return CallocAllocator<T>::allocate(n);
  }
  void deallocate(T* p, std::size_t n) {
#if defined(__linux__)
    if (n * sizeof(T) >= kMappedBytes) return MappingPool::shared().give(p, n * sizeof(T));
#endif
    CallocAllocator<T>::deallocate(p, n);
  }
  friend bool operator==(const ZeroedAllocator&, const ZeroedAllocator&) { return true; }
};

}  // namespace tessera
