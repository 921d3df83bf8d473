#pragma once
// A telemetry message as the link carries it: the DCCL types of
// api/proto/acomms/telemetry/messages.proto (PositionFull, PositionDelta).
//
// The library's own message (telemetry_message.h) starts with a 1-bit kind
// and a 4-bit sequence: enough offline, too short on a link where a message
// may wait for resends for half an hour. On the link the kind is the DCCL
// type, the sequence is 12 bits (kWireSequenceModulus), and the body bits
// travel unchanged as the repeated bool `body`. The receiver rebuilds the
// library's bytes from a wire message whose order it has already checked,
// with the 4-bit sequence the library expects (the wire sequence mod 16).
//
// Thread-safe: values and pure functions; to_dccl() only asks `codec` for a
// new message, which a loaded Codec allows on any thread (codec.h).

#include <google/protobuf/message.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "telemetry/telemetry_encoder.h"

namespace acomms::dccl {
class Codec;
}

namespace acomms::telemetry {

inline constexpr std::string_view kFullType = "acomms.telemetry.PositionFull";
inline constexpr std::string_view kDeltaType = "acomms.telemetry.PositionDelta";
inline constexpr std::string_view kFeedbackType = "acomms.telemetry.PositionFeedback";
inline constexpr int kFullId = 110;
inline constexpr int kDeltaId = 111;
inline constexpr int kFeedbackId = 112;
inline constexpr uint32_t kWireSequenceModulus = 4096;
// The largest bodies messages.proto allows (max_repeat).
inline constexpr size_t kMaxFullBodyBits = 127;
inline constexpr size_t kMaxDeltaBodyBits = 127;

struct WireMessage {
  MessageKind kind = MessageKind::kFull;
  int32_t src = 0;
  int32_t dest = 0;
  uint32_t sequence = 0;  // < kWireSequenceModulus
  std::vector<bool> body;
};

// PositionFeedback: the receiver `src` asks the sender `dest` for a fresh
// full (stream_receiver.h, Feedback).
struct WireFeedback {
  int32_t src = 0;
  int32_t dest = 0;
  std::optional<uint32_t> heard;  // < kWireSequenceModulus
};

// Whether a DCCL type name is one of the telemetry types (the stream's and
// the feedback).
bool is_telemetry_type(std::string_view type);

// The body bits of a library message (its header stripped).
std::vector<bool> body_of(const EncodedMessage& message);

// The library's bytes for a wire message: header (kind, sequence mod 16),
// then the body, zero-padded to a byte.
std::string library_bytes(const WireMessage& message);

// A new message of the wire type in `codec` (which must have loaded
// messages.proto). Throws std::invalid_argument when a field is out of the
// type's bounds (body too long, sequence or ids out of range).
std::unique_ptr<google::protobuf::Message> to_dccl(const dccl::Codec& codec, const WireMessage& message);

// Reads a decoded DCCL message of a telemetry type. Throws
// std::invalid_argument for another type or a field out of range.
WireMessage from_dccl(const google::protobuf::Message& message);

// The same for feedback (kFeedbackType).
std::unique_ptr<google::protobuf::Message> to_dccl(const dccl::Codec& codec, const WireFeedback& feedback);
WireFeedback feedback_from_dccl(const google::protobuf::Message& message);

// (a - b) mod 4096, as a number in [-2048, 2048): > 0 when a is newer.
int32_t sequence_distance(uint32_t a, uint32_t b);

}  // namespace acomms::telemetry
