// The protocol's messages, one struct per frame type (docs/PROTOCOL.md, "Messages"), and their
// codec: encode() turns a message into a frame, decode<M>() a frame into a message. This is the
// only place that reads or writes a frame's header by key; everything above it handles structs.
//
// decode<M>() throws ProtocolError for a frame of another type, a missing or mistyped field, or
// a value past a limit of the protocol; the connection that sent it is then closed. Checks that
// depend on what the receiver knows (is this unit one I sent you? is this render time
// plausible?) belong to the receiver: coordinator/scheduler/result_check.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/progressive/unit_pixels.h"
#include "common/protocol/bundle.h"
#include "common/protocol/frame.h"
#include "common/protocol/job_spec.h"
#include "common/stats/render_stats.h"

namespace tessera {

// A hello announces at most this many cached bundles; more are ignored.
constexpr std::size_t kMaxCachedHashes = 64;
// A worker's name and a job_failed's error are kept and shown: a hostile one could be megabytes.
constexpr std::size_t kMaxWorkerName = 128;
constexpr std::size_t kMaxWorkerError = 1000;

// A hello or challenge of another version is decoded no further than its version: the rest of
// its layout is that version's, and the receiver refuses it with a reason instead of closing the
// connection over a field it does not know.
struct HelloMessage {
  static constexpr MessageType kType = MessageType::Hello;
  int version = 0;
  std::string name;  // cut to kMaxWorkerName
  int threads = 0;
  std::string nonce;                // Nw, hex
  std::vector<std::string> cached;  // bundle hashes the worker holds, at most kMaxCachedHashes
};

struct ChallengeMessage {
  static constexpr MessageType kType = MessageType::Challenge;
  int version = 0;
  std::string nonce;  // Nc, hex
  std::string auth;   // "hmac-sha256" or "none"
};

struct AuthMessage {
  static constexpr MessageType kType = MessageType::Auth;
  std::string proof;  // empty when the coordinator offered "none"
};

struct WelcomeMessage {
  static constexpr MessageType kType = MessageType::Welcome;
  std::int64_t worker = 0;  // the worker's id at the coordinator
  std::string proof;        // empty under "none"
  // The coordinator's heartbeat and silence (--heartbeat-ms, --silence-ms), which the worker
  // adopts so that both ends agree; 0 when not given (the worker keeps its own, 2 s and 10 s).
  std::int64_t heartbeat_ms = 0, silence_ms = 0;
};

struct RejectMessage {
  static constexpr MessageType kType = MessageType::Reject;
  std::string reason;
};

struct HeartbeatMessage {
  static constexpr MessageType kType = MessageType::Heartbeat;
};

// Decoding checks the bundle against `hash`: a worker caches bundles by it.
struct JobMessage {
  static constexpr MessageType kType = MessageType::Job;
  std::int64_t job = 0;
  std::string hash;  // the bundle's content_hash()
  JobSpec spec;
  std::optional<Bundle> bundle;  // absent when the worker already holds `hash`
};

struct UnitMessage {
  static constexpr MessageType kType = MessageType::Unit;
  std::int64_t job = 0;
  std::int64_t unit = 0;  // index in the job's plan
  int pass = 0;
  UnitPixels pixels;
};

// Statistics decode only as non-negative integer counts and a numeric `seconds`; the pixels only
// as whole RGB triples, as many as the header's `count` when it has one.
struct ResultMessage {
  static constexpr MessageType kType = MessageType::Result;
  std::int64_t job = 0;
  std::int64_t unit = 0;
  RenderStats stats;
  FloatValues values;  // 3 per pixel, in the order of the unit's pixels
};

struct JobFailedMessage {
  static constexpr MessageType kType = MessageType::JobFailed;
  std::int64_t job = 0;
  std::string error;  // cut to kMaxWorkerError
  // The job came without its bundle and the worker no longer holds it.
  bool missing_bundle = false;
};

struct CancelMessage {
  static constexpr MessageType kType = MessageType::Cancel;
  std::int64_t job = 0;
};

Frame encode(const HelloMessage& message);
Frame encode(const ChallengeMessage& message);
Frame encode(const AuthMessage& message);
Frame encode(const WelcomeMessage& message);
Frame encode(const RejectMessage& message);
Frame encode(const HeartbeatMessage& message);
Frame encode(const JobMessage& message);
Frame encode(const UnitMessage& message);
Frame encode(const ResultMessage& message);
Frame encode(const JobFailedMessage& message);
Frame encode(const CancelMessage& message);

// A unit's whole frame (encode_frame(encode(message))'s bytes), written directly rather than
// through a JSON object: the coordinator sends one for every unit it schedules.
std::string encode_unit_frame(const UnitMessage& message);

template <typename Message>
Message decode(const Frame& frame);
template <>
HelloMessage decode(const Frame& frame);
template <>
ChallengeMessage decode(const Frame& frame);
template <>
AuthMessage decode(const Frame& frame);
template <>
WelcomeMessage decode(const Frame& frame);
template <>
RejectMessage decode(const Frame& frame);
template <>
HeartbeatMessage decode(const Frame& frame);
template <>
JobMessage decode(const Frame& frame);
template <>
UnitMessage decode(const Frame& frame);
template <>
ResultMessage decode(const Frame& frame);
template <>
JobFailedMessage decode(const Frame& frame);
// decode<ResultMessage> that takes the frame's payload over: its values are the result's,
// neither copied nor moved (the coordinator decodes every result it merges so).
ResultMessage take_result(Frame&& frame);
template <>
CancelMessage decode(const Frame& frame);

}  // namespace tessera
