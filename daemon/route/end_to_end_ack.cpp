// The origin's notes of wrapped sends (end_to_end_ack.h).
#include "route/end_to_end_ack.h"

#include <algorithm>

#include "route/route_journal.h"

namespace acomms::route {

void EndToEndAcks::attach(RouteJournal* journal, double now) {
  if (journal == nullptr) return;
  // Oldest sent first: past max_, the newest are the ones kept. Not
  // written back while read (journal_ still unset).
  for (RoutedSend& send : journal->load_awaiting(now)) sent(std::move(send));
  journal_ = journal;
}

void EndToEndAcks::erase(std::map<uint16_t, RoutedSend>::iterator it) {
  if (journal_ != nullptr) journal_->erase_awaiting(it->first);
  by_seq_.erase(it);
}

void EndToEndAcks::sent(RoutedSend send) {
  const auto seq = static_cast<uint16_t>(send.message_id & 0xffff);
  for (auto it = by_seq_.begin(); it != by_seq_.end();) {
    auto next = std::next(it);
    if (it->second.forget_after < send.sent_at && it->first != seq) erase(it);
    it = next;
  }
  if (by_seq_.count(seq) == 0 && by_seq_.size() >= max_) {
    erase(std::min_element(by_seq_.begin(), by_seq_.end(),
                           [](const auto& a, const auto& b) { return a.second.sent_at < b.second.sent_at; }));
  }
  if (journal_ != nullptr) journal_->save_awaiting(send);
  by_seq_[seq] = std::move(send);
}

bool EndToEndAcks::hop_acked(int64_t message_id) {
  auto it = by_seq_.find(static_cast<uint16_t>(message_id & 0xffff));
  if (it == by_seq_.end() || it->second.message_id != message_id) return false;
  it->second.hop_acked = true;
  if (journal_ != nullptr) journal_->save_awaiting(it->second);
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
  erase(it);
  return send;
}

std::vector<RoutedSend> EndToEndAcks::list() const {
  std::vector<RoutedSend> out;
  for (const auto& [seq, send] : by_seq_) out.push_back(send);
  return out;
}

}  // namespace acomms::route
