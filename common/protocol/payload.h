// A frame's payload (frame.h): bytes, or float32 values whose bytes are the payload itself
// (pixels travel as the host's float32 bytes; messages.cpp allows only little-endian hosts).
// A connection reads a payload of whole floats into float values, so that a result's values go
// from the socket to the coordinator's merge and its store without a copy (docs/SCALING.md).
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace tessera {

// std::allocator, but a vector's new elements are left uninitialised instead of zeroed, for a
// buffer that is about to be read or written into (FloatValues(n) has n undefined values).
template <typename T>
struct UninitializedAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <typename U>
  UninitializedAllocator(const UninitializedAllocator<U>&) {}
  template <typename U>
  void construct(U* p) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// A unit's pixel values, 3 floats a pixel, from the socket to the store (ResultMessage): not
// zero-filled when made to be read into.
using FloatValues = std::vector<float, UninitializedAllocator<float>>;

class Payload {
 public:
  Payload() = default;
  // Implicit: encoders build payloads as strings, and float values (a result's) as they are.
  Payload(std::string bytes) : data_(std::move(bytes)) {}
  Payload(const char* bytes) : data_(std::string(bytes)) {}
  Payload(FloatValues values) : data_(std::move(values)) {}

  // `bytes` to read into, not zero-filled when they are whole floats (else a string).
  static Payload to_read(std::size_t bytes);

  char* data();
  std::size_t size() const;
  bool empty() const { return size() == 0; }
  std::string_view view() const;
  // The payload's float values (its size a multiple of 4: the caller checks), taken over when
  // it holds them, else copied from its bytes.
  FloatValues take_floats() &&;

  friend bool operator==(const Payload& a, const Payload& b) { return a.view() == b.view(); }

 private:
  std::variant<std::string, FloatValues> data_;
};

}  // namespace tessera
