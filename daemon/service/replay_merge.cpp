#include "service/replay_merge.h"

#include <algorithm>
#include <limits>

namespace acomms::service {

std::vector<ReplayPick> merge_replay_pages(const std::vector<int64_t>& message_seqs, bool messages_full,
                                           const std::vector<int64_t>& position_seqs, bool positions_full) {
  int64_t complete_to = std::numeric_limits<int64_t>::max();
  if (messages_full && !message_seqs.empty()) complete_to = std::min(complete_to, message_seqs.back());
  if (positions_full && !position_seqs.empty()) complete_to = std::min(complete_to, position_seqs.back());
  std::vector<ReplayPick> picks;
  size_t m = 0, p = 0;
  for (;;) {
    const bool m_left = m < message_seqs.size() && message_seqs[m] <= complete_to;
    const bool p_left = p < position_seqs.size() && position_seqs[p] <= complete_to;
    if (!m_left && !p_left) break;
    if (m_left && (!p_left || message_seqs[m] < position_seqs[p])) {
      picks.push_back({false, m++});
    } else {
      picks.push_back({true, p++});
    }
  }
  return picks;
}

}  // namespace acomms::service
