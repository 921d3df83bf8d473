#include "queue/queue_policy.h"

#include <cmath>
#include <stdexcept>

namespace acomms::queue {
namespace {

// The first of specific / defaults that sets the field, else `builtin`.
template <typename T, typename Has, typename Get>
T pick(const v1::QueuePolicy& specific, const v1::QueuePolicy& defaults, Has has, Get get, T builtin) {
  if ((specific.*has)()) return (specific.*get)();
  if ((defaults.*has)()) return (defaults.*get)();
  return builtin;
}

}  // namespace

QueuePolicy resolve_policy(const v1::QueuePolicy& specific, const v1::QueuePolicy& defaults,
                           const std::string& what) {
  using P = v1::QueuePolicy;
  QueuePolicy builtin;
  QueuePolicy policy;
  policy.ack = pick(specific, defaults, &P::has_ack, &P::ack, builtin.ack);
  policy.blackout_time_s =
      pick(specific, defaults, &P::has_blackout_time_s, &P::blackout_time_s, builtin.blackout_time_s);
  policy.max_queue = pick(specific, defaults, &P::has_max_queue, &P::max_queue, builtin.max_queue);
  policy.newest_first = pick(specific, defaults, &P::has_newest_first, &P::newest_first, builtin.newest_first);
  policy.ttl_s = pick(specific, defaults, &P::has_ttl_s, &P::ttl_s, builtin.ttl_s);
  policy.value_base = pick(specific, defaults, &P::has_value_base, &P::value_base, builtin.value_base);
  P::OnFull on_full = pick(specific, defaults, &P::has_on_full, &P::on_full, P::ON_FULL_UNSPECIFIED);
  policy.on_full = on_full == P::REFUSE_NEW ? QueuePolicy::OnFull::kRefuseNew
                                            : QueuePolicy::OnFull::kDropOldest;

  auto bad = [&](const std::string& setting, const std::string& rule) {
    throw std::invalid_argument(what + ": " + setting + " " + rule);
  };
  if (!(policy.ttl_s > 0) || !std::isfinite(policy.ttl_s)) bad("ttl_s", "must be a positive number of seconds");
  if (!(policy.value_base >= 0) || !std::isfinite(policy.value_base)) bad("value_base", "must be 0 or more");
  if (!(policy.blackout_time_s >= 0) || !std::isfinite(policy.blackout_time_s)) {
    bad("blackout_time_s", "must be 0 or more seconds");
  }
  if (policy.max_queue == 0) bad("max_queue", "must be at least 1");
  return policy;
}

}  // namespace acomms::queue
