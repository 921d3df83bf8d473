// The slot budget (link/slot_budget.h) with the numbers: a packet's
// air time, its ACK and the sound's travel to mac.max_range_m and back must
// fit in what is left of the slot.

#include "link/slot_budget.h"

#include <gtest/gtest.h>

#include "exact_modem.h"

#include "link/rate_table.h"

namespace acomms::link {
namespace {

using namespace std::chrono_literals;

using testing::ExactModem;

// The defaults: a real modem's estimate, with the margin.
class DefaultModem final : public Driver {
 public:
  void start(DriverCallbacks) override {}
  void stop() override {}
  void do_work() override {}
  void initiate_transmission(const v1::ModemTransmission&) override {}
};

SlotBudget budget(int32_t rate, std::chrono::nanoseconds left, bool ack, double max_range_m = kDefaultMaxRangeM) {
  SlotBudget b;
  b.rate = rate;
  b.time_left = left;
  b.ack_requested = ack;
  b.max_range_m = max_range_m;
  return b;
}

TEST(SlotBudget, TimeNeededIsAirPlusAckPlusTravelThereAndBack) {
  ExactModem modem;
  // Rate 5, 8 frames: 0.3 s + 16384 bits / 5300 bps = 3.391 s in the water;
  // 2000 m at 1500 m/s is 1.333 s each way; turnaround 0.5 s + ACK 0.7 s.
  auto air = link::packet_air_time(*find_rate(5), 8);
  auto travel = 1333333334ns;  // rounded up: a guard never falls short
  EXPECT_EQ(slot_time_needed(modem, budget(5, 0s, false), 8), air + travel);
  EXPECT_EQ(slot_time_needed(modem, budget(5, 0s, true), 8), air + 1200ms + 2 * travel);
  // No range, no travel.
  EXPECT_EQ(slot_time_needed(modem, budget(5, 0s, true, 0), 8), air + 1200ms);
}

TEST(SlotBudget, FourSecondSlotAtRateFiveCannotCarryAFullPacket) {
  ExactModem modem;
  // Without an ACK: 0.3 + n x 0.386 s + 1.333 s <= 4 s holds up to n = 6.
  EXPECT_EQ(frames_that_fit(modem, budget(5, 4s, false), 8), 6u);
  // With one: 0.3 + n x 0.386 + 1.2 + 2.667 > 4 s already for n = 1.
  EXPECT_EQ(frames_that_fit(modem, budget(5, 4s, true), 8), 0u);
  // Even with the others 1 km away at most (max_range_m 1000): 0.3 + n x
  // 0.386 + 1.2 + 2 x 0.667 <= 4 s up to n = 3; never the 8 that used to go.
  EXPECT_EQ(frames_that_fit(modem, budget(5, 4s, true, 1000), 8), 3u);
}

TEST(SlotBudget, EightSecondSlotAtRateFiveCarriesAFullPacketWithItsAck) {
  ExactModem modem;
  // 3.391 + 1.2 + 2.667 = 7.258 s <= 8 s.
  EXPECT_EQ(frames_that_fit(modem, budget(5, 8s, true), 8), 8u);
  // And with a real modem's margin too: 3.730 + 1.32 + 2.667 = 7.717 s.
  EXPECT_EQ(frames_that_fit(DefaultModem(), budget(5, 8s, true), 8), 8u);
}

TEST(SlotBudget, TenSecondSlotsAtRateOneCarryFullPacketsWithinSeventeenHundredMetres) {
  // examples/*.conf: 10 s slots at rate 1 (3 x 64 bytes at 250 bps: 6.444 s
  // in the water), nodes 1.5 km apart, mac.max_range_m 1700: 9.911 s.
  EXPECT_EQ(frames_that_fit(ExactModem(), budget(1, 10s, true, 1700), 3), 3u);
  // The default 2000 m would take a frame: 6.444 + 1.2 + 2.667 > 10 s.
  EXPECT_EQ(frames_that_fit(ExactModem(), budget(1, 10s, true), 3), 2u);
  // The shipped config's suggested 10 s slots at rate 0 (1 x 32 bytes).
  EXPECT_EQ(frames_that_fit(ExactModem(), budget(0, 10s, true), 1), 1u);
}

TEST(SlotBudget, NeverMoreThanTheRateAllowsAndNoneWhenNothingFits) {
  ExactModem modem;
  EXPECT_EQ(frames_that_fit(modem, budget(5, 3600s, true), 8), 8u);
  EXPECT_EQ(frames_that_fit(modem, budget(5, 3600s, true), 3), 3u);
  EXPECT_EQ(frames_that_fit(modem, budget(5, 0s, false, 0), 8), 0u);
  // Exactly enough time is enough.
  auto exact = slot_time_needed(modem, budget(5, 0s, true), 5);
  EXPECT_EQ(frames_that_fit(modem, budget(5, exact, true), 8), 5u);
  EXPECT_EQ(frames_that_fit(modem, budget(5, exact - 1ns, true), 8), 4u);
}

TEST(SlotBudget, ALinkWithoutAirTimeOrTravelKeepsEveryFrame) {
  class Instant final : public Driver {
   public:
    void start(DriverCallbacks) override {}
    void stop() override {}
    void do_work() override {}
    void initiate_transmission(const v1::ModemTransmission&) override {}
    std::chrono::nanoseconds packet_air_time(int32_t, uint32_t) const override { return {}; }
    std::chrono::nanoseconds ack_time(int32_t) const override { return {}; }
    double sound_speed() const override { return 0; }
  };
  EXPECT_EQ(frames_that_fit(Instant(), budget(5, 1s, true), 8), 8u);
}

TEST(SlotBudget, ShortfallSaysWhatOneFrameNeedsAndWhatIsLeft) {
  std::string why = describe_shortfall(ExactModem(), budget(5, 4s, true));
  EXPECT_EQ(why,
            "one frame needs 4.55 s (air 0.69 s, turnaround and ACK 1.20 s, travel 2 x 1.33 s for 2000 m), "
            "4.00 s are left");
}

}  // namespace
}  // namespace acomms::link
