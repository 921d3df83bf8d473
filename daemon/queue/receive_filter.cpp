// The receive filter's two rules (stale, then duplicate) and its refill at
// start-up; the rules themselves are in receive_filter.h. Each refusal is
// logged so an operator can tell a lost message from a refused one, but
// never once per message: a sender resending a backlog would fill the log.

#include "queue/receive_filter.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/core_thread.h"

namespace acomms::queue {

ReceiveFilter::ReceiveFilter(const v1::QueueConfig& config)
    : duplicate_window_s_(config.has_duplicate_window_s() ? config.duplicate_window_s() : 300),
      clock_skew_s_(config.has_clock_skew_s() ? config.clock_skew_s() : 60) {
  if (!(config.duplicate_window_s() >= 0) || !std::isfinite(config.duplicate_window_s())) {
    throw std::invalid_argument("queue.duplicate_window_s must be 0 (off) or a positive number of seconds");
  }
  if (!(clock_skew_s_ >= 0) || !std::isfinite(clock_skew_s_)) {
    throw std::invalid_argument("queue.clock_skew_s must be 0 or a positive number of seconds");
  }
}

double ReceiveFilter::add_type(const std::string& type, double ttl_s, const MessageRoles& roles) {
  if (duplicate_window_s_ <= 0) return 0;
  // Never shorter than the ttl: the sender resends until then.
  const double window_s = std::max(duplicate_window_s_, ttl_s);
  types_.try_emplace(type, TypeWindow{window_s,
                                      DuplicateFilter(window_s + (roles.has_timestamp() ? 2 * clock_skew_s_ : 0))});
  return window_s;
}

bool ReceiveFilter::admit(const ReceivedMessage& received, const MessageRoles& roles, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  auto it = types_.find(received.type);
  if (it == types_.end()) return true;
  TypeWindow& type = it->second;
  // Stale first: a refused message must not be remembered as seen.
  return !refuse_if_stale(type, received, roles.timestamp(*received.message), now) &&
         !drop_if_duplicate(type, received, now);
}

bool ReceiveFilter::refuse_if_stale(TypeWindow& type, const ReceivedMessage& received, std::optional<double> stamped,
                                    double now) {
  double bound = type.window_s + clock_skew_s_;
  if (!stamped || *stamped >= now - bound) {
    if (type.stale_in_burst > 0) {
      spdlog::info("queue {}: {} stale message{} refused before this fresh one", received.type,
                   type.stale_in_burst, type.stale_in_burst == 1 ? "" : "s");
      type.stale_in_burst = 0;
    }
    return false;
  }
  ++stale_refused_;
  // Once per burst: a sender resending a backlog would fill the log.
  if (type.stale_in_burst++ == 0) {
    spdlog::warn("queue {}: message from {} stamped {:.0f} s ago, longer than the type's window of {} s plus "
                 "{} s clock skew: refused as stale, not delivered (a resend whose first copy may already have "
                 "been); further stale ones are counted until a fresh one arrives",
                 received.type, received.src, now - *stamped, type.window_s, clock_skew_s_);
  }
  return true;
}

bool ReceiveFilter::drop_if_duplicate(TypeWindow& type, const ReceivedMessage& received, double now) {
  DuplicateFilter& filter = type.seen;
  bool seen = filter.seen(received.src, received.encoded, now);
  if (filter.forgotten_early() > type.forgotten_early_logged) {
    // Logged at the first and then every 1000th: the filter is too small
    // for this rate, and a resend of a forgotten message would be delivered.
    if (type.forgotten_early_logged == 0 || filter.forgotten_early() / 1000 > type.forgotten_early_logged / 1000) {
      spdlog::warn("queue {}: {} received message{} forgotten inside the {} s duplicate window (capacity {}): "
                   "a resend of them would be delivered again", received.type, filter.forgotten_early(),
                   filter.forgotten_early() == 1 ? "" : "s", filter.window_s(), filter.capacity());
    }
    type.forgotten_early_logged = filter.forgotten_early();
  }
  if (!seen) return false;
  ++duplicates_;
  spdlog::info("queue {}: retransmission from {} not passed on again", received.type, received.src);
  return true;
}

void ReceiveFilter::refill(MessageJournal& journal, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  // A sender whose ACK was lost while this node was down sends again; what
  // was passed on before the restart must still count as seen.
  const double longest = longest_window_s();
  if (longest <= 0) return;
  size_t remembered = 0;
  for (const QueueEvent& event : journal.received_since(now - longest)) {
    auto it = types_.find(event.type);
    if (it == types_.end()) continue;
    DuplicateFilter& filter = it->second.seen;
    if (event.time < now - filter.window_s()) continue;
    filter.remember(event.src, event.encoded, event.time);
    ++remembered;
  }
  spdlog::info("queue: {} message{} received in the last {} s remembered, so that retransmissions of them "
               "are not passed on again", remembered, remembered == 1 ? "" : "s", longest);
}

double ReceiveFilter::longest_window_s() const {
  ACOMMS_ASSERT_CORE_THREAD();
  double longest = 0;
  for (const auto& [name, type] : types_) longest = std::max(longest, type.seen.window_s());
  return longest;
}

}  // namespace acomms::queue
