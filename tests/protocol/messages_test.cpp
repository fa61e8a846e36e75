// The typed messages: each encodes to the header docs/PROTOCOL.md describes (so that old and new
// coordinators and workers interoperate), decodes back to itself, and refuses what the protocol
// refuses.
#include "common/protocol/messages.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include "common/protocol/handshake.h"

namespace tessera {
namespace {

using nlohmann::json;

Bundle small_bundle() {
  return Bundle{.main = "a.sdl", .format = "sdl", .files = {{"a.sdl", "x"}}};
}

ResultMessage small_result() {
  RenderStats stats;
  stats.pixels = 2;
  stats.samples = 2;
  stats.camera_rays = 2;
  stats.seconds = 0.25;
  return ResultMessage{
      .job = 3, .unit = 5, .stats = stats, .values = {0.1f, -0.0f, 1e-38f, 3.4e38f, 0.33f, 7}};
}

TEST(Messages, HeadersAreTheDocumentedOnes) {
  EXPECT_EQ(
      encode(HelloMessage{.version = 2, .name = "w", .threads = 4, .nonce = "n", .cached = {"h1"}})
          .header,
      json({{"version", 2}, {"name", "w"}, {"threads", 4}, {"nonce", "n"}, {"cached", {"h1"}}}));
  EXPECT_EQ(encode(ChallengeMessage{.version = 2, .nonce = "c", .auth = "none"}).header,
            json({{"version", 2}, {"nonce", "c"}, {"auth", "none"}}));
  EXPECT_EQ(encode(AuthMessage{.proof = "p"}).header, json({{"proof", "p"}}));
  EXPECT_EQ(encode(WelcomeMessage{.worker = 7, .proof = "q"}).header,
            json({{"worker", 7}, {"proof", "q"}}));
  EXPECT_EQ(encode(RejectMessage{.reason = "r"}).header, json({{"reason", "r"}}));
  EXPECT_EQ(encode(HeartbeatMessage{}).header, json::object());
  EXPECT_EQ(encode(CancelMessage{.job = 9}).header, json({{"job", 9}}));
  EXPECT_EQ(encode(JobFailedMessage{.job = 9, .error = "e"}).header,
            json({{"job", 9}, {"error", "e"}}));
  EXPECT_EQ(encode(JobFailedMessage{.job = 9, .error = "e", .missing_bundle = true}).header,
            json({{"job", 9}, {"error", "e"}, {"missing_bundle", true}}));
  const Frame unit = encode(UnitMessage{
      .job = 1, .unit = 2, .pass = 3, .pixels = {.rect = {0, 4, 8, 12}, .step = 2, .exclude = 4}});
  EXPECT_EQ(
      unit.header,
      json({{"job", 1},
            {"unit", 2},
            {"pass", 3},
            {"pixels",
             {{"rect", {0, 4, 8, 12}}, {"step", 2}, {"exclude", 4}, {"pattern", "anchors"}}}}));
  const Frame result = encode(small_result());
  EXPECT_EQ(result.type, MessageType::Result);
  EXPECT_EQ(result.header["count"], 2);
  EXPECT_EQ(result.header["stats"], to_json(small_result().stats));
  EXPECT_EQ(result.payload.size(), 6 * sizeof(float));
}

TEST(Messages, AJobCarriesItsBundleOnlyWhenGiven) {
  JobSpec spec;
  spec.settings.width = 17;
  spec.overrides.max_depth = 3;
  const Frame without = encode(JobMessage{.job = 4, .hash = "h", .spec = spec, .bundle = {}});
  EXPECT_EQ(without.header, json({{"job", 4}, {"hash", "h"}, {"settings", to_json(spec)}}));
  EXPECT_TRUE(without.payload.empty());
  const JobMessage back = decode<JobMessage>(without);
  EXPECT_EQ(back.job, 4);
  EXPECT_EQ(back.hash, "h");
  EXPECT_EQ(to_json(back.spec), to_json(spec));
  EXPECT_FALSE(back.bundle);

  const Bundle bundle = small_bundle();
  const Frame with =
      encode(JobMessage{.job = 4, .hash = content_hash(bundle), .spec = spec, .bundle = bundle});
  EXPECT_TRUE(with.header.contains("bundle"));
  EXPECT_EQ(decode<JobMessage>(with).bundle, bundle);
}

TEST(Messages, ABundleThatDoesNotMatchItsHashIsRefused) {
  const Frame job =
      encode(JobMessage{.job = 4, .hash = "not its hash", .spec = {}, .bundle = small_bundle()});
  EXPECT_THROW(decode<JobMessage>(job), ProtocolError);
}

TEST(Messages, DecodeReturnsWhatWasEncoded) {
  const HelloMessage hello = decode<HelloMessage>(encode(HelloMessage{
      .version = kProtocolVersion, .name = "w", .threads = 4, .nonce = "n", .cached = {"a", "b"}}));
  EXPECT_EQ(hello.name, "w");
  EXPECT_EQ(hello.threads, 4);
  EXPECT_EQ(hello.nonce, "n");
  EXPECT_EQ(hello.cached, (std::vector<std::string>{"a", "b"}));
  const ChallengeMessage challenge = decode<ChallengeMessage>(
      encode(ChallengeMessage{.version = kProtocolVersion, .nonce = "c", .auth = "hmac-sha256"}));
  EXPECT_EQ(challenge.nonce, "c");
  EXPECT_EQ(challenge.auth, "hmac-sha256");
  EXPECT_EQ(decode<AuthMessage>(encode(AuthMessage{.proof = "p"})).proof, "p");
  const WelcomeMessage welcome =
      decode<WelcomeMessage>(encode(WelcomeMessage{.worker = 7, .proof = "q"}));
  EXPECT_EQ(welcome.worker, 7);
  EXPECT_EQ(welcome.proof, "q");
  EXPECT_EQ(welcome.heartbeat_ms, 0) << "not given: the worker keeps its own timing";
  const WelcomeMessage timed = decode<WelcomeMessage>(
      encode(WelcomeMessage{.worker = 7, .proof = "", .heartbeat_ms = 500, .silence_ms = 3000}));
  EXPECT_EQ(timed.heartbeat_ms, 500);
  EXPECT_EQ(timed.silence_ms, 3000);
  EXPECT_EQ(decode<RejectMessage>(encode(RejectMessage{.reason = "r"})).reason, "r");
  EXPECT_EQ(decode<CancelMessage>(encode(CancelMessage{.job = 9})).job, 9);
  const JobFailedMessage failed = decode<JobFailedMessage>(
      encode(JobFailedMessage{.job = 9, .error = "e", .missing_bundle = true}));
  EXPECT_EQ(failed.job, 9);
  EXPECT_EQ(failed.error, "e");
  EXPECT_TRUE(failed.missing_bundle);
  const UnitPixels anchors{
      .rect = {8, 16, 40, 48}, .step = 4, .exclude = 8, .pattern = PixelPattern::Anchors};
  const UnitPixels centres{.rect = {0, 0, 5, 3}, .step = 4, .pattern = PixelPattern::Centres};
  for (const UnitPixels& pixels : {anchors, centres}) {
    const UnitMessage unit =
        decode<UnitMessage>(encode(UnitMessage{.job = 1, .unit = 2, .pass = 3, .pixels = pixels}));
    EXPECT_EQ(unit.job, 1);
    EXPECT_EQ(unit.unit, 2);
    EXPECT_EQ(unit.pass, 3);
    EXPECT_EQ(unit.pixels, pixels);
  }
}

TEST(Messages, AUnitFrameWrittenDirectlyIsTheEncodedOne) {
  const UnitPixels anchors{
      .rect = {8, 16, 40, 48}, .step = 4, .exclude = 8, .pattern = PixelPattern::Anchors};
  const UnitPixels centres{
      .rect = {0, 0, 65536, 3}, .step = 65536, .pattern = PixelPattern::Centres};
  for (const UnitPixels& pixels : {anchors, centres}) {
    const UnitMessage unit{.job = std::numeric_limits<std::int64_t>::max(),
                           .unit = 1234567,
                           .pass = 255,
                           .pixels = pixels};
    EXPECT_EQ(encode_unit_frame(unit), encode_frame(encode(unit)));
  }
}

TEST(Messages, ResultPixelsTravelBitExactly) {
  const ResultMessage sent = small_result();
  const ResultMessage back = decode<ResultMessage>(encode(sent));
  EXPECT_EQ(back.job, 3);
  EXPECT_EQ(back.unit, 5);
  EXPECT_EQ(to_json(back.stats), to_json(sent.stats));
  ASSERT_EQ(back.values.size(), sent.values.size());
  EXPECT_EQ(std::memcmp(back.values.data(), sent.values.data(), sent.values.size() * sizeof(float)),
            0);
}

// The coordinator's results: the values are the payload a connection read into, not a copy,
// and the same as decode's.
TEST(Messages, ATakenResultHoldsThePayloadReadIntoAsItsValues) {
  const ResultMessage sent = small_result();
  Frame frame = encode(sent);
  Payload read = Payload::to_read(frame.payload.size());
  frame.payload.view().copy(read.data(), read.size());
  const char* read_into = read.data();
  frame.payload = std::move(read);
  const ResultMessage decoded = decode<ResultMessage>(frame);
  const ResultMessage taken = take_result(std::move(frame));
  EXPECT_EQ(reinterpret_cast<const char*>(taken.values.data()), read_into);
  EXPECT_EQ(taken.values, sent.values);
  EXPECT_EQ(decoded.values, sent.values);
  EXPECT_EQ(taken.unit, sent.unit);
}

TEST(Messages, AFrameOfAnotherTypeIsRefused) {
  EXPECT_THROW(decode<UnitMessage>(encode(CancelMessage{.job = 1})), ProtocolError);
  // A heartbeat the worker cannot keep: none, or not within the silence.
  for (const auto& [heartbeat, silence] : {std::pair{0, 100}, {500, 500}, {500, 100}}) {
    Frame welcome = encode(WelcomeMessage{.worker = 1, .proof = ""});
    welcome.header["heartbeat_ms"] = heartbeat;
    welcome.header["silence_ms"] = silence;
    EXPECT_THROW(decode<WelcomeMessage>(welcome), ProtocolError) << heartbeat << " " << silence;
  }
}

TEST(Messages, MissingOrMistypedFieldsAreProtocolErrors) {
  Frame cancel = encode(CancelMessage{.job = 1});
  cancel.header["job"] = "one";
  EXPECT_THROW(decode<CancelMessage>(cancel), ProtocolError);
  cancel.header.erase("job");
  EXPECT_THROW(decode<CancelMessage>(cancel), ProtocolError);
  Frame failed = encode(JobFailedMessage{.job = 1, .error = "e"});
  failed.header["missing_bundle"] = "yes";
  EXPECT_THROW(decode<JobFailedMessage>(failed), ProtocolError);
}

// A float or an integer too wide for the field is refused, not cast: 1e37 converted to an
// integer is undefined behaviour (a worker's result with it was found by fuzz_worker_frames).
TEST(Messages, IntegerFieldsMustBeIntegersInRange) {
  for (const json& job :
       {json(1.1e37), json(2.5), json(std::numeric_limits<std::uint64_t>::max())}) {
    Frame f = encode(small_result());
    f.header["job"] = job;
    EXPECT_THROW(decode<ResultMessage>(f), ProtocolError) << job;
  }
  Frame unit =
      encode(UnitMessage{.job = 1, .unit = 2, .pass = 0, .pixels = {.rect = {0, 0, 4, 4}}});
  unit.header["pass"] = std::int64_t{1} << 40;  // an int64 that would be cut to an int's bits
  EXPECT_THROW(decode<UnitMessage>(unit), ProtocolError);
  Frame f = encode(small_result());
  f.header["job"] = std::numeric_limits<std::int64_t>::max();
  EXPECT_EQ(decode<ResultMessage>(f).job, std::numeric_limits<std::int64_t>::max());
}

TEST(Messages, AbsurdPixelSetsAreRefused) {
  const Frame good =
      encode(UnitMessage{.job = 1, .unit = 2, .pass = 0, .pixels = {.rect = {0, 0, 4, 4}}});
  Frame f = good;
  f.header["pixels"]["step"] = 0;
  EXPECT_THROW(decode<UnitMessage>(f), ProtocolError);
  f = good;
  f.header["pixels"]["rect"] = {0, 0, 1 << 30, 4};
  EXPECT_THROW(decode<UnitMessage>(f), ProtocolError);
  f.header["pixels"]["rect"] = "everything";
  EXPECT_THROW(decode<UnitMessage>(f), ProtocolError);
  f = good;
  f.header["pixels"]["pattern"] = "spiral";
  EXPECT_THROW(decode<UnitMessage>(f), ProtocolError);
}

TEST(Messages, AResultMustHoldWholePixelsAndItsCount) {
  Frame f = encode(small_result());
  const std::string whole(f.payload.view());  // a copy: the payload is replaced below
  f.payload = whole.substr(0, whole.size() - 1);
  EXPECT_THROW(decode<ResultMessage>(f), ProtocolError);
  f.payload = whole.substr(0, whole.size() - 4);  // whole floats, not pixels
  EXPECT_THROW(decode<ResultMessage>(f), ProtocolError);
  f = encode(small_result());
  f.header["count"] = 3;
  EXPECT_THROW(decode<ResultMessage>(f), ProtocolError);
  f.header["count"] = 2.0;  // a number equal to the count, as before typed messages
  EXPECT_NO_THROW(decode<ResultMessage>(f));
  f.header.erase("count");  // optional
  EXPECT_EQ(decode<ResultMessage>(f).values.size(), 6u);
}

TEST(Messages, StatisticsMustBeNonNegativeIntegersAndANumberOfSeconds) {
  for (const auto& [key, value] : std::vector<std::pair<std::string, json>>{
           {"samples", -1}, {"camera_rays", 1.5}, {"pixels", "2"}, {"seconds", "soon"}}) {
    Frame f = encode(small_result());
    f.header["stats"][key] = value;
    EXPECT_THROW(decode<ResultMessage>(f), ProtocolError) << key << " = " << value;
  }
  Frame f = encode(small_result());
  f.header["stats"] = json::array();
  EXPECT_THROW(decode<ResultMessage>(f), ProtocolError);
  f.header["stats"] = {{"samples", std::numeric_limits<std::uint64_t>::max()}};
  EXPECT_EQ(decode<ResultMessage>(f).stats.samples, std::numeric_limits<std::uint64_t>::max());
}

TEST(Messages, AHelloOfAnotherVersionIsReadNoFurtherThanItsVersion) {
  Frame f;
  f.type = MessageType::Hello;
  f.header = {{"version", kProtocolVersion + 1}, {"greeting", "a layout of its own"}};
  EXPECT_EQ(decode<HelloMessage>(f).version, kProtocolVersion + 1);
  f.header["version"] = kProtocolVersion;
  EXPECT_THROW(decode<HelloMessage>(f), ProtocolError);
  f.type = MessageType::Challenge;
  f.header["version"] = kProtocolVersion + 1;
  EXPECT_EQ(decode<ChallengeMessage>(f).version, kProtocolVersion + 1);
}

TEST(Messages, WhatAWorkerSaysIsCut) {
  HelloMessage hello{.version = kProtocolVersion,
                     .name = std::string(500, 'n'),
                     .threads = 1,
                     .nonce = "n",
                     .cached = std::vector<std::string>(100, "h")};
  const HelloMessage back = decode<HelloMessage>(encode(hello));
  EXPECT_EQ(back.name.size(), kMaxWorkerName);
  EXPECT_EQ(back.cached.size(), kMaxCachedHashes);
  const JobFailedMessage failed =
      decode<JobFailedMessage>(encode(JobFailedMessage{.job = 1, .error = std::string(5000, 'e')}));
  EXPECT_EQ(failed.error.size(), kMaxWorkerError);
}

}  // namespace
}  // namespace tessera
