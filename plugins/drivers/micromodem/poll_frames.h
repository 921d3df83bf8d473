#pragma once
// How many frames a poll asks for: `$CCCYC` field 6 (Nframes) of a
// third-party cycle, and the limit a polled node gives its queues
// (spec §5.1, §11).
//
// The problem: on a simulated link the polled node learns the slot from the
// poll and sizes its answer itself (link/slot_budget.h); the Micro-Modem
// carries no slot on the wire, only Nframes. The polled node's answer
// starts one cycle-init mini-packet and one travel time into the master's
// slot, so the master must size Nframes for what is left then, or the
// answer (and its ACK) outruns the slot and collides with the next one.
// The decision: the master asks for the largest n that fits
//   mini-packet + travel + air(n) + ACK + travel + travel <= time left,
// the slot budget's own formula with the poll's head start taken off, and
// the rate's most when the MAC gave no slot; the polled node asks its
// queues for at most Nframes (and at most the rate's most).

#include <chrono>
#include <cstdint>

#include "acomms/v1/modem_transmission.pb.h"
#include "core/clock.h"
#include "link/driver.h"

namespace acomms::drivers::micromodem {

// Nframes for `poll` (rate already checked), asked at `now`; 0 when not
// even one frame fits in what is left of its slot.
uint32_t poll_frames(const link::Driver& driver, const v1::ModemTransmission& poll, core::Clock::time_point now,
                     double max_range_m);

// What a polled node may send for a `$CACYC` asking for `nframes` at `rate`:
// at least 1 (0 on the wire is read as 1, as the fake does), at most the
// rate's most.
uint32_t polled_frames(int32_t rate, int nframes);

}  // namespace acomms::drivers::micromodem
