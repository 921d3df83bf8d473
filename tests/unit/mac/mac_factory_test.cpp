// make_mac: the right MAC for each name, and clear errors for bad configs;
// each MAC reports its own status through the Mac interface.

#include "mac/mac_factory.h"

#include <gtest/gtest.h>

#include <google/protobuf/text_format.h>

#include "mac/auto_discovery_mac.h"
#include "mac/fixed_mac.h"
#include "mac/polled_mac.h"
#include "mac/silent_mac.h"
#include "mac_test_util.h"

namespace acomms::mac {
namespace {

using namespace testing;

v1::MacConfig parse(const std::string& text) {
  v1::MacConfig config;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &config)) << text;
  return config;
}

// The message of the std::invalid_argument make_mac throws ("" if none).
std::string error_of(const std::string& text, int32_t own_id = 1) {
  core::SimulatedScheduler scheduler(day_s(0));
  try {
    make_mac(parse(text), own_id, scheduler);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// A config that names no blank rule gets the one that converges; each name
// picks its rule, so a fleet can keep "figure" while it upgrades.
TEST(MacFactory, AutoDiscoveryBlankRuleDefaultsToAnywhereAndEachNamePicksItsRule) {
  core::SimulatedScheduler scheduler(day_s(0));
  auto rule_of = [&](const std::string& extra) {
    std::unique_ptr<Mac> mac = make_mac(
        parse("name: 'auto_discovery' slot_seconds: 15 coolness: 4 expire_cycles: 5 " + extra), 1, scheduler);
    return dynamic_cast<AutoDiscoveryMac&>(*mac).blank_rule();
  };
  EXPECT_EQ(rule_of(""), BlankRule::kAnywhere);
  EXPECT_EQ(rule_of("blank_rule: 'anywhere'"), BlankRule::kAnywhere);
  EXPECT_EQ(rule_of("blank_rule: 'figure'"), BlankRule::kFigure);
  EXPECT_EQ(rule_of("blank_rule: 'congruence'"), BlankRule::kCongruence);
}

// LinkStatus asks any MAC through Mac::status(), never by its kind: a
// configured cycle reports the nodes with a slot, auto-discovery the nodes it
// has heard (itself included) and its blank rule, "none" nothing.
TEST(MacFactory, EachMacReportsItsOwnStatusThroughTheInterface) {
  core::SimulatedScheduler scheduler(day_s(0));
  const std::string slots = "slot { src: 3 seconds: 10 } slot { src: 1 dest: 3 seconds: 5 } slot { src: 3 seconds: 5 }";
  for (const char* name : {"fixed", "polled"}) {
    std::unique_ptr<Mac> mac = make_mac(parse(std::string("name: '") + name + "' " + slots), 1, scheduler);
    const MacStatus status = mac->status();
    EXPECT_EQ(status.known_ids, (std::vector<int32_t>{1, 3})) << name;
    EXPECT_EQ(status.blank_rule, "") << name;
  }
  EXPECT_TRUE(make_mac(parse("name: 'none'"), 1, scheduler)->status().known_ids.empty());

  std::unique_ptr<Mac> discovery = make_mac(
      parse("name: 'auto_discovery' slot_seconds: 15 coolness: 4 expire_cycles: 5 blank_rule: 'figure'"), 4,
      scheduler);
  EXPECT_EQ(discovery->status().known_ids, (std::vector<int32_t>{4}));
  EXPECT_EQ(discovery->status().blank_rule, "figure");
  discovery->start([](const v1::ModemTransmission&) {});
  v1::ModemTransmission heard;
  heard.set_src(7);
  discovery->on_receive(heard);
  heard.set_src(2);
  discovery->on_receive(heard);
  EXPECT_EQ(discovery->status().known_ids, (std::vector<int32_t>{2, 4, 7}));
  discovery->stop();
}

// SetCycle asks the MAC whether its cycle can be replaced, never its name:
// a configured cycle can; "none" (nothing to slot) and auto-discovery (the
// cycle is what it learned) say why not, naming themselves.
TEST(MacFactory, EachMacSaysWhetherAnOperatorMaySetItsCycle) {
  core::SimulatedScheduler scheduler(day_s(0));
  auto reason = [&](const std::string& text) { return make_mac(parse(text), 1, scheduler)->cycle_not_settable_reason(); };
  const std::string slots = "slot { src: 1 seconds: 10 }";
  EXPECT_EQ(reason("name: 'fixed' " + slots), "");
  EXPECT_EQ(reason("name: 'polled' " + slots), "");
  EXPECT_NE(reason("name: 'none'").find("MAC is \"none\""), std::string::npos) << reason("name: 'none'");
  EXPECT_NE(reason("").find("MAC is \"none\""), std::string::npos);
  const std::string discovery = reason("name: 'auto_discovery' slot_seconds: 15 coolness: 4 expire_cycles: 5");
  EXPECT_NE(discovery.find("\"auto_discovery\" MAC builds its cycle"), std::string::npos) << discovery;
}

TEST(MacFactory, BuildsEachKind) {
  core::SimulatedScheduler scheduler(day_s(0));
  const std::string slots = "slot { src: 1 seconds: 10 } slot { src: 2 dest: 1 rate: 3 seconds: 5 }";
  EXPECT_NE(dynamic_cast<PolledMac*>(make_mac(parse("name: 'polled' " + slots), 1, scheduler).get()),
            nullptr);
  EXPECT_NE(dynamic_cast<FixedMac*>(make_mac(parse("name: 'fixed' " + slots), 1, scheduler).get()),
            nullptr);
  EXPECT_NE(dynamic_cast<AutoDiscoveryMac*>(
                make_mac(parse("name: 'auto_discovery' slot_seconds: 15 coolness: 4 "
                               "expire_cycles: 5 blank_rule: 'anywhere'"),
                         1, scheduler)
                    .get()),
            nullptr);
  EXPECT_NE(dynamic_cast<SilentMac*>(make_mac(parse("name: 'none'"), 1, scheduler).get()), nullptr);
  EXPECT_NE(dynamic_cast<SilentMac*>(make_mac(parse(""), 1, scheduler).get()), nullptr);

  std::unique_ptr<Mac> fixed = make_mac(parse("name: 'fixed' " + slots), 1, scheduler);
  ASSERT_EQ(fixed->cycle().size(), 2u);
  EXPECT_EQ(fixed->cycle()[0].dest, -1);  // unset: the queues choose
  EXPECT_EQ(fixed->cycle()[1].dest, 1);
  EXPECT_EQ(fixed->cycle()[1].rate, 3);
  EXPECT_EQ(fixed->cycle()[1].seconds, 5);
}

TEST(MacFactory, SilentNeverTransmits) {
  core::SimulatedScheduler scheduler(day_s(0));
  FakeDriver driver(scheduler);
  std::unique_ptr<Mac> mac = make_mac(parse("name: 'none'"), 1, scheduler);
  mac->start(driver.transmit());
  scheduler.run_until(day_s(1000));
  EXPECT_TRUE(driver.sent.empty());
}

TEST(MacFactory, MaxRangeMustBeAFiniteDistance) {
  const std::string negative = error_of("name: 'fixed' slot { src: 1 seconds: 10 } max_range_m: -1");
  EXPECT_NE(negative.find("mac.max_range_m must be a finite number of metres >= 0"), std::string::npos) << negative;
  EXPECT_NE(error_of("name: 'none' max_range_m: inf").find("mac.max_range_m"), std::string::npos);
  EXPECT_EQ(error_of("name: 'fixed' slot { src: 1 seconds: 10 } max_range_m: 0"), "");
  EXPECT_EQ(error_of("name: 'fixed' slot { src: 1 seconds: 10 } max_range_m: 3000"), "");
}

TEST(MacFactory, ClearErrors) {
  const std::string unknown = error_of("name: 'aloha'");
  EXPECT_NE(unknown.find("\"aloha\" is unknown"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("\"auto_discovery\", \"fixed\", \"none\", \"polled\""), std::string::npos)
      << unknown;

  EXPECT_NE(error_of("name: 'fixed'").find("at least one slot"), std::string::npos);
  EXPECT_NE(error_of("name: 'polled'").find("at least one slot"), std::string::npos);
  const std::string zero = error_of("name: 'fixed' slot { src: 1 seconds: 0 }");
  EXPECT_NE(zero.find("mac.slot[0].seconds must be positive"), std::string::npos) << zero;
  EXPECT_NE(error_of("name: 'polled' slot { src: 1 seconds: -3 }").find("must be positive"),
            std::string::npos);
  EXPECT_NE(error_of("name: 'polled' slot { src: 1 seconds: 1 } slot { src: 0 seconds: 1 }")
                .find("mac.slot[1].src"),
            std::string::npos);
  EXPECT_NE(error_of("name: 'fixed' slot { src: 1 seconds: 90000 }").find("set mac.epoch"),
            std::string::npos);
  EXPECT_EQ(error_of("name: 'fixed' slot { src: 1 seconds: 90000 } epoch: 0"), "");
  EXPECT_NE(error_of("name: 'fixed' slot { src: 1 seconds: 10 }", 0).find("modem id"),
            std::string::npos);

  EXPECT_NE(error_of("name: 'auto_discovery' coolness: 3 expire_cycles: 5")
                .find("mac.slot_seconds must be positive"),
            std::string::npos);
  EXPECT_NE(error_of("name: 'auto_discovery' slot_seconds: 10 expire_cycles: 5").find("mac.coolness"),
            std::string::npos);
  EXPECT_NE(error_of("name: 'auto_discovery' slot_seconds: 10 coolness: 3").find("mac.expire_cycles"),
            std::string::npos);
  EXPECT_NE(error_of("name: 'auto_discovery' slot_seconds: 10 coolness: 3 expire_cycles: 5 "
                     "blank_rule: 'middle'")
                .find("mac.blank_rule \"middle\" is unknown"),
            std::string::npos);
  EXPECT_NE(error_of("name: 'auto_discovery' slot_seconds: 10 coolness: 3 expire_cycles: 5 "
                     "slot { src: 1 seconds: 1 }")
                .find("mac.slot is not used"),
            std::string::npos);
}

TEST(MacFactory, SetCycleErrors) {
  core::SimulatedScheduler scheduler(day_s(0));
  std::unique_ptr<Mac> fixed =
      make_mac(parse("name: 'fixed' slot { src: 1 seconds: 10 }"), 1, scheduler);
  EXPECT_THROW(fixed->set_cycle({}), std::invalid_argument);
  std::unique_ptr<Mac> auto_mac = make_mac(
      parse("name: 'auto_discovery' slot_seconds: 10 coolness: 3 expire_cycles: 5"), 1, scheduler);
  try {
    auto_mac->set_cycle({slot(1, 10)});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"fixed\""), std::string::npos);
  }
}

}  // namespace
}  // namespace acomms::mac
