#pragma once
// The sending end of a telemetry stream: one evenly spaced sample in, one
// message out (Schneider 2013, section 3.2-3.3).
//
// A sample goes as a full transmission (position and time coded uniformly
// over the region) when the receiver cannot be assumed to predict it: the
// first sample, the first after a gap (Sample::new_segment, or a time that is
// not the last + tau), the first after full_every deltas, the first after
// request_full() (a delta was given up on, the receiver restarted), and any
// sample whose innovation falls outside [innovation_min, innovation_max).
// Otherwise it goes as a delta: the innovation against the shared
// prediction, arithmetic coded.
//
// A full keeps what the models learned (telemetry_message.h, the full's
// fresh/continues/check bits): it is fresh (both ends forget their
// statistics) only for the stream's first message after the encoder lost
// its state and after request_fresh(); it continues the observer when it
// is just the next sample sent in full (a delta could have carried it: the
// periodic full, or one requested), so what follows costs what it would
// have cost without it; otherwise (a gap in time, an innovation out of
// bounds) it re-anchors the observer and keeps the statistics.
//
// Deltas must reach the receiver in order and all of them (the link resends
// a lost one); state() is what to persist after each message so that a
// restarted sender continues the same stream.
//
// Not thread-safe: one stream, one thread (the core thread in acommsd).

#include <array>
#include <string>
#include <string_view>

#include "telemetry/stream_history.h"
#include "telemetry/stream_predictor.h"
#include "telemetry/telemetry_message.h"

namespace acomms::telemetry {

// One sample of the vehicle's track (sampler.h makes them).
struct Sample {
  int64_t time_s = 0;  // a multiple of tau, seconds (UTC, or track time)
  std::array<double, kAxes> position_m{};
  bool new_segment = false;  // the first sample after a gap in navigation
};

struct EncodedMessage {
  MessageKind kind = MessageKind::kFull;
  bool fresh = false;  // a full with which both ends start the statistics afresh
  uint32_t sequence = 0;
  std::string bytes;       // the message alone, zero-padded to whole bytes
  uint64_t bits = 0;       // header included
  uint64_t body_bits = 0;  // delta: the arithmetic codeword; full: time and position
  GridPosition position{};  // what the receiver will reconstruct
  Innovation innovation{};  // delta only
};

class TelemetryEncoder {
 public:
  // Throws std::invalid_argument for an invalid config (validate()).
  explicit TelemetryEncoder(const TelemetryConfig& config);

  // Throws std::out_of_range when the sample lies outside the region.
  EncodedMessage encode(const Sample& sample);
  // The same, appended to a caller's bit stream (e.g. a DCCL frame).
  EncodedMessage encode(const Sample& sample, dccl::BitWriter& out);

  // The next message is a full transmission.
  void request_full() { full_requested_ = true; }
  // The next message is a full with which both ends start their statistics
  // afresh: the receiver lost them, or will not see a message they include.
  void request_fresh() { full_requested_ = fresh_requested_ = true; }

  std::string state() const { return serialize(history_, fingerprint_); }
  // False (and the encoder starts over: next a full) for bytes that are
  // malformed, from another config, or do not replay.
  bool restore(std::string_view state);

  const TelemetryConfig& config() const { return config_; }

 private:
  GridPosition quantise(const Sample& sample) const;

  TelemetryConfig config_;
  uint64_t fingerprint_;
  RegionGrid region_;
  StreamPredictor predictor_;
  StreamHistory history_;
  bool full_requested_ = false;
  bool fresh_requested_ = false;
};

// Replays history into predictor (the state at the full, then accept the
// samples after it). False when that state does not load or an innovation
// falls outside the bounds (the history is not one this config produced).
bool replay(const TelemetryConfig& config, const StreamHistory& history, StreamPredictor* predictor);

}  // namespace acomms::telemetry
