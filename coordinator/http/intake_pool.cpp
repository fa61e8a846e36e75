#include "coordinator/http/intake_pool.h"

#include <spdlog/spdlog.h>
#include <boost/asio/post.hpp>

namespace tessera {

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
