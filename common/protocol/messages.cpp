#include "common/protocol/messages.h"

#include <bit>
#include <charconv>
#include <iterator>
#include <string_view>
#include <utility>

#include "common/protocol/handshake.h"
#include "common/protocol/json_integer.h"

namespace tessera {

// Pixels travel as the host's float32 bytes; every supported host is little-endian x86-64
// (docs/ARCHITECTURE.md, "Determinism"), and a big-endian build fails here rather than mixing up
// bytes.
static_assert(std::endian::native == std::endian::little);
static_assert(sizeof(float) == 4);

namespace {

using nlohmann::json;

constexpr int kMaxCoordinate = 1 << 16;

// An integer of type T (json_integer.h), else a ProtocolError naming `what`.
template <typename T>
T integer(const json& v, std::string_view what) {
  if (const std::optional<T> value = json_integer<T>(v)) return *value;
  throw ProtocolError(std::string(what) + " is not an integer in range: " + v.dump());
}

template <typename T>
T integer_at(const json& object, const char* key) {
  return integer<T>(object.at(key), key);
}

// The counts of a result's statistics (common/protocol/job_spec.cpp reads them). Read as
// unsigned, a negative count would wrap around to an absurd one: they are refused first.
constexpr const char* kStatCounts[] = {
    "camera_rays",    "shadow_rays", "reflection_rays", "refraction_rays", "shape_tests",
    "triangle_tests", "bvh_nodes",   "pixels",          "samples",         "nan_samples"};

Frame frame_of(MessageType type, json header, Payload payload = {}) {
  return Frame{type, std::move(header), std::move(payload)};
}

// Runs `read` on the frame's header, turning a missing or mistyped field into a ProtocolError
// that names the message.
template <typename Message, typename Read>
Message decoded(const Frame& frame, Read&& read) {
  if (frame.type != Message::kType)
    throw ProtocolError(std::string("expected a ") + to_string(Message::kType) + " frame, not " +
                        to_string(frame.type));
  try {
    Message message;
    read(frame.header, message);
    return message;
  } catch (const json::exception& e) {
    throw ProtocolError(std::string("bad ") + to_string(Message::kType) + ": " + e.what());
  }
}

json pixels_to_json(const UnitPixels& u) {
  return {{"rect", {u.rect.x0, u.rect.y0, u.rect.x1, u.rect.y1}},
          {"step", u.step},
          {"exclude", u.exclude},
          {"pattern", u.pattern == PixelPattern::Anchors ? "anchors" : "centres"}};
}

// Throws ProtocolError for a malformed or absurd pixel set (non-positive step, negative or huge
// rectangle).
UnitPixels pixels_from_json(const json& j) {
  UnitPixels u;
  const auto& r = j.at("rect");
  if (!r.is_array() || r.size() != 4) throw ProtocolError("unit rect needs 4 numbers");
  u.rect = {integer<int>(r[0], "rect"), integer<int>(r[1], "rect"), integer<int>(r[2], "rect"),
            integer<int>(r[3], "rect")};
  u.step = integer_at<int>(j, "step");
  u.exclude = integer_at<int>(j, "exclude");
  const auto pattern = j.at("pattern").get<std::string>();
  if (pattern != "anchors" && pattern != "centres") throw ProtocolError("unit pattern");
  u.pattern = pattern == "anchors" ? PixelPattern::Anchors : PixelPattern::Centres;
  const PixelRect& t = u.rect;
  if (t.x0 < 0 || t.y0 < 0 || t.x1 < t.x0 || t.y1 < t.y0 || t.x1 > kMaxCoordinate ||
      t.y1 > kMaxCoordinate || u.step <= 0 || u.step > kMaxCoordinate || u.exclude < 0)
    throw ProtocolError("unit pixel set out of range");
  return u;
}

RenderStats stats_from_wire(const json& stats) {
  if (!stats.is_object()) throw ProtocolError("statistics are not an object");
  for (const char* key : kStatCounts)
    if (stats.contains(key) && !json_integer<std::uint64_t>(stats[key]))
      throw ProtocolError(std::string("statistic ") + key + " is not a non-negative integer");
  if (stats.contains("seconds") && !stats["seconds"].is_number())
    throw ProtocolError("statistic seconds is not a number");
  return stats_from_json(stats);
}

void check_rgb_payload(std::size_t bytes) {
  constexpr std::size_t kPixelBytes = 3 * sizeof(float);
  if (bytes % kPixelBytes != 0)
    throw ProtocolError("result payload of " + std::to_string(bytes) +
                        " bytes is not whole RGB float32 pixels");
}

}  // namespace

Frame encode(const HelloMessage& m) {
  return frame_of(HelloMessage::kType, {{"version", m.version},
                                        {"name", m.name},
                                        {"threads", m.threads},
                                        {"nonce", m.nonce},
                                        {"cached", m.cached}});
}

template <>
HelloMessage decode(const Frame& frame) {
  return decoded<HelloMessage>(frame, [](const json& h, HelloMessage& m) {
    m.version = integer_at<int>(h, "version");
    if (m.version != kProtocolVersion) return;
    m.name = h.at("name").get<std::string>().substr(0, kMaxWorkerName);
    m.threads = integer_at<int>(h, "threads");
    m.nonce = h.at("nonce").get<std::string>();
    for (const auto& hash : h.value("cached", json::array()))
      if (m.cached.size() < kMaxCachedHashes) m.cached.push_back(hash.get<std::string>());
  });
}

Frame encode(const ChallengeMessage& m) {
  return frame_of(ChallengeMessage::kType,
                  {{"version", m.version}, {"nonce", m.nonce}, {"auth", m.auth}});
}

template <>
ChallengeMessage decode(const Frame& frame) {
  return decoded<ChallengeMessage>(frame, [](const json& h, ChallengeMessage& m) {
    m.version = integer_at<int>(h, "version");
    if (m.version != kProtocolVersion) return;
    m.nonce = h.at("nonce").get<std::string>();
    m.auth = h.at("auth").get<std::string>();
  });
}

Frame encode(const AuthMessage& m) { return frame_of(AuthMessage::kType, {{"proof", m.proof}}); }

template <>
AuthMessage decode(const Frame& frame) {
  return decoded<AuthMessage>(
      frame, [](const json& h, AuthMessage& m) { m.proof = h.value("proof", std::string()); });
}

Frame encode(const WelcomeMessage& m) {
  json header = {{"worker", m.worker}, {"proof", m.proof}};
  if (m.heartbeat_ms > 0) {
    header["heartbeat_ms"] = m.heartbeat_ms;
    header["silence_ms"] = m.silence_ms;
  }
  return frame_of(WelcomeMessage::kType, std::move(header));
}

template <>
WelcomeMessage decode(const Frame& frame) {
  return decoded<WelcomeMessage>(frame, [](const json& h, WelcomeMessage& m) {
    m.worker = h.value("worker", std::int64_t{0});
    m.proof = h.value("proof", std::string());
    if (!h.contains("heartbeat_ms")) return;
    m.heartbeat_ms = integer_at<std::int64_t>(h, "heartbeat_ms");
    m.silence_ms = integer_at<std::int64_t>(h, "silence_ms");
    if (m.heartbeat_ms <= 0 || m.silence_ms <= m.heartbeat_ms)
      throw ProtocolError("heartbeat_ms " + std::to_string(m.heartbeat_ms) + " and silence_ms " +
                          std::to_string(m.silence_ms) +
                          ": both must be positive, the silence longer");
  });
}

Frame encode(const RejectMessage& m) {
  return frame_of(RejectMessage::kType, {{"reason", m.reason}});
}

template <>
RejectMessage decode(const Frame& frame) {
  return decoded<RejectMessage>(
      frame, [](const json& h, RejectMessage& m) { m.reason = h.value("reason", std::string()); });
}

Frame encode(const HeartbeatMessage&) { return frame_of(HeartbeatMessage::kType, json::object()); }

template <>
HeartbeatMessage decode(const Frame& frame) {
  return decoded<HeartbeatMessage>(frame, [](const json&, HeartbeatMessage&) {});
}

Frame encode(const JobMessage& m) {
  Frame frame = frame_of(JobMessage::kType,
                         {{"job", m.job}, {"hash", m.hash}, {"settings", to_json(m.spec)}});
  if (!m.bundle) return frame;
  std::string payload;
  encode_bundle(*m.bundle, frame.header["bundle"], payload);
  frame.payload = std::move(payload);
  return frame;
}

template <>
JobMessage decode(const Frame& frame) {
  return decoded<JobMessage>(frame, [&](const json& h, JobMessage& m) {
    m.job = integer_at<std::int64_t>(h, "job");
    m.hash = h.at("hash").get<std::string>();
    m.spec = job_spec_from_json(h.at("settings"));
    if (!h.contains("bundle")) return;
    m.bundle = decode_bundle(h["bundle"], frame.payload.view());
    if (content_hash(*m.bundle) != m.hash) throw ProtocolError("bundle does not match its hash");
  });
}

Frame encode(const UnitMessage& m) {
  return frame_of(
      UnitMessage::kType,
      {{"job", m.job}, {"unit", m.unit}, {"pass", m.pass}, {"pixels", pixels_to_json(m.pixels)}});
}

std::string encode_unit_frame(const UnitMessage& m) {
  // nlohmann::json's dump of encode(m)'s header: keys sorted, no spaces.
  const UnitPixels& u = m.pixels;
  std::string header;
  header.reserve(128);
  const auto number = [&](const char* before, std::int64_t value) {
    header += before;
    char digits[24];
    header.append(digits, std::to_chars(digits, std::end(digits), value).ptr);
  };
  number(R"({"job":)", m.job);
  number(R"(,"pass":)", m.pass);
  number(R"(,"pixels":{"exclude":)", u.exclude);
  header +=
      u.pattern == PixelPattern::Anchors ? R"(,"pattern":"anchors")" : R"(,"pattern":"centres")";
  number(R"(,"rect":[)", u.rect.x0);
  number(",", u.rect.y0);
  number(",", u.rect.x1);
  number(",", u.rect.y1);
  number(R"(],"step":)", u.step);
  number(R"(},"unit":)", m.unit);
  header += '}';
  return encode_frame_bytes(UnitMessage::kType, header, {});
}

template <>
UnitMessage decode(const Frame& frame) {
  return decoded<UnitMessage>(frame, [](const json& h, UnitMessage& m) {
    m.job = integer_at<std::int64_t>(h, "job");
    m.unit = integer_at<std::int64_t>(h, "unit");
    m.pass = integer_at<int>(h, "pass");
    m.pixels = pixels_from_json(h.at("pixels"));
  });
}

Frame encode(const ResultMessage& m) {
  return frame_of(ResultMessage::kType,
                  {{"job", m.job},
                   {"unit", m.unit},
                   {"count", m.values.size() / 3},
                   {"stats", to_json(m.stats)}},
                  m.values);
}

ResultMessage take_result(Frame&& frame) {
  return decoded<ResultMessage>(frame, [&](const json& h, ResultMessage& m) {
    m.job = integer_at<std::int64_t>(h, "job");
    m.unit = integer_at<std::int64_t>(h, "unit");
    check_rgb_payload(frame.payload.size());
    m.values = std::move(frame.payload).take_floats();
    // Optional, as from the first workers; compared as JSON, so 16.0 counts as 16.
    if (h.contains("count") && h["count"] != m.values.size() / 3)
      throw ProtocolError("result of " + h["count"].dump() + " pixels with a payload of " +
                          std::to_string(m.values.size() / 3));
    m.stats = stats_from_wire(h.at("stats"));
  });
}

template <>
ResultMessage decode(const Frame& frame) {
  return take_result(Frame(frame));
}

Frame encode(const JobFailedMessage& m) {
  json header = {{"job", m.job}, {"error", m.error}};
  if (m.missing_bundle) header["missing_bundle"] = true;
  return frame_of(JobFailedMessage::kType, std::move(header));
}

template <>
JobFailedMessage decode(const Frame& frame) {
  return decoded<JobFailedMessage>(frame, [](const json& h, JobFailedMessage& m) {
    m.job = integer_at<std::int64_t>(h, "job");
    m.error = h.value("error", std::string()).substr(0, kMaxWorkerError);
    m.missing_bundle = h.value("missing_bundle", false);
  });
}

Frame encode(const CancelMessage& m) { return frame_of(CancelMessage::kType, {{"job", m.job}}); }

template <>
CancelMessage decode(const Frame& frame) {
  return decoded<CancelMessage>(
      frame, [](const json& h, CancelMessage& m) { m.job = integer_at<std::int64_t>(h, "job"); });
}

}  // namespace tessera
