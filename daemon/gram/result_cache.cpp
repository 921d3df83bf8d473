// LRU of model answers (see result_cache.h).
#include "gram/result_cache.h"

namespace acomms::gram {

std::shared_ptr<const ModelResult> ResultCache::find(const std::string& key) {
  auto it = index_.find(key);
  if (it == index_.end()) return nullptr;
  lru_.splice(lru_.begin(), lru_, it->second);
  return it->second->result;
}

void ResultCache::insert(const std::string& key, std::shared_ptr<const ModelResult> result, std::size_t bytes) {
  bytes += key.size();
  if (bytes > budget_) return;
  if (auto it = index_.find(key); it != index_.end()) {
    bytes_ -= it->second->bytes;
    lru_.erase(it->second);
    index_.erase(it);
  }
  lru_.push_front({key, std::move(result), bytes});
  index_[key] = lru_.begin();
  bytes_ += bytes;
  while (bytes_ > budget_ && !lru_.empty()) {
    bytes_ -= lru_.back().bytes;
    index_.erase(lru_.back().key);
    lru_.pop_back();
  }
}

}  // namespace acomms::gram
