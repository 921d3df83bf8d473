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
// A gap is also not counted while the sender is heard on more than one of
// this node's links (each heard from it within kSeveralLinks_s of the
// other): its messages may be in flight on the other link (a newer one
// arriving acoustically before older ones on Iridium), and which link lost
// what cannot be told. Not told apart (README, calibration, Limits): a
// message the sender dropped unsent (expired, refused) leaves a gap
// counted as a lost packet.
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
    // Whether more than one link heard `src` within kSeveralLinks_s of
    // each other (null: one link).
    std::function<bool(int32_t src)> several_links;
  };
  static constexpr double kSeveralLinks_s = 3600;
  explicit UnheardPackets(Hooks hooks) : hooks_(std::move(hooks)) {}

  // TelemetryNode::on_sequence.
  void on_sequence(int32_t src, uint32_t missing, bool replayed);

  struct Counters {
    uint64_t recorded = 0;       // unheard packet events
    uint64_t link_recorded = 0;  // missing messages the link had recorded lost already
    uint64_t replayed = 0;       // missing messages of a replay: not counted again
    uint64_t several_links = 0;  // missing while the sender was heard on several links
  };
  const Counters& counters() const { return counters_; }

 private:
  Hooks hooks_;
  std::map<int32_t, uint64_t> lost_at_last_;  // lost_recorded(src) at its last telemetry message
  Counters counters_;
};

}  // namespace acomms::node
