// The heavy half of requests off the io thread: scene loading, preparation, the cost probe and
// image encoding run on a few threads with a bounded queue. Each task's result is posted back
// to the io thread, the only thread that touches the job store and the scheduler, so those
// need no locks and HTTP, heartbeats and dispatch never wait for a scene.
#pragma once

#include <atomic>
#include <functional>
#include <utility>  // before Asio: Boost 1.74 uses std::exchange without it

#include <boost/asio/io_context.hpp>
#include <boost/asio/thread_pool.hpp>

namespace tessera {

class IntakePool {
 public:
  // Work on the pool returns what to do next on the io thread.
  using Task = std::function<std::function<void()>()>;

  IntakePool(boost::asio::io_context& io, int threads, int max_pending);
  // Waits for the tasks running (each bounded by its request's budget).
  ~IntakePool();

  // Queues `work`; false, running nothing, when max_pending tasks are queued or running.
  // `always` skips the bound, for work the service owes (a finished job's final encoding).
  // `work` must not throw (a throw is logged and its continuation is lost).
  bool submit(Task work, bool always = false);
  int pending() const { return pending_; }

 private:
  boost::asio::io_context& io_;
  boost::asio::thread_pool pool_;
  std::atomic<int> pending_{0};
  int max_pending_;
};

}  // namespace tessera
