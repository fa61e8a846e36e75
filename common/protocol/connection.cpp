#include "common/protocol/connection.h"

#include <array>

#include <boost/asio/post.hpp>

#include "common/protocol/messages.h"

namespace tessera {

namespace asio = boost::asio;

namespace {

// A completion condition for async_read that lets each read take all of the frame's bytes still
// missing, as many as the socket holds. Asio's own (transfer_all) caps a read at 64 kB, so a
// 194 kB result took 3.6 reads where one does when it has all arrived (docs/SCALING.md).
auto whole_rest(std::size_t frame_bytes) {
  return [frame_bytes](const boost::system::error_code& ec, std::size_t transferred) {
    return ec ? std::size_t{0} : frame_bytes - transferred;
  };
}

}  // namespace

std::chrono::steady_clock::time_point next_tick(std::chrono::steady_clock::time_point now,
                                                std::chrono::steady_clock::duration period) {
  if (period <= std::chrono::steady_clock::duration::zero()) return now;  // no grid to keep
  const auto since_epoch = now.time_since_epoch();
  return std::chrono::steady_clock::time_point(since_epoch - since_epoch % period + period);
}

FrameConnection::FrameConnection(FrameStream stream, FrameLimits limits, ConnectionTiming timing)
    : stream_(std::move(stream)), timer_(stream_.get_executor()), limits_(limits), timing_(timing) {
  boost::system::error_code ec;
  const auto endpoint = stream_.socket().remote_endpoint(ec);
  peer_ = ec ? "unknown" : endpoint.address().to_string() + ":" + std::to_string(endpoint.port());
  stream_.socket().set_option(asio::ip::tcp::no_delay(true), ec);
}

void FrameConnection::start(FrameHandler on_frame, CloseHandler on_close) {
  on_frame_ = std::move(on_frame);
  on_close_ = std::move(on_close);
  open_ = true;
  last_sent_ = last_received_ = std::chrono::steady_clock::now();
  writing_ = true;  // holds sends in the queue until the stream is ready for them
  tick();           // the silence limit bounds the TLS handshake too
  stream_.handshake([self = shared_from_this()](boost::system::error_code ec) {
    if (!self->open_) return;
    if (ec) return self->close("TLS handshake failed: " + ec.message());
    self->read_head();
    self->write_next();
  });
}

void FrameConnection::send(const Frame& frame) {
  if (!open_) return;
  std::string bytes;
  try {
    bytes = encode_frame(frame, limits_);
  } catch (const ProtocolError& e) {
    close(e.what());
    return;
  }
  send_encoded(frame.type, std::move(bytes));
}

void FrameConnection::send_encoded(MessageType type, std::string bytes) {
  if (!open_) return;
  // A peer that does not read its frames must not make us buffer without bound.
  if (queued_bytes_ + bytes.size() > 2 * limits_.max_body) {
    close("write queue overflow: the peer is not reading");
    return;
  }
  queued_bytes_ += bytes.size();
  if (traffic_) traffic_(true, type, bytes.size());
  queue_.push_back(std::move(bytes));
  if (!writing_) write_next();
}

void FrameConnection::set_timing(ConnectionTiming timing) {
  timing_ = timing;
  if (open_) tick();  // re-arms the timer at the new interval (the pending wait is cancelled)
}

void FrameConnection::close(const std::string& reason) {
  if (!open_) return;
  open_ = false;
  boost::system::error_code ignored;
  stream_.socket().shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  stream_.socket().close(ignored);
  timer_.cancel();
  queue_.clear();
  queued_bytes_ = 0;
  // The handlers usually hold the session that holds us: drop them. The close handler runs
  // later, never inside a caller that is iterating over connections.
  on_frame_ = nullptr;
  if (auto on_close = std::move(on_close_))
    asio::post(stream_.get_executor(),
               [on_close = std::move(on_close), reason] { on_close(reason); });
}

void FrameConnection::close_after_flush(const std::string& reason) {
  if (!writing_) return close(reason);
  closing_reason_ = reason;
}

void FrameConnection::read_head() {
  asio::async_read(stream_, asio::buffer(head_),
                   [self = shared_from_this()](boost::system::error_code ec, std::size_t) {
                     if (!self->open_) return;
                     if (ec)
                       return self->close(ec == asio::error::eof ? "peer closed" : ec.message());
                     try {
                       self->read_rest(decode_frame_head(self->head_, self->limits_));
                     } catch (const ProtocolError& e) {
                       if (self->traffic_) self->traffic_(false, std::nullopt, kFrameHead);
                       self->close(e.what());
                     }
                   });
}

void FrameConnection::read_rest(const FrameHead& head) {
  header_.resize(head.header_bytes);
  payload_ = Payload::to_read(head.payload_bytes);
  // One read into both: the payload lands in the buffer the frame keeps (a result's: the values
  // the coordinator merges and stores).
  const std::array<asio::mutable_buffer, 2> parts{
      asio::buffer(header_), asio::buffer(payload_.data(), head.payload_bytes)};
  asio::async_read(
      stream_, parts, whole_rest(head.header_bytes + head.payload_bytes),
      [self = shared_from_this(), type = head.type](boost::system::error_code ec, std::size_t) {
        if (!self->open_) return;
        if (ec) return self->close(ec.message());
        self->last_received_ = std::chrono::steady_clock::now();
        Frame frame;
        const std::size_t bytes = kFrameHead + self->header_.size() + self->payload_.size();
        try {
          frame = decode_frame_parts(type, self->header_, std::move(self->payload_));
        } catch (const ProtocolError& e) {
          if (self->traffic_) self->traffic_(false, std::nullopt, bytes);
          return self->close(e.what());
        }
        if (self->traffic_) self->traffic_(false, frame.type, bytes);
        self->payload_ = Payload();
        if (frame.type != MessageType::Heartbeat && self->on_frame_)
          self->on_frame_(std::move(frame));
        if (self->open_) self->read_head();
      });
}

void FrameConnection::write_next() {
  if (queue_.empty() || !open_) {
    writing_ = false;
    if (closing_reason_) close(*closing_reason_);
    return;
  }
  writing_ = true;
  asio::async_write(stream_, asio::buffer(queue_.front()),
                    [self = shared_from_this()](boost::system::error_code ec, std::size_t) {
                      if (!self->open_) return;
                      if (ec) return self->close(ec.message());
                      self->queued_bytes_ -= self->queue_.front().size();
                      self->queue_.pop_front();
                      self->last_sent_ = std::chrono::steady_clock::now();
                      self->write_next();
                    });
}

void FrameConnection::tick() {
  const auto now = std::chrono::steady_clock::now();
  if (now - last_received_ > timing_.silence) return close("peer silent for too long");
  if (now - last_sent_ >= timing_.heartbeat && !writing_) send(encode(HeartbeatMessage{}));
  // On a grid shared by all connections rather than half a heartbeat after this one's last
  // tick: each tick of a timer of its own was a timer interrupt, a timerfd re-armed and, on an
  // idle coordinator, a wake-up (3 % of a core with 1,000 idle workers, docs/SCALING.md). A tick
  // still comes at most half a heartbeat after the last, so a heartbeat is sent, and a silent
  // peer closed, no later than before.
  timer_.expires_at(next_tick(now, std::chrono::steady_clock::duration(timing_.heartbeat) / 2));
  timer_.async_wait([self = shared_from_this()](boost::system::error_code ec) {
    if (!ec && self->open_) self->tick();
  });
}

}  // namespace tessera
