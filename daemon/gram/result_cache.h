// Answers kept for identical model requests, within a memory budget.
//
// Problem: behaviours ask the same question again and again (same
// environment, same receivers) between CTD casts; a model run costs
// milliseconds to seconds, a lookup microseconds. Decision: key = the
// request's exact bytes (kind, every environment, every option), so only a
// truly identical request hits; least recently used entries are dropped
// while the estimated bytes exceed the budget; an entry larger than the
// whole budget is not kept. Not thread-safe: the pool holds its lock.
#pragma once

#include <cstddef>
#include <list>
#include <memory>
#include <string>
#include <unordered_map>

namespace acomms::gram {

struct ModelResult;

class ResultCache {
 public:
  explicit ResultCache(std::size_t budget_bytes) : budget_(budget_bytes) {}

  // The result, marked most recently used; null when absent.
  std::shared_ptr<const ModelResult> find(const std::string& key);
  void insert(const std::string& key, std::shared_ptr<const ModelResult> result, std::size_t bytes);

  std::size_t entries() const { return index_.size(); }
  std::size_t bytes() const { return bytes_; }

 private:
  struct Entry {
    std::string key;
    std::shared_ptr<const ModelResult> result;
    std::size_t bytes;
  };
  std::size_t budget_;
  std::size_t bytes_ = 0;
  std::list<Entry> lru_;  // most recent first
  std::unordered_map<std::string, std::list<Entry>::iterator> index_;
};

}  // namespace acomms::gram
