// The job store's own thread: runs the store's flush when asked, so that writing a tick's
// results (SQLite's inserts, the log's frames and the checkpoints that copy them into the
// database file, with their fsyncs) stays off the coordinator's io thread, where it took
// up to half of that thread's time with large units (docs/SCALING.md).
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace tessera {

class FlushThread {
 public:
  explicit FlushThread(std::function<void()> flush);
  // Finishes a flush under way (one asked for but not begun is dropped), then joins.
  ~FlushThread();
  FlushThread(const FlushThread&) = delete;
  FlushThread& operator=(const FlushThread&) = delete;

  // Asks for a flush soon; requests while one runs make one more, not one each.
  void request();
  // Flushes run to the end since start (for tests).
  long long runs() const;

 private:
  void run();

  std::function<void()> flush_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool requested_ = false, stopping_ = false;
  long long runs_ = 0;
  std::thread thread_;  // last: it starts once everything above exists
};

}  // namespace tessera
