#pragma once
// Medium access: when this node may transmit. Acoustic modems share one
// slow, half-duplex channel, so nodes take turns in a TDMA cycle of slots.
//
// A Mac runs on the core thread with time from the Scheduler. At the start
// of a slot it calls the driver's initiate_transmission through `transmit`
// (its src is this node for its own slots, another node's id when a polling
// master asks that node to send). Everything it hears is passed to
// on_receive (the auto-discovery MAC learns the network from it).

#include <functional>
#include <string>
#include <vector>

#include "acomms/v1/modem_transmission.pb.h"
#include "core/scheduler.h"

namespace acomms::mac {

struct Slot {
  int32_t src = 0;           // who transmits
  int32_t dest = -1;         // -1: the queues choose
  int32_t rate = 0;
  double seconds = 10;       // slot length
  v1::ModemTransmission::Type type = v1::ModemTransmission::DATA;
};

using Cycle = std::vector<Slot>;

// What a MAC tells an operator about the network it slots for (LinkStatus):
// each MAC fills it itself, so no caller needs to know which MAC it has.
struct MacStatus {
  std::vector<int32_t> known_ids;  // the nodes it knows of, ascending
  std::string blank_rule;          // its blank-slot rule's name; empty: it has none
};

double cycle_seconds(const Cycle& cycle);

// What a MAC hands the driver at the start of `slot`: src, dest, rate, type
// and slot_seconds from the slot, time = `time_seconds` (the slot start,
// seconds since the Unix epoch).
v1::ModemTransmission slot_transmission(const Slot& slot, double time_seconds);

// Throws std::invalid_argument, naming `what` (e.g. "mac.slot"), unless the
// cycle has at least one slot and every slot a modem id src >= 1 and a
// finite seconds of at least 1 ms (so integer-nanosecond slot times are
// exact and a cycle cannot spin).
void check_cycle(const Cycle& cycle, const std::string& what);

class Mac {
 public:
  using Transmit = std::function<void(const v1::ModemTransmission&)>;
  virtual ~Mac() = default;

  // Begins slotting; `transmit` hands a transmission to the driver.
  virtual void start(Transmit transmit) = 0;
  virtual void stop() = 0;
  // Replaces the cycle; takes effect at the next cycle boundary.
  virtual void set_cycle(const Cycle& cycle) = 0;
  virtual const Cycle& cycle() const = 0;
  // Everything the driver received.
  virtual void on_receive(const v1::ModemTransmission& transmission) = 0;
  // By default the nodes with a slot in cycle() and no blank rule; a MAC
  // that learns the network says what it learned.
  virtual MacStatus status() const;
  // Empty when an operator may replace the cycle (SetCycle); otherwise why
  // not, in words for that operator. Constant for a MAC's life, so any
  // thread may ask.
  virtual std::string cycle_not_settable_reason() const { return {}; }
};

}  // namespace acomms::mac
