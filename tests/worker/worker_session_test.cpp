// The worker's session against a fake coordinator on loopback: after the welcome the worker
// keeps the heartbeat and silence the coordinator announced (--heartbeat-ms, --silence-ms),
// not its own 2 s and 10 s. Counted from the frames the fake coordinator receives, so the
// assertion is a count, not a time.
#include "worker/session/worker_session.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "common/protocol/handshake.h"

namespace tessera {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;
using namespace std::chrono_literals;

TEST(WorkerSession, HeartbeatsAndFallsSilentAtTheCoordinatorsTiming) {
  asio::io_context io;
  tcp::acceptor acceptor(io, tcp::endpoint(asio::ip::address_v4::loopback(), 0));
  WorkerConfig config;
  config.port = std::to_string(acceptor.local_endpoint().port());
  config.name = "heartbeat-test";
  WorkerSession session(io, config);

  // The fake coordinator welcomes the worker with a 10 ms heartbeat and a 2 s silence, then
  // sends nothing at all (its own heartbeat is a minute): the worker heartbeats about 200
  // times and then closes for the silence. With its own 2 s and 10 s it would send 4 or 5.
  int heartbeats = 0;
  bool closed = false;
  std::shared_ptr<FrameConnection> coordinator;
  acceptor.async_accept([&](boost::system::error_code ec, tcp::socket socket) {
    ASSERT_FALSE(ec) << ec.message();
    coordinator = std::make_shared<FrameConnection>(FrameStream(std::move(socket)), FrameLimits{},
                                                    ConnectionTiming{60s, 120s});
    coordinator->set_traffic([&](bool sent, std::optional<MessageType> type, std::size_t) {
      if (!sent && type == MessageType::Heartbeat) ++heartbeats;
    });
    coordinator->start(
        [&](Frame frame) {
          if (frame.type == MessageType::Hello)
            coordinator->send(encode(ChallengeMessage{
                .version = kProtocolVersion, .nonce = make_nonce(), .auth = "none"}));
          else if (frame.type == MessageType::Auth)
            coordinator->send(encode(
                WelcomeMessage{.worker = 1, .proof = "", .heartbeat_ms = 10, .silence_ms = 2000}));
        },
        [&](const std::string&) {
          closed = true;
          io.stop();
        });
  });
  session.start();
  io.run_for(30s);  // a bound in case the worker never closes, not a timing under test
  EXPECT_TRUE(closed) << "the worker did not close the silent connection";
  EXPECT_GE(heartbeats, 20);
  EXPECT_TRUE(session.fatal_error().empty()) << session.fatal_error();
}

}  // namespace
}  // namespace tessera
