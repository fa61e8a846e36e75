#include "coordinator/store/flush_thread.h"

#include <pthread.h>

namespace tessera {

FlushThread::FlushThread(std::function<void()> flush)
    : flush_(std::move(flush)), thread_([this] { run(); }) {}

FlushThread::~FlushThread() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void FlushThread::request() {
  {
    std::lock_guard lock(mutex_);
    requested_ = true;
  }
  wake_.notify_one();
}

long long FlushThread::runs() const {
  std::lock_guard lock(mutex_);
  return runs_;
}

void FlushThread::run() {
  pthread_setname_np(pthread_self(), "tessera-store");  // for top -H and the capacity benchmark
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return requested_ || stopping_; });
    if (stopping_) return;
    requested_ = false;
    lock.unlock();
    flush_();  // reports its own failures
    lock.lock();
    ++runs_;
  }
}

}  // namespace tessera
