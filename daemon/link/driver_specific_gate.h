#pragma once
// The slot rule for driver-specific transmissions (link/driver_specific.h).
//
// The problem: a ping, an LBL interrogation or a mini-packet is sound in
// the water like any packet. Sent whenever a client asks, it would land in
// another node's slot and cost that node its reception: an extra must never
// break the MAC's timing.
//
// The rule: an extra goes out only when the channel is this node's: at the
// start of one of its own slots (the slot carries the extra instead of
// data), or, for a node with no slot of its own (MAC "none", a node the
// polled master polls), when a poll gives it the channel (the poll is
// answered with one blank frame and the extra follows once that answer has
// cleared the water: the sound's travel to mac.max_range_m plus an ACK's
// time, so the poller is not still hearing it). Until then
// the request waits here, oldest first; the wait counts against its
// deadline, and a request whose deadline passes while it waits fails with
// kDeadlineExceeded saying it never got the channel. What is left of the
// deadline goes to the driver for the exchange itself.
//
// Core thread only.

#include <cstdint>
#include <deque>

#include "core/clock.h"
#include "core/scheduler.h"
#include "link/driver.h"

namespace acomms::link {

class DriverSpecificGate {
 public:
  // `scheduler` runs the deadlines (null: they are checked only when the
  // channel comes, as in tests that drive the controller by hand).
  DriverSpecificGate(const core::Clock* clock, core::Scheduler* scheduler);
  ~DriverSpecificGate();
  DriverSpecificGate(const DriverSpecificGate&) = delete;
  DriverSpecificGate& operator=(const DriverSpecificGate&) = delete;

  // A checked request waits for the channel; `done` runs exactly once.
  void wait(v1::ModemTransmission request, double deadline_s, DriverSpecificDone done);
  bool waiting() const { return !waiting_.empty(); }
  // The channel is this node's: the oldest request still in time goes to
  // `driver` (`how` says why, for the log). Returns whether one went.
  bool send_next(Driver& driver, const char* how);
  // Fails every waiting request (the link stops).
  void abort(const std::string& why);

 private:
  struct Waiting {
    uint64_t id = 0;
    v1::ModemTransmission request;
    double since_s = 0;
    double deadline_s = 0;
    DriverSpecificDone done;
    core::Scheduler::TaskId timer = 0;
  };
  double now_s() const;
  void expire(uint64_t id);

  const core::Clock* clock_;
  core::Scheduler* scheduler_;
  std::deque<Waiting> waiting_;
  uint64_t next_id_ = 1;
};

}  // namespace acomms::link
