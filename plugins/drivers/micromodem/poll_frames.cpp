#include "micromodem/poll_frames.h"

#include <algorithm>
#include <cmath>

#include "link/rate_table.h"
#include "link/slot_budget.h"

namespace acomms::drivers::micromodem {

uint32_t poll_frames(const link::Driver& driver, const v1::ModemTransmission& poll, core::Clock::time_point now,
                     double max_range_m) {
  using std::chrono::nanoseconds;
  const link::ModemRate* rate = link::find_rate(poll.rate());
  if (rate == nullptr) return 0;
  uint32_t most = rate->max_num_frames;
  if (poll.max_num_frames() > 0) most = std::min(most, poll.max_num_frames());
  if (!(poll.slot_seconds() > 0)) return most;  // no slot given: nothing to budget
  auto left = nanoseconds(std::llround(poll.slot_seconds() * 1e9));
  if (poll.time() > 0) {
    auto start = nanoseconds(std::llround(poll.time() * 1e9));
    auto elapsed = std::chrono::duration_cast<nanoseconds>(now.time_since_epoch()) - start;
    if (elapsed > nanoseconds(0)) left -= elapsed;
  }
  // First the poll's cycle-init mini-packet, its way to the polled node
  // and that node's turnaround: a mini-packet and a turnaround, which is
  // what the driver's ack_time() is, margin included.
  nanoseconds head_start = driver.ack_time(poll.rate()) + link::travel_time(driver, max_range_m);
  link::SlotBudget budget;
  budget.rate = poll.rate();
  budget.time_left = std::max(nanoseconds(0), left - head_start);
  budget.ack_requested = true;  // a poll always asks for ACKs (§5.1)
  budget.max_range_m = max_range_m;
  return link::frames_that_fit(driver, budget, most);
}

uint32_t polled_frames(int32_t rate, int nframes) {
  const link::ModemRate* found = link::find_rate(rate);
  uint32_t most = found == nullptr ? 1 : found->max_num_frames;
  return std::clamp<uint32_t>(static_cast<uint32_t>(std::max(1, nframes)), 1, most);
}

}  // namespace acomms::drivers::micromodem
