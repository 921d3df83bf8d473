#pragma once
// A queue's policy, resolved from config: the type's own settings, then the
// configured defaults, then the built-in defaults.

#include <cstdint>
#include <string>

#include "acomms/v1/config.pb.h"

namespace acomms::queue {

struct QueuePolicy {
  bool ack = true;
  double blackout_time_s = 0;
  uint32_t max_queue = 100;
  bool newest_first = true;
  double ttl_s = 1800;
  double value_base = 1;
  enum class OnFull { kDropOldest, kRefuseNew } on_full = OnFull::kDropOldest;
};

// Layers `specific` over `defaults` over the built-in values. Throws
// std::invalid_argument naming `what` ("queue gv.Status") and the setting
// when a value is unusable (ttl_s <= 0, value_base < 0, max_queue 0, ...).
QueuePolicy resolve_policy(const v1::QueuePolicy& specific, const v1::QueuePolicy& defaults,
                           const std::string& what);

}  // namespace acomms::queue
