#pragma once
// Recognises an MO the shore has already handed up.
//
// The problem: the same MO reaches the shore twice when the gateway
// redelivers it (no MO confirmation arrived, or our side closed early), or
// when the modem resends after a session whose result it never learnt (the
// gateway had it; the modem retries with the same MOMSN: spec §5.1, §11).
// The decision (spec §9.4): an MO is known by (IMEI, MOMSN, payload); one
// seen within the window is dropped. The MOMSN alone would not do: it wraps
// 65535 → 0 and AT+SBDC zeroes it, so a new MO may reuse an old number; the
// payload tells them apart (two distinct MOs with equal number and equal
// bytes inside the window would be taken as one: for DCCL messages, which
// carry their time, that does not happen).
//
// This filter lives in the process; after a restart the queues' duplicate
// window (queue/duplicate_filter.h, filled again from the event log) is the
// second line that keeps a redelivered message from reaching subscribers
// twice. Memory is bounded by `capacity` (oldest forgotten first).
//
// Thread-compatible: the driver uses it on the core thread only.

#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <unordered_set>

namespace acomms::drivers {

class MoDedup {
 public:
  MoDedup(double window_s, size_t capacity) : window_s_(window_s), capacity_(capacity) {}

  // Whether this MO was remembered within the window (at `now`, seconds).
  bool contains(std::string_view imei, uint16_t momsn, std::string_view payload, double now);
  // Remembers this MO as handed up at `now`. The driver calls it only once
  // the MO is durable: an MO whose commit failed must still be taken when
  // the gateway redelivers it.
  void remember(std::string_view imei, uint16_t momsn, std::string_view payload, double now);
  size_t size() const { return keys_.size(); }

 private:
  static std::string key_of(std::string_view imei, uint16_t momsn, std::string_view payload);
  void forget_before(double cutoff);

  struct Entry {
    double time;
    std::string key;
  };
  std::deque<Entry> order_;
  std::unordered_set<std::string> keys_;
  double window_s_;
  size_t capacity_;
};

}  // namespace acomms::drivers
