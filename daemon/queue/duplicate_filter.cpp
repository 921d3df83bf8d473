#include "queue/duplicate_filter.h"

namespace acomms::queue {

bool DuplicateFilter::seen(int32_t src, std::string_view encoded, double now) {
  if (window_s_ <= 0) return false;
  forget_before(now - window_s_);
  std::string key(reinterpret_cast<const char*>(&src), sizeof src);
  key.append(encoded);
  if (keys_.count(key) > 0) return true;
  if (order_.size() >= capacity_) {
    keys_.erase(order_.front().key);
    order_.pop_front();
  }
  keys_.insert(key);
  order_.push_back({now, std::move(key)});
  return false;
}

void DuplicateFilter::forget_before(double cutoff) {
  while (!order_.empty() && order_.front().time < cutoff) {
    keys_.erase(order_.front().key);
    order_.pop_front();
  }
}

}  // namespace acomms::queue
