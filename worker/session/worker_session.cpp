#include "worker/session/worker_session.h"

#include <spdlog/spdlog.h>
#include <boost/asio/connect.hpp>
#include <boost/asio/post.hpp>

#include "common/protocol/handshake.h"
#include "common/protocol/messages.h"
#include "common/protocol/sha256.h"

namespace tessera {

namespace asio = boost::asio;
using asio::ip::tcp;

WorkerSession::WorkerSession(asio::io_context& io, WorkerConfig config)
    : io_(io),
      config_(std::move(config)),
      resolver_(io),
      retry_timer_(io),
      loop_(config_.threads, [this](RenderLoop::Report report) {
        // From a render thread: hand the report to the connection's thread.
        asio::post(io_, [this, r = std::move(report)] {
          if (connection_ && stage_ == Stage::Ready)
            connection_->send(std::visit([](const auto& message) { return encode(message); }, r));
        });
      }) {}

void WorkerSession::start() { connect(); }

void WorkerSession::connect() {
  stage_ = Stage::Connecting;
  resolver_.async_resolve(
      config_.host, config_.port,
      [this](boost::system::error_code ec, tcp::resolver::results_type r) {
        if (ec) {
          spdlog::warn("cannot resolve {}: {}", config_.host, ec.message());
          return retry_later();
        }
        auto socket = std::make_shared<tcp::socket>(io_);
        asio::async_connect(*socket, r,
                            [this, socket](boost::system::error_code ec2, const tcp::endpoint&) {
                              if (ec2) {
                                // Once per outage, not at every retry.
                                if (backoff_ == kFirstBackoff)
                                  spdlog::warn("cannot connect to {}:{}: {}; retrying",
                                               config_.host, config_.port, ec2.message());
                                return retry_later();
                              }
                              on_connected(std::move(*socket));
                            });
      });
}

void WorkerSession::on_connected(tcp::socket socket) {
  connection_ = std::make_shared<FrameConnection>(
      config_.tls ? FrameStream(std::move(socket), config_.tls, config_.host)
                  : FrameStream(std::move(socket)),
      FrameLimits{}, config_.timing);
  connection_->start([this](Frame f) { on_frame(f); },
                     [this](const std::string& reason) { on_closed(reason); });
  nonce_ = make_nonce();
  stage_ = Stage::Hello;
  connection_->send(encode(HelloMessage{.version = kProtocolVersion,
                                        .name = config_.name,
                                        .threads = config_.threads,
                                        .nonce = nonce_,
                                        .cached = loop_.cached_hashes()}));
}

void WorkerSession::on_frame(const Frame& frame) {
  try {
    switch (frame.type) {
      case MessageType::Challenge:
        if (stage_ == Stage::Hello) return on_challenge(decode<ChallengeMessage>(frame));
        break;
      case MessageType::Welcome:
        if (stage_ == Stage::Authenticating) return on_welcome(decode<WelcomeMessage>(frame));
        break;
      case MessageType::Reject:
        return fail("refused by the coordinator: " + decode<RejectMessage>(frame).reason);
      case MessageType::Job:
        if (stage_ == Stage::Ready) return on_job(decode<JobMessage>(frame));
        break;
      case MessageType::Unit:
        if (stage_ == Stage::Ready) {
          const UnitMessage unit = decode<UnitMessage>(frame);
          return loop_.add_unit(unit.job, unit.unit, unit.pass, unit.pixels);
        }
        break;
      case MessageType::Cancel:
        if (stage_ == Stage::Ready) return loop_.cancel_job(decode<CancelMessage>(frame).job);
        break;
      default:
        break;
    }
    connection_->close(std::string("unexpected ") + to_string(frame.type) + " frame");
  } catch (const std::exception& e) {  // a malformed message (ProtocolError)
    connection_->close(std::string("bad ") + to_string(frame.type) + " frame: " + e.what());
  }
}

void WorkerSession::on_challenge(const ChallengeMessage& challenge) {
  if (challenge.version != kProtocolVersion)
    return fail("the coordinator speaks protocol version " + std::to_string(challenge.version));
  coordinator_nonce_ = challenge.nonce;
  const std::string& auth = challenge.auth;
  // Whether proofs are exchanged is the worker's own decision, never the coordinator's word:
  // a worker given a secret accepts only a coordinator that proves it knows the secret, so a
  // peer impersonating the coordinator cannot downgrade it with auth "none".
  if (!config_.secret.empty() && auth != "hmac-sha256")
    return fail("the coordinator offers authentication \"" + auth +
                "\", but this worker was given a secret and accepts only hmac-sha256");
  if (config_.secret.empty() && auth != "none")
    return fail("the coordinator requires a shared secret (--secret or TESSERA_SECRET)");
  stage_ = Stage::Authenticating;
  connection_->send(encode(AuthMessage{
      .proof = authenticated() ? worker_proof(config_.secret, coordinator_nonce_, nonce_) : ""}));
}

void WorkerSession::on_welcome(const WelcomeMessage& welcome) {
  if (authenticated()) {
    const std::string expected = coordinator_proof(config_.secret, coordinator_nonce_, nonce_);
    if (!constant_time_equal(welcome.proof, expected))
      return fail("the coordinator does not know our secret (its welcome proof is wrong)");
  }
  // Heartbeat and silence as the coordinator's (--heartbeat-ms, --silence-ms): a worker
  // heartbeating every 2 s whatever they were was dropped as silent under a shorter silence.
  if (welcome.heartbeat_ms > 0)
    connection_->set_timing({std::chrono::milliseconds(welcome.heartbeat_ms),
                             std::chrono::milliseconds(welcome.silence_ms)});
  stage_ = Stage::Ready;
  backoff_ = kFirstBackoff;
  spdlog::info("connected to {}:{} as worker {} with {} threads", config_.host, config_.port,
               welcome.worker, config_.threads);
}

void WorkerSession::on_job(JobMessage job) {
  if (!loop_.open_job(job.job, job.spec, job.hash, std::move(job.bundle)))
    connection_->send(encode(JobFailedMessage{.job = job.job,
                                              .error = "bundle " + job.hash + " is not cached here",
                                              .missing_bundle = true}));
}

void WorkerSession::on_closed(const std::string& reason) {
  loop_.clear();
  if (!fatal_.empty()) return;
  spdlog::warn("connection to {}:{} closed: {}", config_.host, config_.port, reason);
  retry_later();
}

void WorkerSession::retry_later() {
  stage_ = Stage::Connecting;
  retry_timer_.expires_after(backoff_);
  backoff_ = std::min(backoff_ * 2, std::chrono::milliseconds(5000));
  retry_timer_.async_wait([this](boost::system::error_code ec) {
    if (!ec) connect();
  });
}

void WorkerSession::fail(const std::string& reason) {
  fatal_ = reason;
  spdlog::error("{}", reason);
  if (connection_) connection_->close(reason);
  io_.stop();
}

}  // namespace tessera
