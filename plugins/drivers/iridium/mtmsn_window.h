#pragma once
// The MTMSNs of the last MTs delivered, to drop an MT the gateway offers
// twice (spec §9.4: an MT keeps its MTMSN from queueing to delivery, so one
// whose over-the-air acknowledgement was lost comes back with the same
// number). The last 64 are kept: far more than the gateway's redeliveries
// of one message, far fewer than the 65535 numbers before they repeat.
//
// Thread-safety: none; the driver's (core thread).

#include <algorithm>
#include <cstddef>
#include <deque>

namespace acomms::drivers::iridium {

class MtmsnWindow {
 public:
  static constexpr size_t kSize = 64;

  // True (and remembered) if `mtmsn` is new; false for a repeat.
  bool admit(int mtmsn) {
    if (std::find(seen_.begin(), seen_.end(), mtmsn) != seen_.end()) return false;
    seen_.push_back(mtmsn);
    if (seen_.size() > kSize) seen_.pop_front();
    return true;
  }

 private:
  std::deque<int> seen_;
};

}  // namespace acomms::drivers::iridium
