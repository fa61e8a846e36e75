// The coordinator's side of one worker connection: the versioned handshake and the
// challenge/response (common/protocol/handshake.h), then results and failures handed to the
// scheduler. A peer that breaks the protocol is dropped; it never takes the coordinator down.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "common/protocol/connection.h"
#include "coordinator/scheduler/scheduler.h"

namespace tessera {

struct WorkerAuth {
  std::string secret;     // shared with the workers
  bool insecure = false;  // --insecure: no proofs at all
};

class WorkerLink : public std::enable_shared_from_this<WorkerLink> {
 public:
  WorkerLink(boost::asio::ip::tcp::socket socket, const WorkerAuth& auth, Scheduler& scheduler,
             ConnectionTiming timing);
  void start();

 private:
  enum class Stage { Hello, Auth, Ready };
  void on_frame(const Frame& frame);
  void on_hello(const Frame& frame);
  void on_auth(const Frame& frame);
  void reject(const std::string& reason);

  std::shared_ptr<FrameConnection> connection_;
  const WorkerAuth& auth_;
  Scheduler& scheduler_;
  Stage stage_ = Stage::Hello;
  std::string nonce_, worker_nonce_;
  std::chrono::steady_clock::time_point challenge_sent_;  // times the handshake's round trip
  WorkerHello hello_;
  std::int64_t id_ = 0;
};

// Accepts worker connections on the worker port.
class WorkerListener {
 public:
  WorkerListener(boost::asio::io_context& io, const boost::asio::ip::tcp::endpoint& endpoint,
                 WorkerAuth auth, Scheduler& scheduler, ConnectionTiming timing);
  unsigned short port() const { return acceptor_.local_endpoint().port(); }

 private:
  void accept();
  boost::asio::ip::tcp::acceptor acceptor_;
  WorkerAuth auth_;
  Scheduler& scheduler_;
  ConnectionTiming timing_;
};

}  // namespace tessera
