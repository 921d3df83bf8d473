// The MM2 clock at start-up (spec §4.5, §4.6 step 4): `$CCTMS` carrying the
// next UTC second, confirmed by `$CATMS`, whose time-out flag and time are
// checked. A scripted modem answers every setting and says what the test
// wants to `$CCTMS`, which the fake modem (always agreeable) cannot.

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "core/scheduler.h"
#include "link/driver.h"
#include "micromodem/micromodem_driver.h"
#include "micromodem/modem_port.h"
#include "micromodem/nmea/line_framer.h"
#include "micromodem/nmea/sentence.h"
#include "micromodem/nmea/time_sentences.h"

namespace acomms::drivers::micromodem {
namespace {

using namespace std::chrono_literals;
namespace nmea = ::acomms::micromodem;

// An MM2 that boots when the port opens (prints_revision: else it booted
// before and says nothing), echoes every $CCCFG, answers $CCCFQ,SRC,
// refuses $CCCLK unless knows_clk, and answers $CCTMS with whatever
// `answer_time_set` makes of it ("": no answer).
class ScriptedMm2 final : public ModemPort {
 public:
  ScriptedMm2(core::Scheduler& scheduler, std::function<std::string(const nmea::TimeSet&)> answer_time_set)
      : scheduler_(scheduler), answer_time_set_(std::move(answer_time_set)) {}
  void open(DataCallback on_data, link::TransportStateCallback on_state) override {
    on_data_ = std::make_shared<DataCallback>(std::move(on_data));
    on_state(link::TransportState::kOpen, name());
    if (!prints_revision) return;
    say("$CAREV,000000,INIT,2.0.27087");
    say("$CAREV,000001,AUV,2.0.27087");
  }
  void close() override { on_data_.reset(); }
  bool write(std::string_view bytes) override {
    for (const std::string& line : framer_.push(bytes)) {
      auto s = nmea::parse_sentence(line);
      if (!s) continue;
      if (s->is("CCCFG")) say(nmea::serialize({"CA", "CFG", s->fields}));
      if (s->is("CCCFQ") && s->field(1) == "SRC") say("$CACFG,SRC,1");
      if (s->is("CCCLK")) {
        ++clock_sets;
        if (knows_clk) say(nmea::serialize({"CA", "CLK", s->fields}));
        if (!knows_clk) say("$CAERR,000000,NMEA,3,Unknown command CCCLK");
      }
      if (s->is("CCTMS")) {
        ++time_sets;
        sent = line;
        auto set = nmea::parse_time_set(*s);
        if (set && !answer_time_set_(*set).empty()) say(answer_time_set_(*set));
      }
    }
    return true;
  }
  std::string name() const override { return "scripted MM2"; }

  bool prints_revision = true;
  bool knows_clk = true;
  int clock_sets = 0;
  int time_sets = 0;
  std::string sent;  // the last $CCTMS line

 private:
  void say(const std::string& line) {
    std::string bytes = line.find('*') == std::string::npos ? nmea::serialize(*nmea::parse_sentence(line, nmea::ChecksumRule::kOptional)) : line;
    std::weak_ptr<DataCallback> target = on_data_;
    scheduler_.after(20ms, [target, bytes] {
      if (auto callback = target.lock()) (*callback)(bytes + "\r\n");
    });
  }
  core::Scheduler& scheduler_;
  std::function<std::string(const nmea::TimeSet&)> answer_time_set_;
  std::shared_ptr<DataCallback> on_data_;
  nmea::LineFramer framer_;
};

class MicroModemClockTest : public ::testing::Test {
 protected:
  // Starts a driver on a scripted MM2; runs up to 20 s. "" once ready, or
  // the DriverError's text.
  std::string start_up(std::function<std::string(const nmea::TimeSet&)> answer, bool prints_revision = true,
                       bool knows_clk = true) {
    v1::DriverConfig config;
    config.set_name("micromodem");
    config.set_modem_id(1);
    config.mutable_micromodem()->set_command_timeout_s(1);
    auto port = std::make_unique<ScriptedMm2>(scheduler_, std::move(answer));
    modem_ = port.get();
    modem_->prints_revision = prints_revision;
    modem_->knows_clk = knows_clk;
    driver_ = std::make_unique<MicroModemDriver>(config, scheduler_, std::move(port));
    driver_->start({});
    try {
      for (int i = 0; i < 100 && !driver_->ready(); ++i) {
        scheduler_.run_for(200ms);
        driver_->do_work();
      }
    } catch (const link::DriverError& e) {
      return e.what();
    }
    return driver_->ready() ? "" : "neither ready nor failed";
  }
  static std::string reply(bool timed_out, const nmea::ClockTime& time) {
    return nmea::serialize(nmea::to_sentence(nmea::TimeSetReply{timed_out, time}));
  }

  core::SimulatedScheduler scheduler_{core::Clock::time_point(std::chrono::milliseconds(1'700'000'000'300))};
  ScriptedMm2* modem_ = nullptr;
  std::unique_ptr<MicroModemDriver> driver_;
};

TEST_F(MicroModemClockTest, TheNextUtcSecondIsSentJustAfterASecondBoundaryAndTheConfirmationMakesItReady) {
  nmea::TimeSet seen;
  EXPECT_EQ(start_up([&](const nmea::TimeSet& set) {
              seen = set;
              return reply(false, set.time);
            }),
            "");
  ASSERT_EQ(modem_->time_sets, 1);
  EXPECT_EQ(seen.mode, 0) << "no external pulse";
  // 1'700'000'000 s is 2023-11-14T22:13:20Z; the settings take ~0.2 s,
  // so the command goes at 22:13:21.05 carrying 22:13:22.
  EXPECT_EQ(nmea::iso_time_text(seen.time), "2023-11-14T22:13:22Z");
  EXPECT_EQ(modem_->sent, "$CCTMS,2023-11-14T22:13:22Z,0*" + modem_->sent.substr(modem_->sent.size() - 2));
}

TEST_F(MicroModemClockTest, ACatmsThatReportsATimeOutIsAStartUpError) {
  std::string error = start_up([](const nmea::TimeSet& set) { return reply(true, set.time); });
  EXPECT_NE(error.find("the clock was not set: $CATMS reports a time-out"), std::string::npos) << error;
  EXPECT_FALSE(driver_->ready());
}

TEST_F(MicroModemClockTest, AModemThatKeepsAnotherTimeIsAStartUpErrorNamingBothTimes) {
  std::string error = start_up([](const nmea::TimeSet&) { return reply(false, nmea::ClockTime{}); });
  EXPECT_NE(error.find("sent 2023-11-14T22:13:22Z, the modem keeps 1970-01-01T00:00:00Z"), std::string::npos)
      << error;
}

TEST_F(MicroModemClockTest, AConfirmationWithinTwoSecondsIsAccepted) {
  EXPECT_EQ(start_up([](const nmea::TimeSet& set) {
              nmea::ClockTime earlier = set.time;
              earlier.second -= 2;  // 22:13:20: the modem answered before applying the next second
              return reply(false, earlier);
            }),
            "");
}

TEST_F(MicroModemClockTest, NoConfirmationAtAllIsAStartUpErrorNamingTheCommand) {
  std::string error = start_up([](const nmea::TimeSet&) { return std::string(); });
  EXPECT_NE(error.find("the clock was not set ($CCTMS)"), std::string::npos) << error;
  EXPECT_EQ(modem_->time_sets, 3) << "tried three times";
}

TEST_F(MicroModemClockTest, AModemThatPrintedNoRevisionGetsCcclkThenCctmsWhenItRefusesCcclk) {
  auto agree = [](const nmea::TimeSet& set) { return reply(false, set.time); };
  EXPECT_EQ(start_up(agree, /*prints_revision=*/false, /*knows_clk=*/false), "");
  EXPECT_EQ(modem_->clock_sets, 1) << "refused with $CAERR NMEA: not tried again";
  EXPECT_EQ(modem_->time_sets, 1);
}

TEST_F(MicroModemClockTest, AModemThatPrintedNoRevisionAndTakesCcclkIsNotSentCctms) {
  auto agree = [](const nmea::TimeSet& set) { return reply(false, set.time); };
  EXPECT_EQ(start_up(agree, /*prints_revision=*/false, /*knows_clk=*/true), "");
  EXPECT_EQ(modem_->clock_sets, 1);
  EXPECT_EQ(modem_->time_sets, 0);
}

}  // namespace
}  // namespace acomms::drivers::micromodem
