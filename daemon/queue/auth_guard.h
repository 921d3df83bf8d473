#pragma once
// What the receive side refuses of an authenticated type (dccl/message_auth.h)
// beyond a bad tag: a message it accepted before (replayed) and one stamped
// outside the type's window (stale).
//
// Problem: a tag proves who made a message, not that it is new: a recorded
// Command sent again later carries a valid tag. Decision: each type has a
// window W (config auth.type.window_s, > 0). A message stamped more than W
// before (or after) the receiver's clock is stale; inside it, the exact
// bytes (trailer included: the counter and time make each of a sender's
// sealed messages unique) and their sender are remembered for W past their
// stamp, so a second copy is a replay. The sender is part of what is
// remembered because two nodes sealing the same message in the same second
// make the same bytes; the tag covers the sender (dccl/message_auth.h), so
// a copy sent under another id fails its tag instead of passing as new. The two rules meet: a copy the guard has forgotten is stale.
// What was accepted is made durable with its received event (the store's
// auth_accepted table) before any subscriber sees the message, and refill()
// reads it back at start-up, so a receiver's restart opens no gap.
// A legitimate retransmission (its ack lost) is the same bytes, so it is
// counted as replayed too: the receiver cannot tell them apart, and both
// must not be delivered twice.
//
// Refusals are counted per reason and logged once per burst (the first of
// a burst in full, then a count when the next burst starts, a burst ending
// after 60 s without a refusal), so a rogue transmitter cannot fill the log.
//
// Threads: the core thread only.

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>

#include "dccl/message_auth.h"
#include "queue/message_journal.h"

namespace acomms::queue {

enum class AuthRefusal { kAuthFailed, kReplayed, kStale };
std::string_view to_string(AuthRefusal refusal);

struct AuthRefusals {
  uint64_t auth_failed = 0;
  uint64_t replayed = 0;
  uint64_t stale = 0;
};

class AuthGuard {
 public:
  static constexpr double kBurstGapS = 60;

  // Makes `type` authenticated with window `window_s`. Throws
  // std::invalid_argument naming the type unless window_s > 0 (and finite).
  void add_type(const std::string& type, double window_s);
  bool covers(const std::string& type) const { return windows_.count(type) > 0; }
  // W of an authenticated type; 0 for others.
  double window_s(const std::string& type) const;
  double longest_window_s() const;

  // Whether a message of `type` from `sender` whose tag verified with
  // `stamp` is fresh and new at `now`: nullopt to pass it on, else why not.
  // Does not count.
  std::optional<AuthRefusal> judge(const std::string& type, int32_t sender, std::string_view encoded,
                                   const dccl::AuthStamp& stamp, double now) const;

  // Counts and logs (once per burst) a refusal; `detail` says more.
  void refuse(AuthRefusal why, const std::string& type, int32_t src, std::string_view detail, double now);

  // Remembers a message from `sender` passed on, so that its copy is
  // refused. Forgets what is past every window.
  void remember(const std::string& type, int32_t sender, std::string_view encoded, uint32_t sent_s, double now);
  // The stamp before which nothing is remembered any more (the store may
  // forget it too).
  double forget_before(double now) const { return now - longest_window_s(); }

  // Start-up: remembers again what the journal's auth_accepted holds.
  void refill(MessageJournal& journal, double now);

  const AuthRefusals& refusals() const { return refusals_; }

 private:
  // nullopt: any sender (rows stored before senders were told apart).
  static std::string key_of(const std::string& type, std::optional<int32_t> sender, std::string_view encoded);
  void forget(double now);

  std::unordered_map<std::string, double> windows_;
  std::set<std::string> seen_;                         // key_of
  bool any_sender_seen_ = false;                       // seen_ holds keys of any sender
  std::multimap<uint32_t, std::string> by_sent_;       // stamp -> key_of, to forget in order
  AuthRefusals refusals_;
  double last_refusal_ = -1e300;
  uint64_t in_burst_ = 0;  // refusals since the burst's first, not yet logged
};

}  // namespace acomms::queue
