// The coordinator's side of one worker connection: the versioned handshake and the
// challenge/response (common/protocol/handshake.h), then results and failures handed to the
// scheduler. A peer that breaks the protocol is dropped; it never takes the coordinator down.
// Until it has authenticated a peer is a stranger: it counts against a cap and must finish the
// handshake before a deadline (WorkerPortLimits, docs/SECURITY.md).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <boost/asio/steady_timer.hpp>

#include "common/protocol/connection.h"
#include "common/protocol/messages.h"
#include "coordinator/net/backoff.h"
#include "coordinator/net/log_limiter.h"
#include "coordinator/net/stranger_slots.h"
#include "coordinator/scheduler/scheduler.h"

namespace tessera {

struct WorkerAuth {
  std::string secret;     // shared with the workers
  bool insecure = false;  // --insecure: no proofs at all
};

// What a peer that has not authenticated may hold of the coordinator.
struct WorkerPortLimits {
  // Sockets between accept and welcome; beyond it new connections are closed at once.
  std::size_t max_unauthenticated = 64;
  // Of those, from one address (an IPv6 /64): one host cannot take every place.
  std::size_t max_unauthenticated_per_address = 8;
  // From accept to authenticated; heartbeats do not extend it.
  std::chrono::milliseconds handshake_deadline{5000};
};

// Shared by the listener and its links (a link may outlive the listener at shutdown).
struct WorkerPortState {
  explicit WorkerPortState(const WorkerPortLimits& limits)
      : strangers(limits.max_unauthenticated, limits.max_unauthenticated_per_address) {}
  StrangerSlots strangers;
  // One line a second per kind of event a stranger can repeat at will: connections refused
  // at the cap, handshakes past the deadline, handshakes rejected (wrong secret, version...).
  LogLimiter refused_log, timeout_log, reject_log;
  FrameTraffic traffic;  // every link's frames, for metrics
};

class WorkerLink : public std::enable_shared_from_this<WorkerLink> {
 public:
  WorkerLink(FrameStream stream, const WorkerAuth& auth, Scheduler& scheduler,
             ConnectionTiming timing, std::shared_ptr<WorkerPortState> port,
             StrangerSlots::Place stranger, std::chrono::milliseconds handshake_deadline);
  void start();

 private:
  enum class Stage { Hello, Auth, Ready };
  void on_frame(Frame frame);
  void on_hello(const HelloMessage& hello);
  void on_auth(const AuthMessage& auth);
  void reject(const std::string& reason);
  // Stops counting this link as a stranger (authenticated or closed); idempotent.
  void leave_unauthenticated();

  boost::asio::steady_timer deadline_;  // before connection_: built from the socket's executor
  std::shared_ptr<FrameConnection> connection_;
  const WorkerAuth& auth_;
  Scheduler& scheduler_;
  std::shared_ptr<WorkerPortState> port_;
  std::chrono::milliseconds handshake_deadline_;
  std::optional<StrangerSlots::Place> stranger_;  // until authenticated or closed
  Stage stage_ = Stage::Hello;
  std::string nonce_, worker_nonce_;
  std::chrono::steady_clock::time_point challenge_sent_;  // times the handshake's round trip
  WorkerHello hello_;
  std::int64_t id_ = 0;
};

// Accepts worker connections on the worker port; with `tls` (--tls-cert) every connection
// is TLS, the handshake bounded by the handshake deadline.
class WorkerListener {
 public:
  WorkerListener(boost::asio::io_context& io, const boost::asio::ip::tcp::endpoint& endpoint,
                 WorkerAuth auth, Scheduler& scheduler, ConnectionTiming timing,
                 WorkerPortLimits limits = {},
                 std::shared_ptr<boost::asio::ssl::context> tls = nullptr);
  unsigned short port() const { return acceptor_.local_endpoint().port(); }
  // Told of every frame of every link accepted from now on.
  void observe_traffic(FrameTraffic traffic) { state_->traffic = std::move(traffic); }

 private:
  void accept();
  boost::asio::ip::tcp::acceptor acceptor_;
  boost::asio::steady_timer retry_;
  Backoff backoff_;
  LogLimiter accept_log_;
  WorkerAuth auth_;
  Scheduler& scheduler_;
  ConnectionTiming timing_;
  WorkerPortLimits limits_;
  std::shared_ptr<boost::asio::ssl::context> tls_;
  std::shared_ptr<WorkerPortState> state_ = std::make_shared<WorkerPortState>(limits_);
};

}  // namespace tessera
