#pragma once
// The receiving end of a telemetry stream: one message in, at most one
// position out, with the same StreamPredictor as the sender.
//
// A fresh full always puts the decoder in step. A full that carries the
// statistics on does only when the decoder holds them (in step, and its
// check equals the full's): otherwise its position is still good, but no
// delta can be decoded until a fresh full (DecodedMessage::in_step, so the
// receiver can ask for one). A delta is decoded
// only when it is the next message (sequence = last + 1 mod 16); the same
// sequence again is a resent duplicate (ignored); anything else means a
// message was missed, and deltas are refused until the next full (the
// sender sends one at least every full_every deltas).
//
// Not thread-safe: one stream, one thread.

#include <string>
#include <string_view>

#include "telemetry/stream_history.h"
#include "telemetry/stream_predictor.h"
#include "telemetry/telemetry_message.h"

namespace acomms::telemetry {

enum class DecodeOutcome {
  kPosition,   // a new position
  kDuplicate,  // the last message again (a resend): nothing new
  kOutOfStep,  // a delta after a gap or before any full: cannot be decoded
};

struct DecodedMessage {
  DecodeOutcome outcome = DecodeOutcome::kOutOfStep;
  MessageKind kind = MessageKind::kFull;
  uint32_t sequence = 0;
  // A full's time of day, or the last time + tau (see unwrap_time_of_day).
  int64_t time_s = 0;
  GridPosition grid{};
  std::array<double, kAxes> position_m{};
  // After a kPosition: whether the next delta can be decoded (false after a
  // full whose statistics this decoder does not hold).
  bool in_step = false;
};

class TelemetryDecoder {
 public:
  // Throws std::invalid_argument for an invalid config.
  explicit TelemetryDecoder(const TelemetryConfig& config);

  // Reads one message from in, exactly its bits (a duplicate too, so a
  // frame's next message starts in the right place). An out-of-step delta's
  // length cannot be known (its tables are), so after kOutOfStep the rest
  // of the frame is unreadable. Throws dccl::Error or dccl::TruncatedRead
  // for bits that are not a message.
  DecodedMessage decode(dccl::BitReader& in);
  DecodedMessage decode(std::string_view bytes);

  std::string state() const { return serialize(history_, fingerprint_); }
  // False (and out of step until a full) for unusable bytes.
  bool restore(std::string_view state);

 private:
  DecodedMessage decode_delta(dccl::BitReader& in, DecodedMessage message);
  // Applies a full's position to the predictor; false when this decoder
  // does not hold the statistics the full carries on.
  bool apply_full(const FullBody& body);

  TelemetryConfig config_;
  uint64_t fingerprint_;
  RegionGrid region_;
  StreamPredictor predictor_;
  StreamHistory history_;
};

}  // namespace acomms::telemetry
