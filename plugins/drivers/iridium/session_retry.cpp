#include "iridium/session_retry.h"

#include <algorithm>

namespace acomms::drivers::iridium {

std::chrono::milliseconds SessionRetry::next() {
  ++failures_;
  if (failures_ > 4) return kSteady;
  const int64_t spread_ms = failures_ <= 2 ? 5000 : 30000;
  std::uniform_int_distribution<int64_t> pick(0, spread_ms);
  return std::max<std::chrono::milliseconds>(kFloor, std::chrono::milliseconds(pick(random_)));
}

}  // namespace acomms::drivers::iridium
