// `acommsd --check-config`'s slot warnings (link/slot_check.h): one line per
// slot that cannot carry one frame at its rate, naming it.

#include "link/slot_check.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include "../link/exact_modem.h"

#include "link/rate_table.h"

namespace acomms::link {
namespace {

using testing::ExactModem;

v1::MacConfig mac(const std::string& text) {
  v1::MacConfig config;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &config)) << text;
  return config;
}

TEST(SlotCheck, OneLineForEachSlotThatCannotCarryOneFrame) {
  std::vector<std::string> warnings = short_slot_warnings(
      mac("name: 'fixed' slot { src: 1 rate: 5 seconds: 8 } slot { src: 2 rate: 5 seconds: 4 } "
          "slot { src: 3 rate: 0 seconds: 7 }"),
      ExactModem());
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0],
            "mac slot 2 (src 2, rate 5, 4 s) cannot carry one frame: one frame needs 4.55 s (air 0.69 s, "
            "turnaround and ACK 1.20 s, travel 2 x 1.33 s for 2000 m), 4.00 s are left");
  // Rate 0: 3.5 s of air for its one frame.
  EXPECT_EQ(warnings[1].rfind("mac slot 3 (src 3, rate 0, 7 s) cannot carry one frame: one frame needs 7.37 s", 0),
            0u)
      << warnings[1];
}

TEST(SlotCheck, TheRangeDecides) {
  const std::string slots = "name: 'polled' slot { src: 1 rate: 5 seconds: 4 } slot { src: 2 rate: 5 seconds: 4 }";
  EXPECT_EQ(short_slot_warnings(mac(slots), ExactModem()).size(), 2u);
  EXPECT_TRUE(short_slot_warnings(mac(slots + " max_range_m: 1000"), ExactModem()).empty());
  EXPECT_THROW(short_slot_warnings(mac(slots + " max_range_m: -5"), ExactModem()), std::invalid_argument);
}

TEST(SlotCheck, AutoDiscoverySlotsAreOneLine) {
  std::vector<std::string> warnings =
      short_slot_warnings(mac("name: 'auto_discovery' slot_seconds: 3 rate: 1 coolness: 3 expire_cycles: 5"),
                          ExactModem());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].rfind("mac auto_discovery slots (rate 1, 3 s) cannot carry one frame: ", 0), 0u)
      << warnings[0];
  EXPECT_TRUE(short_slot_warnings(mac("name: 'auto_discovery' slot_seconds: 15 rate: 0 coolness: 3 "
                                      "expire_cycles: 5"),
                                  ExactModem())
                  .empty());
}

TEST(SlotCheck, NoneAndUnknownRatesAreNotWarnedAbout) {
  EXPECT_TRUE(short_slot_warnings(mac("name: 'none'"), ExactModem()).empty());
  // A rate outside 0..5 is the MAC's and the driver's error, not a short slot.
  EXPECT_TRUE(short_slot_warnings(mac("name: 'fixed' slot { src: 1 rate: 9 seconds: 1 }"), ExactModem()).empty());
}

TEST(SlotCheck, ConfigsDriverGivesTheTimingOrARealModemsDefaults) {
  v1::Config config;
  *config.mutable_mac() = mac("name: 'fixed' slot { src: 1 rate: 5 seconds: 4.7 } max_range_m: 1000");
  // No driver of that name here: the defaults (rate table + 10 %) need
  // 0.755 + 1.32 + 1.333 = 3.41 s for one frame: it fits.
  config.mutable_driver()->set_name("nonesuch");
  EXPECT_TRUE(short_slot_warnings(config, DriverRegistry()).empty());
  *config.mutable_mac() = mac("name: 'fixed' slot { src: 1 rate: 5 seconds: 3.3 } max_range_m: 1000");
  EXPECT_EQ(short_slot_warnings(config, DriverRegistry()).size(), 1u);
  // The registry's driver gives its own: one that says nothing takes time.
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
  DriverRegistry registry;
  registry.add("nonesuch", [](const DriverContext&) -> std::unique_ptr<Driver> { return std::make_unique<Instant>(); });
  EXPECT_TRUE(short_slot_warnings(config, registry).empty());
}

}  // namespace
}  // namespace acomms::link
