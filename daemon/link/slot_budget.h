#pragma once
// How many frames a packet may carry so that it never outruns its slot.
//
// The problem: the rate table says how many frames a packet at a rate can
// hold, not whether they fit in the slot. A full rate-5 packet (8 x 256
// bytes) is about 3.4 s in the water; in a 4 s slot its tail reached a node
// 1 km away after that node's own slot had begun, the half-duplex receiver
// lost it, and a backed-up link delivered nothing for minutes.
//
// The decision: before the queues are asked for frames, the link caps
// max_num_frames at the largest n for which
//
//   air(n) + [ack_time + travel, if an ACK is requested] + travel <= time left
//
// where air(n) is the driver's air time of a DATA packet of n frames at the
// slot's rate, ack_time the driver's turnaround plus ACK air time, travel
// the longest one-way travel time (mac.max_range_m / the driver's sound
// speed; a guard, since the sender cannot know where the others are), and
// the time left is what remains of the slot when the request is made. The
// data's tail has then reached every node in range, and its ACK is back,
// before the next slot begins.
//
// Invariant: frames_that_fit() never exceeds the rate table's limit it is
// given, and is 0 when not even one frame fits (the caller then sends no
// data: a packet that outruns its slot is worse than none).
//
// Thread-safe as the driver it asks: pure arithmetic over the driver's const
// timing figures (air time, ACK time, sound speed).

#include <chrono>
#include <cstdint>
#include <string>

#include "link/driver.h"

namespace acomms::link {

// mac.max_range_m when unset.
inline constexpr double kDefaultMaxRangeM = 2000;

struct SlotBudget {
  int32_t rate = 0;
  std::chrono::nanoseconds time_left{0};
  bool ack_requested = true;
  double max_range_m = kDefaultMaxRangeM;
};

// The longest one-way travel: max_range_m / the driver's sound speed
// (rounded up; zero when either is zero).
std::chrono::nanoseconds travel_time(const Driver& driver, double max_range_m);

// The time a packet of `num_frames` frames takes out of its slot, by the
// formula above.
std::chrono::nanoseconds slot_time_needed(const Driver& driver, const SlotBudget& budget, uint32_t num_frames);

// The largest n <= max_num_frames that fits `budget` (0 if none does).
uint32_t frames_that_fit(const Driver& driver, const SlotBudget& budget, uint32_t max_num_frames);

// Why one frame does not fit, for a person: "one frame needs 4.62 s (air
// 0.75 s, turnaround and ACK 1.32 s, travel 2 x 1.33 s for 2000 m), 4.00 s
// are left".
std::string describe_shortfall(const Driver& driver, const SlotBudget& budget);

}  // namespace acomms::link
