#include "worker/session/worker_session.h"

#include <spdlog/spdlog.h>
#include <boost/asio/connect.hpp>
#include <boost/asio/post.hpp>

#include "common/protocol/handshake.h"
#include "common/protocol/sha256.h"
#include "common/protocol/unit_message.h"

namespace tessera {

namespace asio = boost::asio;
using asio::ip::tcp;

WorkerSession::WorkerSession(asio::io_context& io, WorkerConfig config)
    : io_(io),
      config_(std::move(config)),
      resolver_(io),
      retry_timer_(io),
      loop_(config_.threads, [this](Frame frame) {
        // From a render thread: hand the result to the connection's thread.
        asio::post(io_, [this, f = std::move(frame)] {
          if (connection_ && stage_ == Stage::Ready) connection_->send(f);
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
  connection_->send(Frame{MessageType::Hello,
                          {{"version", kProtocolVersion},
                           {"name", config_.name},
                           {"threads", config_.threads},
                           {"nonce", nonce_},
                           {"cached", loop_.cached_hashes()}},
                          {}});
}

void WorkerSession::on_frame(const Frame& frame) {
  try {
    switch (frame.type) {
      case MessageType::Challenge:
        if (stage_ == Stage::Hello) return on_challenge(frame);
        break;
      case MessageType::Welcome:
        if (stage_ == Stage::Authenticating) return on_welcome(frame);
        break;
      case MessageType::Reject:
        return fail("refused by the coordinator: " + frame.header.value("reason", std::string()));
      case MessageType::Job:
        if (stage_ == Stage::Ready) return on_job(frame);
        break;
      case MessageType::Unit:
        if (stage_ == Stage::Ready)
          return loop_.add_unit(frame.header.at("job").get<std::int64_t>(),
                                frame.header.at("unit").get<std::int64_t>(),
                                frame.header.at("pass").get<int>(),
                                unit_pixels_from_json(frame.header.at("pixels")));
        break;
      case MessageType::Cancel:
        if (stage_ == Stage::Ready)
          return loop_.cancel_job(frame.header.at("job").get<std::int64_t>());
        break;
      default:
        break;
    }
    connection_->close(std::string("unexpected ") + to_string(frame.type) + " frame");
  } catch (const std::exception& e) {  // malformed header fields
    connection_->close(std::string("bad ") + to_string(frame.type) + " frame: " + e.what());
  }
}

void WorkerSession::on_challenge(const Frame& frame) {
  if (frame.header.at("version").get<int>() != kProtocolVersion)
    return fail("the coordinator speaks protocol version " + frame.header["version"].dump());
  coordinator_nonce_ = frame.header.at("nonce").get<std::string>();
  const std::string auth = frame.header.at("auth").get<std::string>();
  // Whether proofs are exchanged is the worker's own decision, never the coordinator's word:
  // a worker given a secret accepts only a coordinator that proves it knows the secret, so a
  // peer impersonating the coordinator cannot downgrade it with auth "none".
  if (!config_.secret.empty() && auth != "hmac-sha256")
    return fail("the coordinator offers authentication \"" + auth +
                "\", but this worker was given a secret and accepts only hmac-sha256");
  if (config_.secret.empty() && auth != "none")
    return fail("the coordinator requires a shared secret (--secret or TESSERA_SECRET)");
  stage_ = Stage::Authenticating;
  connection_->send(Frame{
      MessageType::Auth,
      {{"proof", authenticated() ? worker_proof(config_.secret, coordinator_nonce_, nonce_) : ""}},
      {}});
}

void WorkerSession::on_welcome(const Frame& frame) {
  if (authenticated()) {
    const std::string expected = coordinator_proof(config_.secret, coordinator_nonce_, nonce_);
    if (!constant_time_equal(frame.header.value("proof", std::string()), expected))
      return fail("the coordinator does not know our secret (its welcome proof is wrong)");
  }
  stage_ = Stage::Ready;
  backoff_ = kFirstBackoff;
  spdlog::info("connected to {}:{} as worker {} with {} threads", config_.host, config_.port,
               frame.header.value("worker", 0), config_.threads);
}

void WorkerSession::on_job(const Frame& frame) {
  const auto job = frame.header.at("job").get<std::int64_t>();
  const auto hash = frame.header.at("hash").get<std::string>();
  const JobSpec spec = job_spec_from_json(frame.header.at("settings"));
  std::optional<Bundle> bundle;
  if (frame.header.contains("bundle")) {
    bundle = decode_bundle(frame.header["bundle"], frame.payload);
    if (content_hash(*bundle) != hash) throw ProtocolError("bundle does not match its hash");
  }
  if (!loop_.open_job(job, spec, hash, std::move(bundle)))
    connection_->send(Frame{MessageType::JobFailed,
                            {{"job", job},
                             {"missing_bundle", true},
                             {"error", "bundle " + hash + " is not cached here"}},
                            {}});
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
