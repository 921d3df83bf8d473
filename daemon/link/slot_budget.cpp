#include "link/slot_budget.h"

#include <cmath>
#include <cstdio>

namespace acomms::link {

namespace {

double seconds(std::chrono::nanoseconds t) { return std::chrono::duration<double>(t).count(); }

}  // namespace

std::chrono::nanoseconds travel_time(const Driver& driver, double max_range_m) {
  double speed = driver.sound_speed();
  if (!(speed > 0) || !(max_range_m > 0)) return std::chrono::nanoseconds(0);
  return std::chrono::nanoseconds(static_cast<int64_t>(std::ceil(max_range_m / speed * 1e9)));
}

std::chrono::nanoseconds slot_time_needed(const Driver& driver, const SlotBudget& budget, uint32_t num_frames) {
  std::chrono::nanoseconds travel = travel_time(driver, budget.max_range_m);
  std::chrono::nanoseconds needed = driver.packet_air_time(budget.rate, num_frames) + travel;
  if (budget.ack_requested) needed += driver.ack_time(budget.rate) + travel;
  return needed;
}

uint32_t frames_that_fit(const Driver& driver, const SlotBudget& budget, uint32_t max_num_frames) {
  // Air time grows with n, so the first n that does not fit ends the search.
  uint32_t n = 0;
  while (n < max_num_frames && slot_time_needed(driver, budget, n + 1) <= budget.time_left) ++n;
  return n;
}

std::string describe_shortfall(const Driver& driver, const SlotBudget& budget) {
  std::chrono::nanoseconds travel = travel_time(driver, budget.max_range_m);
  char text[200];
  std::snprintf(text, sizeof text, "one frame needs %.2f s (air %.2f s", seconds(slot_time_needed(driver, budget, 1)),
                seconds(driver.packet_air_time(budget.rate, 1)));
  std::string out = text;
  if (budget.ack_requested) {
    std::snprintf(text, sizeof text, ", turnaround and ACK %.2f s", seconds(driver.ack_time(budget.rate)));
    out += text;
  }
  std::snprintf(text, sizeof text, ", travel %s%.2f s for %.0f m), %.2f s are left", budget.ack_requested ? "2 x " : "",
                seconds(travel), budget.max_range_m, seconds(budget.time_left));
  out += text;
  return out;
}

}  // namespace acomms::link
