#include "coordinator/workers/local_workers.h"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

#include <spdlog/spdlog.h>

namespace tessera {

std::filesystem::path default_worker_binary() {
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
  for (const auto& candidate : {self.parent_path() / "tessera-worker",
                                self.parent_path().parent_path() / "worker" / "tessera-worker"})
    if (std::filesystem::exists(candidate)) return candidate;
  return self.parent_path() / "tessera-worker";
}

LocalWorkers::LocalWorkers(const std::filesystem::path& binary, int count, int threads_each,
                           unsigned short port, const std::string& secret, bool tls) {
  if (count > 0 && !std::filesystem::exists(binary))
    throw std::runtime_error("no worker binary at " + binary.string() + " (use --worker-binary)");
  const pid_t parent = getpid();
  for (int i = 0; i < count; ++i) {
    const std::string address = "127.0.0.1:" + std::to_string(port);
    const std::string threads = std::to_string(threads_each);
    const std::string name = "local-" + std::to_string(i + 1);
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
      prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (getppid() != parent) _exit(0);  // the coordinator died before prctl took effect
      // Nothing of the coordinator's but stdin, stdout and stderr: an inherited listening
      // socket would keep the coordinator's ports taken after it died, until the worker exits,
      // and a coordinator restarted at once could not bind them.
      close_range(3, ~0U, 0);
      if (!secret.empty()) setenv("TESSERA_SECRET", secret.c_str(), 1);
      // The last argument ends the list early without TLS.
      execl(binary.c_str(), binary.c_str(), "--coordinator", address.c_str(), "--threads",
            threads.c_str(), "--name", name.c_str(), tls ? "--tls-insecure" : nullptr,
            static_cast<char*>(nullptr));
      _exit(127);
    }
    children_.push_back(pid);
  }
  if (count > 0) spdlog::info("started {} local workers with {} threads each", count, threads_each);
}

LocalWorkers::~LocalWorkers() {
  for (pid_t pid : children_) kill(pid, SIGTERM);
  for (pid_t pid : children_) waitpid(pid, nullptr, 0);
}

}  // namespace tessera
