// The destination's memory of delivered identities (delivered_identities.h).
#include "route/delivered_identities.h"

namespace acomms::route {
namespace {

template <typename Map>
void erase_pair(Map& by_time, double time, const MessageIdentity& identity) {
  auto [first, last] = by_time.equal_range(time);
  for (auto it = first; it != last; ++it) {
    if (it->second == identity) {
      by_time.erase(it);
      return;
    }
  }
}

}  // namespace

bool DeliveredIdentities::contains(const MessageIdentity& identity, double now) {
  while (!by_time_.empty() && by_time_.begin()->first < now) {
    by_identity_.erase(by_time_.begin()->second);
    by_time_.erase(by_time_.begin());
  }
  return by_identity_.count(identity) > 0;
}

void DeliveredIdentities::remember(const MessageIdentity& identity, double forget_after) {
  if (auto it = by_identity_.find(identity); it != by_identity_.end()) {
    erase_pair(by_time_, it->second, identity);
    by_identity_.erase(it);
  }
  // Full: the one due to be forgotten first, never the newest.
  if (by_identity_.size() >= max_ && !by_time_.empty()) {
    by_identity_.erase(by_time_.begin()->second);
    by_time_.erase(by_time_.begin());
  }
  by_identity_[identity] = forget_after;
  by_time_.emplace(forget_after, identity);
}

}  // namespace acomms::route
