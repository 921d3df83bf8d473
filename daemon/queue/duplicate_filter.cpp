#include "queue/duplicate_filter.h"

namespace acomms::queue {

bool DuplicateFilter::seen(int32_t src, std::string_view encoded, double now) {
  if (window_s_ <= 0) return false;
  forget_before(now - window_s_);
  std::string key = key_of(src, encoded);
  if (keys_.count(key) > 0) return true;
  insert(std::move(key), now);
  return false;
}

void DuplicateFilter::remember(int32_t src, std::string_view encoded, double time) {
  if (window_s_ <= 0) return;
  std::string key = key_of(src, encoded);
  if (keys_.count(key) == 0) insert(std::move(key), time);
}

std::string DuplicateFilter::key_of(int32_t src, std::string_view encoded) {
  std::string key(reinterpret_cast<const char*>(&src), sizeof src);
  key.append(encoded);
  return key;
}

void DuplicateFilter::insert(std::string key, double time) {
  if (order_.size() >= capacity_) {
    // Still inside its window (the caller pruned the expired ones first).
    if (order_.front().time >= time - window_s_) ++forgotten_early_;
    keys_.erase(order_.front().key);
    order_.pop_front();
  }
  keys_.insert(key);
  order_.push_back({time, std::move(key)});
}

void DuplicateFilter::forget_before(double cutoff) {
  while (!order_.empty() && order_.front().time < cutoff) {
    keys_.erase(order_.front().key);
    order_.pop_front();
  }
}

}  // namespace acomms::queue
