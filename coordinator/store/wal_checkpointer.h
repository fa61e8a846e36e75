// Copies the job store's write-ahead log back into the database file on a thread of its own.
// SQLite would otherwise do it inside a commit once the log passes wal_autocheckpoint pages,
// that is on the coordinator's io thread, in the flush of every few ticks: for results of
// large units a quarter of that thread's time, with an fsync of the database file in it
// (docs/SCALING.md). A passive checkpoint runs beside the writer without blocking it.
#pragma once

#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <thread>

#include "coordinator/store/sqlite.h"

namespace tessera {

class WalCheckpointer {
 public:
  // Opens a second connection to `database`, which must exist and be in WAL mode.
  // Throws sqlite::SqliteError.
  explicit WalCheckpointer(const std::filesystem::path& database);
  // Waits for a checkpoint under way, then closes the connection.
  ~WalCheckpointer();
  WalCheckpointer(const WalCheckpointer&) = delete;
  WalCheckpointer& operator=(const WalCheckpointer&) = delete;

  // Asks for a checkpoint soon (after a commit); requests while one runs make one more.
  void request();
  // Checkpoints that completed (for tests).
  long long completed() const;

 private:
  void run();

  sqlite::Connection connection_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool requested_ = false, stopping_ = false, failing_ = false;
  long long completed_ = 0;
  std::thread thread_;
};

}  // namespace tessera
