#include "common/render/mapping_pool.h"

#if defined(__linux__)

#include <algorithm>
#include <cstring>
#include <new>

#include <sys/mman.h>
#include <unistd.h>

namespace tessera {

namespace {

std::size_t whole_pages(std::size_t bytes) {
  static const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return (bytes + page - 1) / page * page;
}

void unmap(void* mapping, std::size_t bytes) { munmap(mapping, whole_pages(bytes)); }

}  // namespace

MappingPool::~MappingPool() {
  for (const Kept& k : kept_) unmap(k.mapping, k.bytes);
}

MappingPool& MappingPool::shared() {
  // Never destroyed: buffers freed by other static objects' destructors may still come back.
  static auto* pool = new MappingPool();
  return *pool;
}

void* MappingPool::take(std::size_t bytes, Clock::time_point now) {
  {
    std::lock_guard lock(mutex_);
    release_idle_locked(now);
    auto best = kept_.end();
    for (auto k = kept_.begin(); k != kept_.end(); ++k)
      if (k->bytes >= bytes && (best == kept_.end() || k->bytes < best->bytes)) best = k;
    if (best != kept_.end()) {
      const Kept kept = *best;
      kept_.erase(best);
      kept_bytes_ -= kept.bytes;
      const std::size_t used = whole_pages(bytes);
      if (whole_pages(kept.bytes) > used)
        munmap(static_cast<char*>(kept.mapping) + used, whole_pages(kept.bytes) - used);
      // Outside the lock would let another thread in sooner, but takes are rare (a job's start).
      std::memset(kept.mapping, 0, bytes);
      return kept.mapping;
    }
  }
  void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  madvise(p, bytes, MADV_HUGEPAGE);  // advice: refused, the buffer keeps 4 kB pages
  return p;
}

void MappingPool::give(void* mapping, std::size_t bytes, Clock::time_point now) {
  if (bytes > limits_.max_bytes) return unmap(mapping, bytes);
  std::lock_guard lock(mutex_);
  release_idle_locked(now);
  kept_.push_back({mapping, bytes, now});
  kept_bytes_ += bytes;
  while (kept_bytes_ > limits_.max_bytes) {
    unmap(kept_.front().mapping, kept_.front().bytes);
    kept_bytes_ -= kept_.front().bytes;
    kept_.erase(kept_.begin());
  }
}

void MappingPool::release_idle(Clock::time_point now) {
  std::lock_guard lock(mutex_);
  release_idle_locked(now);
}

void MappingPool::renew(Clock::time_point now) {
  std::lock_guard lock(mutex_);
  for (Kept& k : kept_) k.since = now;
}

void MappingPool::release_idle_locked(Clock::time_point now) {
  std::erase_if(kept_, [&](const Kept& k) {
    if (now - k.since < limits_.idle) return false;
    unmap(k.mapping, k.bytes);
    kept_bytes_ -= k.bytes;
    return true;
  });
}

std::size_t MappingPool::kept_bytes() const {
  std::lock_guard lock(mutex_);
  return kept_bytes_;
}

}  // namespace tessera

#endif
