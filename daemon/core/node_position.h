#pragma once
// Where this node is now: the newest navigation fix (SubmitNavigation), in
// the local metres of the telemetry datum (x east, y north, z up).
//
// Written by telemetry (the navigation input) and read by whoever needs the
// vehicle's position without caring where it came from: the simulator
// driver places its modem there, so a moving simulated vehicle needs no
// other input, and a later physical channel model can read depth the same
// way. A small value under a mutex: writers and readers may be on any
// thread (telemetry on the core thread, a driver on its own).

#include <mutex>
#include <optional>

namespace acomms::core {

struct NodeFix {
  double time_s = 0;  // seconds since the Unix epoch
  double x = 0, y = 0, z = 0;
};

class NodePosition {
 public:
  void set(const NodeFix& fix) {
    std::lock_guard lock(mutex_);
    latest_ = fix;
  }
  // The newest fix; nullopt before the first.
  std::optional<NodeFix> latest() const {
    std::lock_guard lock(mutex_);
    return latest_;
  }

 private:
  mutable std::mutex mutex_;
  std::optional<NodeFix> latest_;
};

}  // namespace acomms::core
