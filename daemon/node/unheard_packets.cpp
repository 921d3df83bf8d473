#include "node/unheard_packets.h"

#include <algorithm>

#include "core/core_thread.h"

namespace acomms::node {

void UnheardPackets::on_sequence(int32_t src, uint32_t missing, bool replayed) {
  ACOMMS_ASSERT_CORE_THREAD();
  const uint64_t lost = hooks_.lost_recorded ? hooks_.lost_recorded(src) : 0;
  auto [it, first] = lost_at_last_.try_emplace(src, lost);
  const uint64_t since = first ? 0 : lost - it->second;
  it->second = lost;
  if (missing == 0) return;
  if (replayed) {
    counters_.replayed += missing;
    return;
  }
  if (hooks_.several_links && hooks_.several_links(src)) {
    counters_.several_links += missing;
    return;
  }
  const uint64_t already = std::min<uint64_t>(since, missing);
  counters_.link_recorded += already;
  for (uint64_t i = already; i < missing; ++i) {
    if (hooks_.record) hooks_.record(src);
    ++counters_.recorded;
  }
}

}  // namespace acomms::node
