#include "coordinator/workers/worker_link.h"

#include <spdlog/spdlog.h>

#include "common/protocol/handshake.h"
#include "common/protocol/messages.h"
#include "common/protocol/sha256.h"

namespace tessera {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {
// Before authentication only small frames are accepted, so a stranger cannot make the
// coordinator buffer megabytes; results of trusted workers may be larger.
constexpr FrameLimits kHandshakeLimits{.max_body = 64u << 10, .max_header = 32u << 10};
constexpr FrameLimits kWorkerLimits{.max_body = 16u << 20, .max_header = 64u << 10};
}  // namespace

WorkerLink::WorkerLink(FrameStream stream, const WorkerAuth& auth, Scheduler& scheduler,
                       ConnectionTiming timing, std::shared_ptr<WorkerPortState> port,
                       StrangerSlots::Place stranger, std::chrono::milliseconds handshake_deadline)
    : deadline_(stream.get_executor()),
      connection_(std::make_shared<FrameConnection>(std::move(stream), kHandshakeLimits, timing)),
      auth_(auth),
      scheduler_(scheduler),
      port_(std::move(port)),
      handshake_deadline_(handshake_deadline),
      stranger_(std::move(stranger)) {}

void WorkerLink::start() {
  auto self = shared_from_this();
  connection_->set_traffic(port_->traffic);
  connection_->start([self](Frame f) { self->on_frame(std::move(f)); },
                     [self](const std::string& reason) {
                       if (self->stage_ == Stage::Ready) {
                         spdlog::info("worker {}: {}", self->id_, reason);
                         self->scheduler_.remove_worker(self->id_);
                       } else if (reason.starts_with("TLS handshake failed")) {
                         // A plaintext client or a worker that does not trust our certificate.
                         if (auto suppressed = self->port_->reject_log.allow())
                           spdlog::warn("worker port: {}: {}{}", self->connection_->peer(), reason,
                                        suppressed_note(*suppressed));
                       }
                       self->leave_unauthenticated();
                       self->deadline_.cancel();
                       self->connection_.reset();  // breaks the cycle through the handlers
                     });
  // Heartbeats keep a connection open, so only this deadline keeps a stranger from holding a
  // socket forever.
  deadline_.expires_after(handshake_deadline_);
  deadline_.async_wait([self](boost::system::error_code ec) {
    if (ec || self->stage_ == Stage::Ready || !self->connection_) return;
    if (auto suppressed = self->port_->timeout_log.allow())
      spdlog::warn("worker port: {} did not authenticate within {} ms; closed{}",
                   self->connection_->peer(), self->handshake_deadline_.count(),
                   suppressed_note(*suppressed));
    self->connection_->close("handshake deadline passed");
  });
}

void WorkerLink::leave_unauthenticated() { stranger_.reset(); }

void WorkerLink::on_frame(Frame frame) {
  try {
    if (stage_ == Stage::Hello && frame.type == MessageType::Hello)
      return on_hello(decode<HelloMessage>(frame));
    if (stage_ == Stage::Auth && frame.type == MessageType::Auth)
      return on_auth(decode<AuthMessage>(frame));
    if (stage_ == Stage::Ready && frame.type == MessageType::Result)
      return scheduler_.on_result(id_, take_result(std::move(frame)));
    if (stage_ == Stage::Ready && frame.type == MessageType::JobFailed)
      return scheduler_.on_job_failed(id_, decode<JobFailedMessage>(frame));
    connection_->close(std::string("unexpected ") + to_string(frame.type) + " frame");
  } catch (const std::exception& e) {  // a malformed or forged message (ProtocolError)
    if (stage_ == Stage::Ready)
      spdlog::warn("worker {} ({}): {}", id_, connection_->peer(), e.what());
    else if (auto suppressed = port_->reject_log.allow())  // a stranger may repeat it at will
      spdlog::warn("worker port: {}: {}{}", connection_->peer(), e.what(),
                   suppressed_note(*suppressed));
    connection_->close(e.what());
  }
}

void WorkerLink::on_hello(const HelloMessage& hello) {
  if (hello.version != kProtocolVersion)
    return reject("protocol version " + std::to_string(hello.version) + " is not " +
                  std::to_string(kProtocolVersion));
  hello_.name = hello.name;
  hello_.threads = hello.threads;
  hello_.address = connection_->peer();
  if (hello_.threads < 1 || hello_.threads > 1024) return reject("threads must be 1..1024");
  worker_nonce_ = hello.nonce;
  if (worker_nonce_.size() < 16 || worker_nonce_.size() > 128) return reject("bad nonce");
  hello_.cached.insert(hello.cached.begin(), hello.cached.end());
  nonce_ = make_nonce();
  stage_ = Stage::Auth;
  challenge_sent_ = std::chrono::steady_clock::now();
  connection_->send(encode(ChallengeMessage{.version = kProtocolVersion,
                                            .nonce = nonce_,
                                            .auth = auth_.insecure ? "none" : "hmac-sha256"}));
}

void WorkerLink::on_auth(const AuthMessage& auth) {
  if (!auth_.insecure) {
    const std::string expected = worker_proof(auth_.secret, nonce_, worker_nonce_);
    if (!constant_time_equal(auth.proof, expected))
      return reject("authentication failed: wrong shared secret");
  }
  hello_.handshake_round_trip =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - challenge_sent_).count();
  connection_->set_limits(kWorkerLimits);
  stage_ = Stage::Ready;
  leave_unauthenticated();
  deadline_.cancel();
  id_ = scheduler_.add_worker(hello_, connection_);
  connection_->send(encode(WelcomeMessage{
      .worker = id_,
      .proof = auth_.insecure ? "" : coordinator_proof(auth_.secret, nonce_, worker_nonce_),
      .heartbeat_ms = connection_->timing().heartbeat.count(),
      .silence_ms = connection_->timing().silence.count()}));
  scheduler_.fill_slots();
}

void WorkerLink::reject(const std::string& reason) {
  if (auto suppressed = port_->reject_log.allow())
    spdlog::warn("refused worker from {}: {}{}", connection_->peer(), reason,
                 suppressed_note(*suppressed));
  connection_->send(encode(RejectMessage{.reason = reason}));
  connection_->close_after_flush(reason);
}

WorkerListener::WorkerListener(asio::io_context& io, const tcp::endpoint& endpoint, WorkerAuth auth,
                               Scheduler& scheduler, ConnectionTiming timing,
                               WorkerPortLimits limits, std::shared_ptr<asio::ssl::context> tls)
    : acceptor_(io, endpoint),
      retry_(io),
      auth_(std::move(auth)),
      scheduler_(scheduler),
      timing_(timing),
      limits_(limits),
      tls_(std::move(tls)) {
  accept();
}

void WorkerListener::accept() {
  acceptor_.async_accept([this](boost::system::error_code ec, tcp::socket socket) {
    if (!acceptor_.is_open() || ec == asio::error::operation_aborted) return;
    if (ec) {  // EMFILE and the like: the next accept would fail at once too
      const auto delay = backoff_.next();
      if (auto suppressed = accept_log_.allow())
        spdlog::warn("worker port: accept failed: {}; retrying in {} ms{}", ec.message(),
                     delay.count(), suppressed_note(*suppressed));
      retry_.expires_after(delay);
      retry_.async_wait([this](boost::system::error_code wait_ec) {
        if (!wait_ec) accept();
      });
      return;
    }
    backoff_.reset();
    boost::system::error_code peer_ec;
    const tcp::endpoint peer = socket.remote_endpoint(peer_ec);
    std::string refusal = "the peer is gone";
    std::optional<StrangerSlots::Place> place;
    if (!peer_ec) place = state_->strangers.enter(peer.address(), refusal);
    if (!place) {
      if (auto suppressed = state_->refused_log.allow())
        spdlog::warn("worker port: refused a connection: {}{}", refusal,
                     suppressed_note(*suppressed));
      boost::system::error_code ignored;
      socket.close(ignored);
    } else {
      std::make_shared<WorkerLink>(
          tls_ ? FrameStream(std::move(socket), tls_) : FrameStream(std::move(socket)), auth_,
          scheduler_, timing_, state_, std::move(*place), limits_.handshake_deadline)
          ->start();
    }
    accept();
  });
}

}  // namespace tessera
