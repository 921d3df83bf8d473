#pragma once
// The last MTs delivered, to drop an MT the gateway offers twice (spec
// §9.4: an MT keeps its MTMSN from queueing to delivery, so one whose
// over-the-air acknowledgement was lost comes back with the same number).
// The last 64 are kept: far more than the gateway's redeliveries of one
// message, far fewer than the 65535 numbers before they repeat.
//
// A repeat is the same MTMSN with the same payload. The number alone is not
// enough: a shore endpoint that restarts may hand out numbers again (ours
// starts from its clock), and a new MT under a number still in the window
// must not be dropped: the shore has already counted it delivered.
//
// Thread-safety: none; the driver's (core thread).

#include <algorithm>
#include <cstddef>
#include <deque>
#include <string>
#include <utility>

namespace acomms::drivers::iridium {

class MtmsnWindow {
 public:
  static constexpr size_t kSize = 64;

  // True (and remembered) if this MT is new; false for a repeat.
  bool admit(int mtmsn, const std::string& payload) {
    const std::pair<int, std::string> mt{mtmsn, payload};
    if (std::find(seen_.begin(), seen_.end(), mt) != seen_.end()) return false;
    seen_.push_back(mt);
    if (seen_.size() > kSize) seen_.pop_front();
    return true;
  }

 private:
  std::deque<std::pair<int, std::string>> seen_;  // at most 64 x 270 bytes
};

}  // namespace acomms::drivers::iridium
