// An allocator for numbers whose zero is all zero bits, from calloc. A vector of n zeros then
// costs no pass over its bytes where calloc takes fresh pages from the kernel (blocks above
// malloc's mmap threshold, 128 kB at first: a whole image's pixels): each page is zeroed by the
// kernel when it is first written, on the thread that writes it. render_image's tile threads
// so fault in the image between them, where a filled vector had the thread that made it fault
// in all of it before they started (docs/PERFORMANCE.md, "The image's pages, and one pass
// without a frame buffer").
//
// Only calloc and free, inline: OpenImageIO's module (common/image/oiio/), which links none of
// Tessera's sources, makes and frees images too.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <utility>

namespace tessera {

template <typename T>
struct CallocAllocator {
  using value_type = T;

  CallocAllocator() = default;
  template <typename U>
  CallocAllocator(const CallocAllocator<U>&) {}

  T* allocate(std::size_t n) {
    // calloc refuses a count whose bytes overflow.
    if (void* p = std::calloc(n, sizeof(T))) return static_cast<T*>(p);
    throw std::bad_alloc();
  }
  void deallocate(T* p, std::size_t) { std::free(p); }
  // A value-initialized element is already there: zero bits. (Not so for elements a vector
  // grows back into after it shrank within its capacity; the vectors that use this never shrink.)
  template <typename U>
  void construct(U*) {}
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  friend bool operator==(const CallocAllocator&, const CallocAllocator&) { return true; }
};

}  // namespace tessera
