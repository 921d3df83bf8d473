#pragma once
// Packets sent and not received that only a telemetry gap tells of, made
// packet events (issue 32), so that `acommsctl link calibrate` counts them
// as not decoded.
//
// The problem: a gap in a sender's telemetry sequence
// (telemetry/sequence_gaps.h) says messages were sent and did not arrive,
// but the link may already have recorded some of those packets as lost:
// the Micro-Modem tells a damaged packet or a poll never answered, the
// simulator every failed draw (link_controller.h, lost_recorded). Counting
// the gap as well would count those packets twice.
//
// The decision: at each telemetry message from a sender, the losses the
// links recorded from it since its previous telemetry message are taken
// as part of the gap; only the rest become events ("unheard" packets: no
// measured figures, the model's prediction when the link has one and both
// positions are known, the sender's position being the last one its
// telemetry gave before the gap: the message after the gap waits held
// until the gap fills, stream_receiver.h, so there is no later one to
// interpolate to). A gap told again from the event log at start (replayed)
// is not counted: it was when it first came.
//
// Core thread only.

#include <cstdint>
#include <functional>
#include <map>

namespace acomms::node {

class UnheardPackets {
 public:
  struct Hooks {
    // The lost packet events the links recorded from `src` so far.
    std::function<uint64_t(int32_t src)> lost_recorded;
    // Records one packet from `src` sent and not received (an event).
    std::function<void(int32_t src)> record;
  };
  explicit UnheardPackets(Hooks hooks) : hooks_(std::move(hooks)) {}

  // TelemetryNode::on_sequence.
  void on_sequence(int32_t src, uint32_t missing, bool replayed);

  struct Counters {
    uint64_t recorded = 0;       // unheard packet events
    uint64_t link_recorded = 0;  // missing messages the link had recorded lost already
    uint64_t replayed = 0;       // missing messages of a replay: not counted again
  };
  const Counters& counters() const { return counters_; }

 private:
  Hooks hooks_;
  std::map<int32_t, uint64_t> lost_at_last_;  // lost_recorded(src) at its last telemetry message
  Counters counters_;
};

}  // namespace acomms::node
