// Stopping a render part-way (issue 16 §3): a cancel flag another thread sets, a deadline, or
// both. The renderer checks them before every pixel and, inside a pixel, every
// Tracer::kPollRays rays, so that even a pixel of runaway cost stops within milliseconds.
// The default interrupt never fires and costs a render nothing measurable.
#pragma once

#include <atomic>
#include <chrono>
#include <exception>

namespace tessera {

struct RenderInterrupt {
  using Clock = std::chrono::steady_clock;
  const std::atomic<bool>* cancel = nullptr;              // stop once it reads true
  Clock::time_point deadline = Clock::time_point::max();  // stop once it has passed

  // Whether it can ever fire.
  bool armed() const { return cancel || deadline != Clock::time_point::max(); }
  bool requested() const {
    return (cancel && cancel->load(std::memory_order_relaxed)) ||
           (deadline != Clock::time_point::max() && Clock::now() >= deadline);
  }
};

// What render_pass, render_pixels and render_image throw when their RenderInterrupt fires: the
// values of the pixels are lost; the statistics hold the work done until then.
class RenderInterrupted : public std::exception {
 public:
  const char* what() const noexcept override { return "render interrupted"; }
};

}  // namespace tessera
