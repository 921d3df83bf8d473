#pragma once
// The receiving end of one telemetry stream on the link (from one sender):
// puts wire messages back in order and feeds them, each exactly once, to
// the library's decoder.
//
// The rules, by the signed distance d of a message's 12-bit sequence from
// the last one consumed (wire_message.h, sequence_distance):
//   d == 1   consumed now, then any held messages that follow on;
//   d > 1    held until the gap before it fills (the sender resends
//            what was lost, oldest first); a held full whose gap has been
//            open longer than gap_timeout_s is consumed without it (the
//            sender gave up on the missing message: its ttl passed);
//   d <= 0   a resend of something consumed: dropped.
// Except a full whose time cannot follow the last position d messages on
// (d <= 0; or fewer than d tau seconds later, samples being tau apart; or
// 2048 tau or more later, past what the 12-bit number tells apart). Such a
// full newer than the last position and than every held full starts the
// stream afresh at once (its sender counts anew: restarted without its
// state): held fulls from before it are delivered with the deltas that
// follow each, the messages numbered after it are kept when its time, or
// their arrival after it was sampled, proves them its own count's, the
// rest is dropped (start_afresh). One not
// newer is an old full resent late: dropped, never held, since consumed
// after a gap timeout it would take the stream back to an old state.
// Between the two bounds (at least d tau and less than 2048 tau later) a
// full may follow d - 1 messages still being resent, and waits for them as
// any held full does.
// A delta is applied only when the decoder is in step (a fresh full since
// the start, or a full whose statistics it holds, and every message since
// consumed); otherwise it is dropped and the stream waits for the next
// full: a position is never decoded against the wrong state. Body bits that
// do not decode count as a lost delta. Consuming past a gap (the messages
// in it never come) forgets the decoder's state: the sender's statistics
// include what was lost.
//
// Statistics outlive fulls (stream_predictor.h), so a receiver that lost
// them is in step again only from a fresh full, which the sender sends when
// asked: take_feedback() says when to ask (the receiver lost its state, saw
// a gap, or a full whose statistics it does not hold), at most once per
// full received, and the sender's next message is then a fresh full.
//
// Not thread-safe: the core thread in acommsd.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "telemetry/telemetry_decoder.h"
#include "telemetry/wire_message.h"

namespace acomms::telemetry {

// One reconstructed sample.
struct ReceivedPosition {
  int32_t src = 0;
  int64_t time_s = 0;  // seconds since the Unix epoch
  std::array<double, kAxes> position_m{};
  bool full = false;
  // Set by the telemetry node when it stores the position: its number in
  // the node's received sequence (0: none) and when it was reconstructed
  // (seconds since the Unix epoch).
  int64_t seq = 0;
  double received_s = 0;
};

struct ReceiverCounters {
  uint64_t positions = 0;
  uint64_t duplicates = 0;    // resends of consumed messages
  uint64_t out_of_step = 0;   // deltas dropped: no state to apply them to
  uint64_t undecodable = 0;   // bodies that did not decode
  uint64_t gaps_skipped = 0;  // fulls consumed past a gap that timed out (or a fresh start closed)
  uint64_t fresh_starts = 0;  // fulls that restarted the stream: the sender counts anew
};

// What a receiver tells its sender when it lost the statistics.
struct Feedback {
  // The sequence of the last message consumed; none when nothing was (a
  // receiver without state). The sender ignores a request that a fresh
  // full it sent since will answer.
  std::optional<uint32_t> heard;
};

class StreamReceiver {
 public:
  static constexpr size_t kMaxHeld = 1024;

  // Throws std::invalid_argument for an invalid config.
  StreamReceiver(const TelemetryConfig& config, int32_t src, double gap_timeout_s);

  // A message of this stream, received at `now` (seconds since the Unix
  // epoch: places a full's time of day in a day). Returns the positions it
  // (and held messages it released) reconstructed, in order.
  std::vector<ReceivedPosition> receive(const WireMessage& message, double now);

  std::string state() const;
  // False for unusable bytes: the stream waits for the next full.
  bool restore(std::string_view state);

  // A request for a fresh full, when one is due (then not again until the
  // next full is consumed).
  std::optional<Feedback> take_feedback();

  const ReceiverCounters& counters() const { return counters_; }
  size_t held() const { return held_.size(); }

 private:
  struct Held {
    WireMessage message;
    double arrived = 0;
  };
  void consume(const WireMessage& message, double now, std::vector<ReceivedPosition>* out);
  void release(double now, std::vector<ReceivedPosition>* out);
  // Forgets the held messages at or before the last consumed.
  void drop_behind();
  // Out of step: ask the sender for a fresh full, unless asked since the
  // last full.
  void ask_for_fresh();
  // A body that did not decode: out of step until the next full.
  void undecodable(const WireMessage& message, const char* why);
  // Whether `full`, d messages on from the last consumed, can be the
  // sender's same count by its time (samples are tau apart).
  bool could_follow(const WireMessage& full, int32_t d, double now) const;
  // Seconds from the last position to `full`'s time, if both are usable.
  std::optional<int64_t> since_last(const WireMessage& full, double now) const;
  // Whether `full` is later than the last position and every held full.
  bool newer_than_all(const WireMessage& full, double now) const;
  // Continues from `full` (d from the last consumed) whatever the gap.
  void start_afresh(const WireMessage& full, int32_t d, double now, std::vector<ReceivedPosition>* out);
  // The held full nearest after the last consumed among those that arrived
  // by `arrived_by`, if any.
  std::optional<uint32_t> nearest_full(double arrived_by) const;
  // A full's time, placed in the day nearest `now`.
  int64_t full_time(const WireMessage& message, double now) const;

  TelemetryConfig config_;
  int32_t src_;
  double gap_timeout_s_;
  TelemetryDecoder decoder_;
  bool started_ = false;   // a message was consumed since the start
  bool in_step_ = false;   // the decoder holds the sender's state
  uint32_t last_ = 0;      // sequence of the last consumed message
  int64_t day_offset_s_ = 0;  // absolute time - the decoder's time of day
  int64_t last_time_s_ = 0;   // of the last position
  bool asked_ = false;        // for a fresh full, since the last full consumed
  bool feedback_due_ = false;
  // Messages after a gap, by sequence (at most kMaxHeld: past it the
  // newest is refused, and the sender's resend brings it again).
  std::map<uint32_t, Held> held_;
  ReceiverCounters counters_;
};

}  // namespace acomms::telemetry
