#pragma once
// Recognises retransmissions on the receive side.
//
// A sender that does not hear the ACK for a frame (the ACK was lost, or
// the sender restarted before it arrived) sends the same messages again,
// and DCCL carries no sequence number to tell. So a message whose source
// and encoded bytes equal one received within the last `window_s` seconds
// is taken as a retransmission and not delivered again. Messages that are
// meant to repeat identical content within the window must differ in some
// field (most carry a time), or the window must be shortened (0 turns the
// filter off). The filter itself lives in memory; the ReceiveFilter keeps
// one per type, with the type's window (receive_filter.h: at least as long
// as the type's ttl, so that a sender's last resend still falls inside it),
// and fills it again at start-up from the received events in the event log.
//
// Memory is bounded by a capacity: past it the oldest entry is forgotten,
// even one still inside its window. Such early forgetting is counted
// (forgotten_early), because a resend of that message would then be passed
// on again; the ReceiveFilter logs it.

#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <unordered_set>

namespace acomms::queue {

class DuplicateFilter {
 public:
  // Remembers at most `capacity` messages (oldest forgotten first), so a
  // flood cannot grow memory without bound.
  static constexpr size_t kDefaultCapacity = 16384;
  explicit DuplicateFilter(double window_s, size_t capacity = kDefaultCapacity)
      : window_s_(window_s), capacity_(capacity) {}

  // True if (src, encoded) was seen within the window; otherwise remembers
  // it and returns false.
  bool seen(int32_t src, std::string_view encoded, double now);

  // Remembers (src, encoded) as received at `time`, as seen() would have:
  // to fill the filter again at start-up from the event log. Calls must
  // come in time order, and before any seen().
  void remember(int32_t src, std::string_view encoded, double time);

  double window_s() const { return window_s_; }
  size_t capacity() const { return capacity_; }
  // Entries forgotten for want of room while still inside their window.
  uint64_t forgotten_early() const { return forgotten_early_; }

 private:
  struct Entry {
    double time;
    std::string key;
  };
  static std::string key_of(int32_t src, std::string_view encoded);
  void insert(std::string key, double time);
  void forget_before(double cutoff);

  double window_s_;
  size_t capacity_;
  std::deque<Entry> order_;  // by arrival time
  std::unordered_set<std::string> keys_;
  uint64_t forgotten_early_ = 0;
};

}  // namespace acomms::queue
