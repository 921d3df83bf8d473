#pragma once
// Packets sent and not received, told by the gaps in a telemetry stream's
// sequence (issue 32, "calibration from the field").
//
// The problem: a packet the modem never detected leaves no trace on the
// receiving side's link, yet the link's calibration (eval/link_calibration.h)
// must count it as not decoded, or the reception curve sees only the
// survivors. Position telemetry numbers its messages (12 bits,
// wire_message.h) and each sender's stream is sent in order, so a message
// that arrives with messages missing before it tells of messages sent and
// not received.
//
// The decision, per sender, by the signed distance d of a message's
// sequence from the newest seen (sequence_distance):
//   first message heard        the baseline, nothing missing;
//   d == 1                     nothing missing;
//   1 < d <= kMaxCounted + 1   d - 1 missing, counted now, once;
//   d > kMaxCounted + 1        a jump (the sender was silent or out of
//                              range for long, or dropped what expired
//                              unsent): a new baseline, nothing counted;
//   d <= 0                     a late copy (the sender's resend of a missing
//                              message) or a replay: nothing, not again;
//   the stream's receiver took the message as a fresh start (the sender
//   restarted without its state and counts anew, stream_receiver.h): a
//   new baseline, nothing counted.
// A gap across this node's own restart is never counted: the newest seen
// is not kept, and messages consumed again from the event log at start
// (whose gaps are told as replayed, not counted again) are forgotten once
// the replay is done (forget), so the first live message from each
// sender is a new baseline. Each missing message counts as one packet: telemetry
// sends a message per sample and a slot's packet usually carries one; a
// packet carrying two is then counted twice, one whose telemetry went in a
// later packet is not counted at all (documented in the README).
//
// Not thread-safe: the core thread in acommsd (owned by TelemetryNode).

#include <cstdint>
#include <map>

namespace acomms::telemetry {

struct SequenceGapCounters {
  uint64_t missing = 0;   // messages counted missing
  uint64_t late = 0;      // copies of what was seen or counted missing
  uint64_t jumps = 0;     // gaps too long to count
  uint64_t restarts = 0;  // fresh starts: a new baseline
};

class SequenceGaps {
 public:
  static constexpr int32_t kMaxCounted = 64;

  // The message numbered `sequence` from `src` arrived; `fresh_start`: its
  // stream took it as the sender counting anew. Returns how many messages
  // before it never arrived (see above).
  uint32_t observe(int32_t src, uint32_t sequence, bool fresh_start);

  // Every sender's newest seen dropped: the next message from each is a
  // baseline (after this node's own restart, TelemetryNode::restore).
  void forget() { newest_.clear(); }

  const SequenceGapCounters& counters() const { return counters_; }

 private:
  std::map<int32_t, uint32_t> newest_;
  SequenceGapCounters counters_;
};

}  // namespace acomms::telemetry
