// The accept backoff, the log limiter and the strangers' places of coordinator/net/: exact
// delays and counts.
#include <gtest/gtest.h>

#include "coordinator/net/backoff.h"
#include "coordinator/net/log_limiter.h"
#include "coordinator/net/stranger_slots.h"

namespace tessera {
namespace {

using std::chrono::milliseconds;

TEST(Backoff, DoublesFromTheFirstDelayToTheCapAndStartsOverAfterASuccess) {
  Backoff backoff(milliseconds(50), milliseconds(1000));
  std::vector<long long> delays;
  for (int i = 0; i < 7; ++i) delays.push_back(backoff.next().count());
  EXPECT_EQ(delays, (std::vector<long long>{50, 100, 200, 400, 800, 1000, 1000}));
  backoff.reset();
  EXPECT_EQ(backoff.next(), milliseconds(50));
}

TEST(LogLimiter, OneLineAnIntervalWithTheCountSuppressedMeanwhile) {
  LogLimiter limiter(milliseconds(1000));
  const LogLimiter::Clock::time_point t0{};
  EXPECT_EQ(limiter.allow(t0), 0u);
  for (int i = 1; i <= 5; ++i) EXPECT_FALSE(limiter.allow(t0 + milliseconds(i * 100)));
  EXPECT_EQ(limiter.allow(t0 + milliseconds(1000)), 5u);
  EXPECT_FALSE(limiter.allow(t0 + milliseconds(1999)));
  EXPECT_EQ(limiter.allow(t0 + milliseconds(2000)), 1u);
  EXPECT_EQ(suppressed_note(0), "");
  EXPECT_EQ(suppressed_note(5), " (5 more suppressed)");
}

TEST(StrangerSlots, OneAddressCannotTakeEveryPlace) {
  using boost::asio::ip::make_address;
  StrangerSlots slots(5, 2);
  std::string why;
  std::vector<StrangerSlots::Place> held;
  for (int i = 0; i < 2; ++i) held.push_back(*slots.enter(make_address("10.0.0.1"), why));
  EXPECT_FALSE(slots.enter(make_address("10.0.0.1"), why));
  EXPECT_EQ(why, "2 unauthenticated connections open from 10.0.0.1");
  // An IPv4-mapped IPv6 peer is the same host.
  EXPECT_FALSE(slots.enter(make_address("::ffff:10.0.0.1"), why));
  for (int i = 0; i < 2; ++i) held.push_back(*slots.enter(make_address("10.0.0.2"), why));
  held.push_back(*slots.enter(make_address("2001:db8::1"), why));
  EXPECT_EQ(slots.held(), 5u);
  EXPECT_FALSE(slots.enter(make_address("10.0.0.3"), why));
  EXPECT_EQ(why, "5 unauthenticated connections open");
  // A place given back is free again, for its address and in all.
  held.erase(held.begin());
  EXPECT_EQ(slots.held_by(make_address("10.0.0.1")), 1u);
  EXPECT_TRUE(slots.enter(make_address("10.0.0.3"), why));  // released at once
  EXPECT_EQ(slots.held(), 4u);
  // IPv6 peers count by their /64: a host cannot get around the cap by changing addresses.
  held.erase(held.begin());
  held.push_back(*slots.enter(make_address("2001:db8::2"), why));
  EXPECT_FALSE(slots.enter(make_address("2001:db8::ffff:3"), why));
  EXPECT_EQ(why, "2 unauthenticated connections open from 2001:db8::");
  held.clear();
  EXPECT_EQ(slots.held(), 0u);
  EXPECT_EQ(slots.held_by(make_address("10.0.0.1")), 0u);
}

TEST(StrangerSlots, APlaceMayOutliveItsSlots) {
  std::optional<StrangerSlots::Place> place;
  {
    StrangerSlots slots(1, 1);
    std::string why;
    place = slots.enter(boost::asio::ip::make_address("127.0.0.1"), why);
  }
  place.reset();  // gives its place back to counts it shares, not to the destroyed object
}

}  // namespace
}  // namespace tessera
