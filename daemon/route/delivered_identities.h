#pragma once
// Which routed messages this node has delivered, by identity (origin,
// sequence): a copy that arrives by another path, or a resend whose hop ACK
// was lost, is dropped instead of delivered twice.
//
// The problem. A sequence is the origin's journal id mod 2^16: after
// 65536 messages it wraps, so the smallest identity is not the oldest, and
// a memory that evicts by identity (std::map::begin) throws away the newest
// when it is full. The memory must also outlive a SIGKILL.
//
// The decision. Each identity is kept until its own forget_after (its
// remaining ttl when it arrived plus a margin: no copy can be younger);
// when full, the one due to be forgotten first goes. The durable half is
// the journal's (MessageJournal::routed_since, migrations/0013): the
// forwarder fills this from it at start.
//
// Threads: core thread only (a plain class, owned by the Forwarder).

#include <cstddef>
#include <map>

#include "route/envelope.h"

namespace acomms::route {

class DeliveredIdentities {
 public:
  inline static constexpr size_t kDefaultMax = 16384;
  explicit DeliveredIdentities(size_t max = kDefaultMax) : max_(max) {}

  // Whether `identity` was delivered and is still remembered at `now`
  // (those past their time are forgotten first).
  bool contains(const MessageIdentity& identity, double now);
  // Remembers `identity` until `forget_after` (a second call moves it).
  void remember(const MessageIdentity& identity, double forget_after);
  size_t size() const { return by_identity_.size(); }

 private:
  size_t max_;
  std::map<MessageIdentity, double> by_identity_;
  std::multimap<double, MessageIdentity> by_time_;
};

}  // namespace acomms::route
