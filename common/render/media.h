// The media a ray travels in, for interpenetrating transparent objects (§4.1.4): inside
// several objects at once, the one of highest priority sets the speed of light (ties go to
// the one entered last); outside all of them the ray is in air (priority 0, speed 1).
// Surfaces whose crossing does not change that medium are false interfaces and are skipped
// (Schmidt and Budge, "Simple nested dielectrics in ray traced images", 2002).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

namespace tessera {

// Trivially constructible, so that a stack's unused entries cost nothing: a MediumStack is made
// or copied for every ray traced. Air is Medium::air().
struct Medium {
  std::uint32_t instance;
  int priority;
  double speed_of_light;
  static constexpr std::uint32_t kAir = 0xffffffffu;
  static constexpr Medium air() { return {kAir, 0, 1}; }
};

class MediumStack {
 public:
  static constexpr int kCapacity = 16;

  MediumStack() = default;
  // Only the entries in use are copied (and ever read): the rest stay uninitialized.
  MediumStack(const MediumStack& other) : size_(other.size_) {
    std::copy_n(other.entries_.begin(), size_, entries_.begin());
  }
  MediumStack& operator=(const MediumStack& other) {
    size_ = other.size_;
    std::copy_n(other.entries_.begin(), size_, entries_.begin());
    return *this;
  }

  // The medium that governs refraction: highest priority, latest entered among equals.
  Medium top() const {
    Medium best = Medium::air();
    for (int i = 0; i < size_; ++i)
      if (entries_[i].priority >= best.priority) best = entries_[i];
    return best;
  }
  bool contains(std::uint32_t instance) const {
    for (int i = 0; i < size_; ++i)
      if (entries_[i].instance == instance) return true;
    return false;
  }
  // Entering past the capacity is ignored (the ray then treats the surface as false).
  MediumStack entered(const Medium& m) const {
    MediumStack s = *this;
    if (s.size_ < kCapacity) s.entries_[s.size_++] = m;
    return s;
  }
  MediumStack exited(std::uint32_t instance) const {
    MediumStack s;
    for (int i = 0; i < size_; ++i)
      if (entries_[i].instance != instance) s.entries_[s.size_++] = entries_[i];
    return s;
  }

 private:
  std::array<Medium, kCapacity> entries_;
  int size_ = 0;
};

}  // namespace tessera
