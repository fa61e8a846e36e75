#include "coordinator/store/wal_checkpointer.h"

#include <spdlog/spdlog.h>

namespace tessera {

WalCheckpointer::WalCheckpointer(const std::filesystem::path& database)
    : connection_(database.string()) {
  // A connection learns that the database is in WAL mode when it first reads it; until then
  // a checkpoint does nothing.
  connection_.query_int("PRAGMA schema_version");
  thread_ = std::thread([this] { run(); });
}

WalCheckpointer::~WalCheckpointer() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void WalCheckpointer::request() {
  {
    std::lock_guard lock(mutex_);
    requested_ = true;
  }
  wake_.notify_one();
}

long long WalCheckpointer::completed() const {
  std::lock_guard lock(mutex_);
  return completed_;
}

void WalCheckpointer::run() {
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return requested_ || stopping_; });
    if (stopping_) return;
    requested_ = false;
    lock.unlock();
    bool done = false;
    try {
      connection_.checkpoint_passive();
      done = true;
    } catch (const sqlite::SqliteError& e) {
      // Not fatal: the writer's own automatic checkpoint, kept as a backstop, bounds the log.
      // Said once per run of failures, not at every flush.
      if (!failing_) spdlog::warn("job store: background checkpoint failed: {}", e.what());
    }
    lock.lock();
    failing_ = !done;
    if (done) ++completed_;
  }
}

}  // namespace tessera
