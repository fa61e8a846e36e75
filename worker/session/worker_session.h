// The worker's side of the wire protocol: connect, hello, prove the secret, check the
// coordinator's proof, then turn job/unit/cancel messages into render-loop calls and send what
// the render loop reports. Reconnects with a growing delay when the connection drops; stops for
// good when the coordinator refuses it (wrong secret or version) or cannot prove it knows the
// secret, since retrying cannot help.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "common/protocol/connection.h"
#include "common/protocol/messages.h"
#include "worker/render_loop/render_loop.h"

namespace tessera {

struct WorkerConfig {
  std::string host = "127.0.0.1";
  std::string port = "7701";
  std::string secret;  // empty: only an --insecure coordinator accepts us
  std::string name;
  int threads = 1;
  std::shared_ptr<boost::asio::ssl::context> tls;  // null: plain TCP
  ConnectionTiming timing;
};

class WorkerSession {
 public:
  WorkerSession(boost::asio::io_context& io, WorkerConfig config);
  void start();
  // Set when the coordinator refused us; the process exits with an error.
  const std::string& fatal_error() const { return fatal_; }

 private:
  enum class Stage { Connecting, Hello, Authenticating, Ready };
  void connect();
  void on_connected(boost::asio::ip::tcp::socket socket);
  void on_frame(const Frame& frame);
  void on_challenge(const ChallengeMessage& challenge);
  void on_welcome(const WelcomeMessage& welcome);
  void on_job(JobMessage job);
  void on_closed(const std::string& reason);
  void retry_later();
  void fail(const std::string& reason);
  // Proofs are exchanged exactly when this worker was given a secret.
  bool authenticated() const { return !config_.secret.empty(); }

  boost::asio::io_context& io_;
  WorkerConfig config_;
  boost::asio::ip::tcp::resolver resolver_;
  boost::asio::steady_timer retry_timer_;
  std::shared_ptr<FrameConnection> connection_;
  RenderLoop loop_;
  Stage stage_ = Stage::Connecting;
  std::string nonce_, coordinator_nonce_;
  static constexpr std::chrono::milliseconds kFirstBackoff{250};
  std::chrono::milliseconds backoff_ = kFirstBackoff;
  std::string fatal_;
};

}  // namespace tessera
