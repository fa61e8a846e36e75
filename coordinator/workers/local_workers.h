// --local-workers N: the coordinator starts N tessera-worker processes on this machine, so one
// command serves a single host. They get the secret through the environment (not argv, which
// `ps` shows) and die with the coordinator (PR_SET_PDEATHSIG), even if it is killed. With `tls`
// they connect with --tls-insecure over loopback: the certificate names the public host, not
// 127.0.0.1, and the secret's mutual proofs already tell them they reached their coordinator.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace tessera {

class LocalWorkers {
 public:
  LocalWorkers(const std::filesystem::path& binary, int count, int threads_each,
               unsigned short port, const std::string& secret, bool tls);
  ~LocalWorkers();
  LocalWorkers(const LocalWorkers&) = delete;
  LocalWorkers& operator=(const LocalWorkers&) = delete;

 private:
  std::vector<pid_t> children_;
};

// tessera-worker next to this executable, or in the build tree's worker/ folder.
std::filesystem::path default_worker_binary();

}  // namespace tessera
