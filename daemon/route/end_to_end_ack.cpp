// The origin's notes of wrapped sends (end_to_end_ack.h).
#include "route/end_to_end_ack.h"

#include <algorithm>

namespace acomms::route {

void EndToEndAcks::sent(RoutedSend send) {
  const auto seq = static_cast<uint16_t>(send.message_id & 0xffff);
  if (by_seq_.count(seq) == 0 && by_seq_.size() >= max_) {
    auto oldest = std::min_element(by_seq_.begin(), by_seq_.end(),
                                   [](const auto& a, const auto& b) { return a.second.sent_at < b.second.sent_at; });
    by_seq_.erase(oldest);
  }
  by_seq_[seq] = std::move(send);
}

bool EndToEndAcks::hop_acked(int64_t message_id) {
  auto it = by_seq_.find(static_cast<uint16_t>(message_id & 0xffff));
  if (it == by_seq_.end() || it->second.message_id != message_id) return false;
  it->second.hop_acked = true;
  return true;
}

const RoutedSend* EndToEndAcks::find(uint16_t seq) const {
  auto it = by_seq_.find(seq);
  return it == by_seq_.end() ? nullptr : &it->second;
}

std::optional<RoutedSend> EndToEndAcks::take(uint16_t seq) {
  auto it = by_seq_.find(seq);
  if (it == by_seq_.end()) return std::nullopt;
  RoutedSend send = std::move(it->second);
  by_seq_.erase(it);
  return send;
}

std::vector<RoutedSend> EndToEndAcks::list() const {
  std::vector<RoutedSend> out;
  for (const auto& [seq, send] : by_seq_) out.push_back(send);
  return out;
}

}  // namespace acomms::route
