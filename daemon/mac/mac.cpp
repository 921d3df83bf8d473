#include "mac/mac.h"

#include <cmath>
#include <set>
#include <stdexcept>

namespace acomms::mac {

double cycle_seconds(const Cycle& cycle) {
  double total = 0;
  for (const Slot& slot : cycle) total += slot.seconds;
  return total;
}

v1::ModemTransmission slot_transmission(const Slot& slot, double time_seconds) {
  v1::ModemTransmission transmission;
  transmission.set_src(slot.src);
  transmission.set_dest(slot.dest);
  transmission.set_rate(slot.rate);
  transmission.set_type(slot.type);
  transmission.set_slot_seconds(slot.seconds);
  transmission.set_time(time_seconds);
  return transmission;
}

MacStatus Mac::status() const {
  std::set<int32_t> known;
  for (const Slot& slot : cycle()) {
    if (slot.src > 0) known.insert(slot.src);
  }
  return MacStatus{{known.begin(), known.end()}, ""};
}

void check_cycle(const Cycle& cycle, const std::string& what) {
  if (cycle.empty()) throw std::invalid_argument(what + ": the cycle needs at least one slot");
  for (size_t i = 0; i < cycle.size(); ++i) {
    const Slot& slot = cycle[i];
    const std::string name = what + "[" + std::to_string(i) + "]";
    if (slot.src < 1)
      throw std::invalid_argument(name + ".src must be a modem id >= 1 (0 is broadcast), got " +
                                  std::to_string(slot.src));
    if (!std::isfinite(slot.seconds) || slot.seconds < 1e-3)
      throw std::invalid_argument(name + ".seconds must be positive (at least 0.001 s), got " +
                                  std::to_string(slot.seconds));
    if (slot.dest < -1)
      throw std::invalid_argument(name + ".dest must be a modem id >= 0 or unset, got " +
                                  std::to_string(slot.dest));
  }
}

}  // namespace acomms::mac
