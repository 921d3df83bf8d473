#pragma once
// What the receive side refuses to pass on: a retransmission of a message
// already passed on, and a message too old to tell apart from one.
//
// Delivered at most once, for as long as the sender may resend: an
// acknowledged message whose ACK is lost (or whose sender restarts before
// the ACK is in) is sent again until it is acked or its ttl passes. Each
// type therefore remembers what it received for its window, W = the longer
// of queue.duplicate_window_s and the type's ttl_s, and a Submit ttl_s
// longer than W is refused (QueueManager, TtlTooLongError), so a resend
// always falls inside the window of a receiver with the same queue config.
// Types with a timestamp role also refuse as stale a message stamped more
// than W + clock_skew_s ago (a sender whose ttl is longer than ours, or a
// message the filter had to forget), and remember for W + 2 * clock_skew_s
// so that the two rules meet: a resend the filter no longer holds is older
// than the stale bound. What was passed on before a restart still counts
// as seen: refill() reads it back from the event log at start-up.
//
// The decision: one class for the whole node, holding each type's window
// and DuplicateFilter (duplicate_filter.h), so that the queues
// (queue_manager.h) only ask "pass this on?" and the rule lives in one
// place.
//
// Threads: the core thread only.

#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>

#include "acomms/v1/config.pb.h"
#include "queue/duplicate_filter.h"
#include "queue/message_journal.h"
#include "queue/received_message.h"
#include "queue/roles.h"

namespace acomms::queue {

class ReceiveFilter {
 public:
  // Reads queue.duplicate_window_s (unset: 300 s; 0: off) and
  // queue.clock_skew_s (unset: 60 s). Throws std::invalid_argument naming
  // the field when either is negative or not a number.
  explicit ReceiveFilter(const v1::QueueConfig& config);

  // Gives `type` (whose messages live `ttl_s` and carry `roles`) its window
  // and returns W in seconds; 0 when the filter is off. Call once per type
  // that wants filtering; types never added are always passed on.
  double add_type(const std::string& type, double ttl_s, const MessageRoles& roles);

  // Whether `received` (decoded, with its type, source and bytes set) is
  // passed on: false for a stale message or a retransmission, each counted
  // and logged. `roles` reads its timestamp. A message passed on is
  // remembered, so that its resend is not.
  bool admit(const ReceivedMessage& received, const MessageRoles& roles, double now);

  // Start-up: remembers what the journal's event log says was received
  // within each type's window, before anything new is admitted.
  void refill(MessageJournal& journal, double now);

  // The longest any type looks back (seconds; 0: none does): received
  // events this recent are read back by refill, so the event log must keep
  // them.
  double longest_window_s() const;
  // Received messages recognised as retransmissions and not passed on.
  uint64_t duplicates() const { return duplicates_; }
  // Received messages refused as stale: stamped longer ago than their
  // type's window (plus the clock skew allowed).
  uint64_t stale_refused() const { return stale_refused_; }

 private:
  struct TypeWindow {
    double window_s;  // W
    // Remembers for W, or W + 2 * clock skew when the type has a timestamp
    // role.
    DuplicateFilter seen;
    uint64_t stale_in_burst = 0;  // stale refusals since the last fresh message
    uint64_t forgotten_early_logged = 0;
  };

  bool refuse_if_stale(TypeWindow& type, const ReceivedMessage& received, std::optional<double> stamped,
                       double now);
  bool drop_if_duplicate(TypeWindow& type, const ReceivedMessage& received, double now);

  double duplicate_window_s_;  // queue.duplicate_window_s (0: off)
  double clock_skew_s_;        // queue.clock_skew_s
  std::unordered_map<std::string, TypeWindow> types_;
  uint64_t duplicates_ = 0;
  uint64_t stale_refused_ = 0;
};

}  // namespace acomms::queue
