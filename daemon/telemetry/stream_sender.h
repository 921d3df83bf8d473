#pragma once
// The sending end of one telemetry stream on the link (to one receiver):
// the library's encoder plus the 12-bit wire sequence (wire_message.h).
//
// Restart rule: state() is stored after the message it describes is queued,
// in the same store queue (which commits in order), so after a crash the
// stored state is never ahead of the queue: no sequence number is skipped,
// and the receiver never waits for a message that does not exist. It may
// be behind (the message stored, the kill before the state): the daemon
// then continues after the newest sequence still queued (continue_after),
// and the first message after any restart is a full (the sampler starts a
// new segment), which does not depend on the encoder state the crash lost;
// it keeps the statistics, but when the state was behind, a fresh one
// (the receiver's statistics will include the message the state missed).
// At most one full per restart.
//
// Statistics outlive fulls (stream_predictor.h): the receiver asks for a
// fresh full when it lost them (on_feedback).
//
// Core thread (one stream, one thread).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "telemetry/telemetry_encoder.h"
#include "telemetry/wire_message.h"

namespace acomms::telemetry {

class StreamSender {
 public:
  // Throws std::invalid_argument for an invalid config.
  StreamSender(const TelemetryConfig& config, int32_t src, int32_t dest);

  // The next message for `sample`. Throws std::out_of_range for a sample
  // outside the region (nothing changes then).
  WireMessage send(const Sample& sample);
  // The next message is a fresh full (the last one could not be queued: the
  // receiver will never see what the statistics learned from it).
  void request_fresh() { encoder_.request_fresh(); }
  // The receiver asks for a fresh full (WireFeedback). True when the next
  // message will be one; false when a fresh full sent after the receiver's
  // last heard message answers it already.
  bool on_feedback(std::optional<uint32_t> heard);

  std::string state() const;
  // False for unusable bytes: the stream then starts over (next a full,
  // sequence from 0, which the receiver accepts: a full newer in time).
  bool restore(std::string_view state);

  uint32_t last_sequence() const { return sequence_; }
  // After a restart: `sequence` is queued (sent before the stored state was
  // written), so the next message follows it. Ignored when not newer than
  // last_sequence().
  void continue_after(uint32_t sequence);
  int32_t dest() const { return dest_; }

 private:
  TelemetryEncoder encoder_;
  int32_t src_;
  int32_t dest_;
  uint32_t sequence_ = kWireSequenceModulus - 1;  // the first message is 0
  std::optional<uint32_t> last_fresh_;            // sequence of the last fresh full
};

}  // namespace acomms::telemetry
