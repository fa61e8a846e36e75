// One framed TCP connection on a single-threaded io_context, shared by the coordinator's worker
// sessions and the worker's session: the TLS handshake when the stream is TLS, length-prefixed
// reads, a bounded write queue, heartbeats when idle, and a close when the peer is silent,
// misbehaves or the queue overflows. Every
// member runs on the io_context's thread; the close handler runs exactly once, posted.
#pragma once

#include <chrono>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>  // before Asio: Boost 1.74 uses std::exchange without it

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/write.hpp>

#include "common/protocol/frame.h"
#include "common/protocol/tls.h"

namespace tessera {

struct ConnectionTiming {
  std::chrono::milliseconds heartbeat{2000};  // send a heartbeat after this long without sending
  std::chrono::milliseconds silence{10000};   // close after this long without receiving
};

// Told of every frame read (its type, or none when it does not decode) and of every frame
// queued to send, heartbeats included, with its bytes on the wire before TLS: for metrics.
using FrameTraffic =
    std::function<void(bool sent, std::optional<MessageType> type, std::size_t bytes)>;

// When a connection ticks next (checks the silence limit, sends a heartbeat if due): the first
// multiple of `period` on the steady clock after `now`, so at most `period` away. Every
// connection of a process with the same timing ticks at the same instants: a coordinator with
// 1,000 workers wakes once a period for all of them, not 1,000 times (docs/SCALING.md, io10).
std::chrono::steady_clock::time_point next_tick(std::chrono::steady_clock::time_point now,
                                                std::chrono::steady_clock::duration period);

class FrameConnection : public std::enable_shared_from_this<FrameConnection> {
 public:
  using FrameHandler = std::function<void(Frame)>;
  using CloseHandler = std::function<void(const std::string& reason)>;

  FrameConnection(FrameStream stream, FrameLimits limits, ConnectionTiming timing);
  // Runs the TLS handshake first when the stream is TLS; frames sent meanwhile wait for it, and
  // a failed handshake closes with "TLS handshake failed: ...".
  void start(FrameHandler on_frame, CloseHandler on_close);
  void send(const Frame& frame);
  // A frame already encoded (encode_frame_bytes), of `type`: for metrics.
  void send_encoded(MessageType type, std::string bytes);
  void close(const std::string& reason);
  // Closes once every queued frame is written (a reject the peer should read first).
  void close_after_flush(const std::string& reason);
  // Raises the frame limits once the peer is trusted (after authentication).
  void set_limits(FrameLimits limits) { limits_ = limits; }
  void set_traffic(FrameTraffic traffic) { traffic_ = std::move(traffic); }
  // The worker adopts the coordinator's timing once welcomed; takes effect at once.
  void set_timing(ConnectionTiming timing);
  const ConnectionTiming& timing() const { return timing_; }
  bool open() const { return open_; }
  const std::string& peer() const { return peer_; }

 private:
  void read_head();
  void read_rest(const FrameHead& head);
  void write_next();
  void tick();

  FrameStream stream_;
  boost::asio::steady_timer timer_;
  FrameLimits limits_;
  ConnectionTiming timing_;
  std::string peer_;
  FrameHandler on_frame_;
  CloseHandler on_close_;
  FrameTraffic traffic_;
  bool open_ = false;
  std::uint8_t head_[kFrameHead] = {};
  std::string header_;
  Payload payload_;
  std::deque<std::string> queue_;
  std::size_t queued_bytes_ = 0;
  bool writing_ = false;
  std::optional<std::string> closing_reason_;
  std::chrono::steady_clock::time_point last_sent_, last_received_;
};

}  // namespace tessera
