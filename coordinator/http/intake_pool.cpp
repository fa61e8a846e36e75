#include "coordinator/http/intake_pool.h"

#include <pthread.h>
#include <sys/resource.h>
#include <unistd.h>

#include <spdlog/spdlog.h>
#include <boost/asio/post.hpp>

namespace tessera {

namespace {

// Intake threads yield the cores to the io thread: a hostile scene may keep them busy until
// its deadline, but must not delay heartbeats or status answers. Named for top -H and the
// capacity benchmark.
void prepare_this_thread() {
  thread_local bool prepared = false;
  if (prepared) return;
  prepared = true;
  setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), 10);
  pthread_setname_np(pthread_self(), "tessera-intake");
}

}  // namespace

IntakePool::IntakePool(boost::asio::io_context& io, int threads, int max_pending)
    : io_(io), pool_(static_cast<std::size_t>(threads)), max_pending_(max_pending) {}

IntakePool::~IntakePool() {
  pool_.stop();
  pool_.join();
}

bool IntakePool::submit(Task work, bool always) {
  if (++pending_ > max_pending_ && !always) {
    --pending_;
    return false;
  }
  boost::asio::post(pool_, [this, work = std::move(work)] {
    prepare_this_thread();
    std::function<void()> then;
    try {
      then = work();
    } catch (const std::exception& e) {
      spdlog::error("intake task: {}", e.what());
    }
    --pending_;
    if (then) boost::asio::post(io_, std::move(then));
  });
  return true;
}

}  // namespace tessera
