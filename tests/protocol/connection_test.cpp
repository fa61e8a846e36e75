#include "common/protocol/connection.h"

#include <gtest/gtest.h>

namespace tessera {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;

// A connected pair of sockets on loopback.
std::pair<tcp::socket, tcp::socket> socket_pair(asio::io_context& io) {
  tcp::acceptor acceptor(io, tcp::endpoint(asio::ip::address_v4::loopback(), 0));
  tcp::socket client(io);
  client.connect(acceptor.local_endpoint());
  tcp::socket server = acceptor.accept();
  return {std::move(client), std::move(server)};
}

TEST(FrameConnection, DeliversFramesAndHidesHeartbeats) {
  asio::io_context io;
  auto [a, b] = socket_pair(io);
  const ConnectionTiming fast{std::chrono::milliseconds(20), std::chrono::milliseconds(2000)};
  auto left = std::make_shared<FrameConnection>(std::move(a), FrameLimits{}, fast);
  auto right = std::make_shared<FrameConnection>(std::move(b), FrameLimits{}, fast);
  std::vector<Frame> received;
  left->start([](Frame) {}, [](const std::string&) {});
  right->start(
      [&](Frame f) {
        received.push_back(std::move(f));
        if (received.size() == 2) {
          left->close("done");
          right->close("done");
        }
      },
      [](const std::string&) {});
  left->send(Frame{MessageType::Unit, {{"unit", 1}}, "abc"});
  asio::steady_timer later(io, std::chrono::milliseconds(100));  // heartbeats flow meanwhile
  later.async_wait([&](auto) { left->send(Frame{MessageType::Cancel, {{"job", 2}}, ""}); });
  io.run_for(std::chrono::seconds(5));
  ASSERT_EQ(received.size(), 2u);
  EXPECT_EQ(received[0].type, MessageType::Unit);
  EXPECT_EQ(received[0].payload, "abc");
  EXPECT_EQ(received[1].header["job"], 2);
}

TEST(FrameConnection, ClosesOnOversizedFrameAndOnSilence) {
  asio::io_context io;
  auto [a, b] = socket_pair(io);
  auto receiver = std::make_shared<FrameConnection>(
      std::move(b), FrameLimits{.max_body = 100, .max_header = 50},
      ConnectionTiming{std::chrono::milliseconds(20), std::chrono::milliseconds(5000)});
  std::string reason;
  receiver->start([](Frame) { ADD_FAILURE() << "no frame expected"; },
                  [&](const std::string& r) { reason = r; });
  const std::string big = encode_frame(Frame{MessageType::Result, {}, std::string(1000, 'x')});
  asio::write(a, asio::buffer(big));
  io.run_for(std::chrono::seconds(5));
  EXPECT_NE(reason.find("exceeds the limit"), std::string::npos) << reason;

  asio::io_context io2;
  auto [c, d] = socket_pair(io2);
  auto quiet = std::make_shared<FrameConnection>(
      std::move(d), FrameLimits{},
      ConnectionTiming{std::chrono::milliseconds(20), std::chrono::milliseconds(100)});
  reason.clear();
  quiet->start([](Frame) {}, [&](const std::string& r) { reason = r; });
  io2.run_for(std::chrono::seconds(5));  // `c` never sends: not even heartbeats
  EXPECT_NE(reason.find("silent"), std::string::npos) << reason;
}

TEST(FrameConnection, TicksOnAGridSharedByAllConnections) {
  using namespace std::chrono;
  const steady_clock::duration period = milliseconds(1000);
  const steady_clock::time_point grid(hours(100));  // a multiple of the period
  // Connections that tick at different instants within a period all tick next at its end, so one
  // timer expiry serves them all...
  for (const steady_clock::duration since : std::initializer_list<steady_clock::duration>{
           nanoseconds(0), nanoseconds(1), milliseconds(250),
           milliseconds(999) + microseconds(999)})
    EXPECT_EQ(next_tick(grid + since, period), grid + period) << since.count();
  // ...and a tick is never more than a period after the last, so heartbeats and the silence limit
  // are checked as often as before.
  EXPECT_EQ(next_tick(grid + period, period), grid + 2 * period);
  EXPECT_EQ(next_tick(grid + period, milliseconds(20)), grid + period + milliseconds(20));
  // A worker takes the heartbeat from the coordinator's welcome, where 1 ms is valid: half of it
  // is a grid still; a period of nothing (no grid) must not divide by zero.
  EXPECT_EQ(next_tick(grid + nanoseconds(1), microseconds(500)), grid + microseconds(500));
  EXPECT_EQ(next_tick(grid + nanoseconds(3), steady_clock::duration::zero()),
            grid + nanoseconds(3));
}

// Writes `pieces` to `socket` one after the other, 30 ms apart.
void write_pieces(tcp::socket& socket, std::shared_ptr<std::vector<std::string>> pieces,
                  std::size_t i = 0) {
  if (i == pieces->size()) return;
  asio::async_write(socket, asio::buffer((*pieces)[i]), [&socket, pieces, i](auto ec, auto) {
    ASSERT_FALSE(ec) << ec.message();
    auto gap =
        std::make_shared<asio::steady_timer>(socket.get_executor(), std::chrono::milliseconds(30));
    gap->async_wait([&socket, pieces, i, gap](auto) { write_pieces(socket, pieces, i + 1); });
  });
}

TEST(FrameConnection, ReadsFramesThatArriveTogetherOrInPieces) {
  asio::io_context io;
  auto [a, b] = socket_pair(io);
  auto receiver =
      std::make_shared<FrameConnection>(std::move(b), FrameLimits{}, ConnectionTiming{});
  std::vector<Frame> received;
  receiver->start(
      [&](Frame f) {
        received.push_back(std::move(f));
        if (received.size() == 4) receiver->close("done");
      },
      [](const std::string&) {});
  // Large frames (a result's size, read in several pieces) and small ones, arriving alone,
  // cut through a head or a payload, or with the start of the next frame.
  const std::string large(200000, 'x'), small = "abc";
  const std::string frames[] = {encode_frame(Frame{MessageType::Result, {{"n", 0}}, large}),
                                encode_frame(Frame{MessageType::Unit, {{"n", 1}}, small}),
                                encode_frame(Frame{MessageType::Result, {{"n", 2}}, large}),
                                encode_frame(Frame{MessageType::Unit, {{"n", 3}}, small})};
  auto pieces = std::make_shared<std::vector<std::string>>(
      std::vector<std::string>{frames[0], frames[1], frames[2].substr(0, 5),  // a head cut in two
                               frames[2].substr(5, 100000),  // a payload cut in two
                               frames[2].substr(100005) + frames[3].substr(0, frames[3].size() - 1),
                               frames[3].substr(frames[3].size() - 1)});
  write_pieces(a, pieces);
  io.run_for(std::chrono::seconds(5));
  ASSERT_EQ(received.size(), 4u);
  for (int n = 0; n < 4; ++n) {
    EXPECT_EQ(received[n].header["n"], n);
    EXPECT_EQ(received[n].payload, n % 2 == 0 ? large : small);
  }
}

}  // namespace
}  // namespace tessera
