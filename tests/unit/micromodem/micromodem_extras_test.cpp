// The micromodem driver's driver-specific transmissions (ping, narrowband
// and REMUS LBL, 13-bit mini-packets, MM2 FDP) against fake Micro-Modems
// on simulated time: results from the fake's geometry, the refusals a
// client must see at once, and what the other node's driver reports.

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "acomms/drivers/micromodem_transmission.pb.h"
#include "fake_micromodem.h"
#include "fake_modem_port.h"
#include "link/driver.h"
#include "micromodem/micromodem_driver.h"

namespace acomms::fake_micromodem {
namespace {

using namespace std::chrono_literals;
using drivers::MicroModemTransmission;
using drivers::micromodem::MicroModemDriver;
using link::DriverSpecificResult;
using link::DriverSpecificStatus;
using v1::ModemTransmission;

constexpr double kStart = 1'700'000'000;

struct Node {
  Node(Water& water, core::Scheduler& scheduler, int id, Generation generation, Position position,
       std::vector<std::string> cfg = {})
      : modem(water, [&] {
          FakeModemConfig c;
          c.address = id;
          c.generation = generation;
          c.position = position;
          return c;
        }()) {
    config.set_name("micromodem");
    config.set_modem_id(static_cast<uint32_t>(id));
    config.mutable_micromodem()->set_max_range_m(3000);
    for (const std::string& entry : cfg) config.mutable_micromodem()->add_cfg(entry);
    driver = std::make_unique<MicroModemDriver>(config, scheduler,
                                                std::make_unique<FakeModemPort>(modem, scheduler, &written));
  }
  void start() {
    link::DriverCallbacks callbacks;
    callbacks.on_receive = [this](const ModemTransmission& tx) { received.push_back(tx); };
    callbacks.on_data_request = [](ModemTransmission*) {};
    callbacks.on_transmit_result = [](const ModemTransmission&, bool, const std::string&) {};
    driver->start(std::move(callbacks));
    modem.power_on();
  }
  std::vector<ModemTransmission> received_driver_specific() const {
    std::vector<ModemTransmission> out;
    for (const auto& tx : received) {
      if (tx.type() == ModemTransmission::DRIVER_SPECIFIC) out.push_back(tx);
    }
    return out;
  }

  FakeMicroModem modem;
  v1::DriverConfig config;
  std::string written;
  std::unique_ptr<MicroModemDriver> driver;
  std::vector<ModemTransmission> received;
};

ModemTransmission request(int dest, MicroModemTransmission ask) {
  ModemTransmission tx;
  tx.set_type(ModemTransmission::DRIVER_SPECIFIC);
  tx.set_src(1);
  tx.set_dest(dest);
  *tx.MutableExtension(drivers::micromodem_transmission) = std::move(ask);
  return tx;
}

MicroModemTransmission kind(MicroModemTransmission::Kind k) {
  MicroModemTransmission ask;
  ask.set_kind(k);
  return ask;
}

class MicroModemExtrasTest : public ::testing::Test {
 protected:
  void run(Duration d) {
    auto until = scheduler_.clock().now() + d;
    while (scheduler_.clock().now() < until) {
      scheduler_.run_for(100ms);
      for (Node* node : nodes_) node->driver->do_work();
    }
  }
  // Node 1 at the origin, node 2 at (x, 0, 0).
  void two_nodes(Generation a = Generation::kMM2, Generation b = Generation::kMM2, std::vector<std::string> cfg = {},
                 double x = 1500) {
    a_ = std::make_unique<Node>(water_, scheduler_, 1, a, Position{0, 0, 0}, cfg);
    b_ = std::make_unique<Node>(water_, scheduler_, 2, b, Position{x, 0, 0}, cfg);
    nodes_ = {a_.get(), b_.get()};
    for (Node* node : nodes_) node->start();
    run(8s);
    ASSERT_TRUE(a_->driver->ready());
    ASSERT_TRUE(b_->driver->ready());
  }
  // Node 1 an MM2 set up for FDP, node 2 an MM1 it has not been told of.
  void mm2_and_unlisted_mm1() {
    two_nodes(Generation::kMM2, Generation::kMM1, {});
    // Only node 1 needs (and an MM1 refuses) the MM2 header setting.
    a_->config.mutable_micromodem()->add_cfg("psk.packet.mod_hdr_version,1");
    a_->driver = std::make_unique<MicroModemDriver>(
        a_->config, scheduler_, std::make_unique<FakeModemPort>(a_->modem, scheduler_, &a_->written));
    a_->start();
    run(8s);
    ASSERT_TRUE(a_->driver->ready());
  }
  // Checks then sends from node 1; runs until it is done (at most `limit`).
  DriverSpecificResult send(const ModemTransmission& tx, Duration limit = 30s) {
    DriverSpecificResult checked = a_->driver->check_driver_specific(tx);
    if (checked.status != DriverSpecificStatus::kOk) return checked;
    std::optional<DriverSpecificResult> result;
    double deadline = scheduler_.clock().now_seconds() + std::chrono::duration<double>(limit).count();
    a_->driver->send_driver_specific(tx, deadline, [&](DriverSpecificResult r) { result = std::move(r); });
    auto until = scheduler_.clock().now() + limit + 1s;
    while (!result && scheduler_.clock().now() < until) run(100ms);
    EXPECT_TRUE(result.has_value()) << "no result within " << std::chrono::duration<double>(limit).count() << " s";
    return result.value_or(DriverSpecificResult{DriverSpecificStatus::kAborted, "no result", tx});
  }

  core::SimulatedScheduler scheduler_{core::Clock::time_point(std::chrono::seconds(1'700'000'000))};
  Water::Settings settings_ = [] {
    Water::Settings s{1500, 0, 1, {}};
    // Narrowband: A 26 kHz 750 m away (0.5 s), B 27 kHz 1500 m (1.0 s),
    // C 28 kHz never answers. REMUS: A 300 m (0.2 s), B never answers.
    s.transponders.push_back({Transponder::Kind::kNarrowband, 26000, 'A', {0, 750, 0}, true, 50ms});
    s.transponders.push_back({Transponder::Kind::kNarrowband, 27000, 'B', {-900, 0, 1200}, true, 50ms});
    s.transponders.push_back({Transponder::Kind::kNarrowband, 28000, 'C', {0, 100, 0}, false, 50ms});
    s.transponders.push_back({Transponder::Kind::kRemus, 0, 'A', {0, 0, 300}, true, 50ms});
    s.transponders.push_back({Transponder::Kind::kRemus, 0, 'B', {0, 200, 0}, false, 50ms});
    return s;
  }();
  Water water_{scheduler_, settings_};
  std::unique_ptr<Node> a_, b_;
  std::vector<Node*> nodes_;
};

TEST_F(MicroModemExtrasTest, PingGivesTheOneWayTravelTimeOfTheGeometryAndItsRange) {
  two_nodes(Generation::kMM2, Generation::kMM1, {}, 1234);
  DriverSpecificResult result = send(request(2, kind(MicroModemTransmission::PING)));
  ASSERT_EQ(result.status, DriverSpecificStatus::kOk) << result.error;
  const auto& answer = result.transmission.GetExtension(drivers::micromodem_transmission);
  EXPECT_NEAR(answer.travel_time_s(), 1234.0 / 1500, 0.002);
  EXPECT_NEAR(answer.range_m(), 1234, 3);
  EXPECT_NE(a_->written.find("$CCMPC,1,2*"), std::string::npos);
}

TEST_F(MicroModemExtrasTest, PingToAModemThatIsNotThereTimesOutAfterTheSpecsTime) {
  two_nodes();
  auto started = scheduler_.clock().now();
  DriverSpecificResult result = send(request(9, kind(MicroModemTransmission::PING)), 60s);
  EXPECT_EQ(result.status, DriverSpecificStatus::kDeadlineExceeded);
  EXPECT_NE(result.error.find("$CCMPC"), std::string::npos) << result.error;
  // 2 x 3000 m / 1500 m/s + 3 s = 7 s after the echo.
  double took = std::chrono::duration<double>(scheduler_.clock().now() - started).count();
  EXPECT_GT(took, 7.0);
  EXPECT_LT(took, 8.5);
}

TEST_F(MicroModemExtrasTest, NarrowbandLblGivesEachTransponderItsTravelTimeAndNamesTheSilentOne) {
  two_nodes();
  MicroModemTransmission ask = kind(MicroModemTransmission::NARROWBAND_LBL);
  ask.mutable_narrowband_lbl()->add_reply_frequency_hz(26000);
  ask.mutable_narrowband_lbl()->add_reply_frequency_hz(27000);
  ask.mutable_narrowband_lbl()->add_reply_frequency_hz(28000);
  ask.mutable_narrowband_lbl()->set_timeout_ms(4000);
  DriverSpecificResult result = send(request(0, ask));
  ASSERT_EQ(result.status, DriverSpecificStatus::kOk) << result.error;
  const auto& answer = result.transmission.GetExtension(drivers::micromodem_transmission);
  ASSERT_EQ(answer.lbl_reply_size(), 3);
  EXPECT_EQ(answer.lbl_reply(0).transponder(), "A");
  EXPECT_TRUE(answer.lbl_reply(0).answered());
  EXPECT_NEAR(answer.lbl_reply(0).travel_time_s(), 0.5, 0.001);
  EXPECT_TRUE(answer.lbl_reply(1).answered());
  EXPECT_NEAR(answer.lbl_reply(1).travel_time_s(), 1.0, 0.001);
  EXPECT_NEAR(answer.lbl_reply(1).range_m(), 1500, 2);
  EXPECT_EQ(answer.lbl_reply(2).transponder(), "C");
  EXPECT_FALSE(answer.lbl_reply(2).answered());
  EXPECT_FALSE(answer.lbl_reply(2).has_travel_time_s());
  // §8.5: TAT first, then the interrogation with the spec's field order.
  EXPECT_NE(a_->written.find("$CCCFG,TAT,50*"), std::string::npos);
  EXPECT_NE(a_->written.find("$CCPNT,25000,5,5,4000,26000,27000,28000,0,1*"), std::string::npos) << a_->written;
}

TEST_F(MicroModemExtrasTest, RemusLblSetsTat50AndReportsTheBeaconsAskedFor) {
  two_nodes();
  MicroModemTransmission ask = kind(MicroModemTransmission::REMUS_LBL);
  ask.mutable_remus_lbl()->set_channel(2);
  ask.mutable_remus_lbl()->set_beacons("AB");
  ask.mutable_remus_lbl()->set_timeout_ms(3000);
  DriverSpecificResult result = send(request(0, ask));
  ASSERT_EQ(result.status, DriverSpecificStatus::kOk) << result.error;
  const auto& answer = result.transmission.GetExtension(drivers::micromodem_transmission);
  ASSERT_EQ(answer.lbl_reply_size(), 2);
  EXPECT_TRUE(answer.lbl_reply(0).answered());
  EXPECT_NEAR(answer.lbl_reply(0).travel_time_s(), 0.2, 0.001);
  EXPECT_EQ(answer.lbl_reply(1).transponder(), "B");
  EXPECT_FALSE(answer.lbl_reply(1).answered());
  EXPECT_NE(a_->written.find("$CCPDT,1,2,0,0,3000,1,1,0,0*"), std::string::npos) << a_->written;
}

TEST_F(MicroModemExtrasTest, MiniPacketReachesTheOtherDriverAsItsOwnMessage) {
  two_nodes();
  MicroModemTransmission ask = kind(MicroModemTransmission::MINI_PACKET);
  ask.set_mini_packet_value(0x1ABC);
  DriverSpecificResult result = send(request(2, ask));
  ASSERT_EQ(result.status, DriverSpecificStatus::kOk) << result.error;
  run(3s);
  auto heard = b_->received_driver_specific();
  ASSERT_EQ(heard.size(), 1u);
  ASSERT_TRUE(heard[0].HasExtension(drivers::micromodem_mini_packet));
  const auto& mini = heard[0].GetExtension(drivers::micromodem_mini_packet);
  EXPECT_EQ(mini.src(), 1);
  EXPECT_EQ(mini.dest(), 2);
  EXPECT_EQ(mini.value(), 0x1ABCu);
  EXPECT_NE(a_->written.find("$CCMUC,1,2,1ABC*"), std::string::npos);
}

TEST_F(MicroModemExtrasTest, MiniPacketValueBeyond13BitsIsRefusedNamingTheBound) {
  two_nodes();
  MicroModemTransmission ask = kind(MicroModemTransmission::MINI_PACKET);
  ask.set_mini_packet_value(0x2000);
  DriverSpecificResult result = send(request(2, ask));
  EXPECT_EQ(result.status, DriverSpecificStatus::kInvalidArgument);
  EXPECT_NE(result.error.find("0..8191"), std::string::npos) << result.error;
  EXPECT_EQ(a_->written.find("$CCMUC"), std::string::npos);
}

TEST_F(MicroModemExtrasTest, FdpBetweenTwoMm2sCarriesTheBytesAndIsAcknowledgedInSoftware) {
  two_nodes(Generation::kMM2, Generation::kMM2, {"psk.packet.mod_hdr_version,1"});
  MicroModemTransmission ask = kind(MicroModemTransmission::FDP);
  ask.set_fdp_rate(3);
  std::string data = "odd-length FDP payload";  // 22 bytes + 2 header: even; add one for the pad
  data += '!';
  ask.set_fdp_data(data);
  DriverSpecificResult result = send(request(2, ask));
  ASSERT_EQ(result.status, DriverSpecificStatus::kOk) << result.error;
  EXPECT_TRUE(result.transmission.GetExtension(drivers::micromodem_transmission).fdp_acknowledged());
  auto heard = b_->received_driver_specific();
  ASSERT_EQ(heard.size(), 1u);
  const auto& fdp = heard[0].GetExtension(drivers::micromodem_fdp_packet);
  EXPECT_EQ(fdp.data(), data);
  EXPECT_EQ(fdp.src(), 1);
  EXPECT_EQ(fdp.rate(), 3u);
  EXPECT_NE(a_->written.find("$CCTDP,2,3,0,0,FE00"), std::string::npos) << a_->written;
  EXPECT_NE(b_->written.find("$CCTDP,1,3,0,0,FA00*"), std::string::npos) << b_->written;
}

TEST_F(MicroModemExtrasTest, FdpTowardsAModemKnownToBeMm1IsRefusedAtOnce) {
  a_ = std::make_unique<Node>(water_, scheduler_, 1, Generation::kMM2, Position{}, std::vector<std::string>{"psk.packet.mod_hdr_version,1"});
  a_->config.mutable_micromodem()->add_mm1_modems(2);
  a_->driver = std::make_unique<MicroModemDriver>(a_->config, scheduler_,
                                                  std::make_unique<FakeModemPort>(a_->modem, scheduler_, &a_->written));
  nodes_ = {a_.get()};
  a_->start();
  run(8s);
  ASSERT_TRUE(a_->driver->ready());
  MicroModemTransmission ask = kind(MicroModemTransmission::FDP);
  ask.set_fdp_data("x");
  DriverSpecificResult result = send(request(2, ask));
  EXPECT_EQ(result.status, DriverSpecificStatus::kFailedPrecondition);
  EXPECT_NE(result.error.find("modem 2: it is a Micro-Modem 1"), std::string::npos) << result.error;
  EXPECT_EQ(a_->written.find("$CCTDP"), std::string::npos);
  EXPECT_EQ(a_->driver->check_driver_specific(request(3, ask)).status, DriverSpecificStatus::kOk);
}

TEST_F(MicroModemExtrasTest, FdpToAnUnlistedMm1GoesOutButIsNeverAcknowledged) {
  ASSERT_NO_FATAL_FAILURE(mm2_and_unlisted_mm1());
  MicroModemTransmission ask = kind(MicroModemTransmission::FDP);
  ask.set_fdp_data("hi");
  DriverSpecificResult result = send(request(2, ask));
  ASSERT_EQ(result.status, DriverSpecificStatus::kOk) << result.error;
  EXPECT_FALSE(result.transmission.GetExtension(drivers::micromodem_transmission).fdp_acknowledged());
  EXPECT_TRUE(b_->received_driver_specific().empty());
  EXPECT_EQ(b_->written.find("$CCTDP"), std::string::npos);  // nothing to acknowledge
}

// The deadline passing while the sent packet awaits its ACK is not a
// failure: the packet went out, the result says it was not acknowledged.
TEST_F(MicroModemExtrasTest, FdpWhoseDeadlinePassesAwaitingTheAckSucceedsUnacknowledged) {
  ASSERT_NO_FATAL_FAILURE(mm2_and_unlisted_mm1());
  MicroModemTransmission ask = kind(MicroModemTransmission::FDP);
  ask.set_fdp_rate(5);
  ask.set_fdp_data("hi");
  // Rate 5: about 3.3 s in the water, then at least 5.8 s more for an ACK;
  // the call's 5 s end between the two.
  constexpr Duration kFdpDeadline = 5s;
  const double start = scheduler_.clock().now_seconds();
  DriverSpecificResult result = send(request(2, ask), kFdpDeadline);
  ASSERT_EQ(result.status, DriverSpecificStatus::kOk) << result.error;
  EXPECT_FALSE(result.transmission.GetExtension(drivers::micromodem_transmission).fdp_acknowledged());
  EXPECT_NE(a_->written.find("$CCTDP,2,"), std::string::npos);
  EXPECT_LE(scheduler_.clock().now_seconds() - start, std::chrono::duration<double>(kFdpDeadline).count() + 0.2)
      << "answered at the call's deadline, not at the end of the ACK wait";
}

TEST_F(MicroModemExtrasTest, FdpIsNotDecodedByAnMm2WithTheLegacyHeaderVersion) {
  two_nodes();  // neither sets psk.packet.mod_hdr_version 1
  a_->config.mutable_micromodem()->add_cfg("psk.packet.mod_hdr_version,1");
  a_->driver = std::make_unique<MicroModemDriver>(a_->config, scheduler_,
                                                  std::make_unique<FakeModemPort>(a_->modem, scheduler_, &a_->written));
  a_->start();
  run(8s);
  ASSERT_TRUE(a_->driver->ready());
  MicroModemTransmission ask = kind(MicroModemTransmission::FDP);
  ask.set_fdp_data("hi");
  uint64_t heard_before = b_->driver->reception_counters().packets;
  DriverSpecificResult result = send(request(2, ask));
  ASSERT_EQ(result.status, DriverSpecificStatus::kOk) << result.error;
  EXPECT_FALSE(result.transmission.GetExtension(drivers::micromodem_transmission).fdp_acknowledged());
  // §6, §8.6: heard (its $CACST counted) but undecodable: no $CARDP, nothing reported.
  EXPECT_EQ(b_->driver->reception_counters().packets, heard_before + 1);
  EXPECT_EQ(b_->driver->driver_specific_counters().fdp_received, 0u);
  EXPECT_TRUE(b_->received_driver_specific().empty());
}

TEST_F(MicroModemExtrasTest, FdpOnAnMm1IsRefusedAtOnceSayingItNeedsAnMm2) {
  two_nodes(Generation::kMM1, Generation::kMM2);
  MicroModemTransmission ask = kind(MicroModemTransmission::FDP);
  ask.set_fdp_data("x");
  DriverSpecificResult result = send(request(2, ask));
  EXPECT_EQ(result.status, DriverSpecificStatus::kFailedPrecondition);
  EXPECT_NE(result.error.find("Micro-Modem 1"), std::string::npos) << result.error;
  EXPECT_EQ(a_->written.find("$CCTDP"), std::string::npos);
}

TEST_F(MicroModemExtrasTest, FdpWithoutTheHeaderVersionConfiguredIsRefusedNamingTheSetting) {
  two_nodes();
  MicroModemTransmission ask = kind(MicroModemTransmission::FDP);
  ask.set_fdp_data("x");
  DriverSpecificResult result = send(request(2, ask));
  EXPECT_EQ(result.status, DriverSpecificStatus::kFailedPrecondition);
  EXPECT_NE(result.error.find("psk.packet.mod_hdr_version,1"), std::string::npos) << result.error;
}

TEST_F(MicroModemExtrasTest, FdpLargerThanTheRatesDataSectionIsRefused) {
  two_nodes(Generation::kMM2, Generation::kMM2, {"psk.packet.mod_hdr_version,1"});
  MicroModemTransmission ask = kind(MicroModemTransmission::FDP);
  ask.set_fdp_rate(1);
  ask.set_fdp_data(std::string(191, 'x'));
  DriverSpecificResult result = send(request(2, ask));
  EXPECT_EQ(result.status, DriverSpecificStatus::kInvalidArgument);
  EXPECT_NE(result.error.find("1..190"), std::string::npos) << result.error;
}

TEST_F(MicroModemExtrasTest, ARequestWithoutTheMicroModemExtensionIsUnimplementedNamingIt) {
  two_nodes();
  ModemTransmission tx;
  tx.set_type(ModemTransmission::DRIVER_SPECIFIC);
  tx.mutable_unknown_fields()->AddVarint(4242, 1);
  DriverSpecificResult result = a_->driver->check_driver_specific(tx);
  EXPECT_EQ(result.status, DriverSpecificStatus::kUnimplemented);
  EXPECT_NE(result.error.find("extension 4242"), std::string::npos) << result.error;
}

TEST_F(MicroModemExtrasTest, AModemRebootFailsTheExtraInProgress) {
  two_nodes();
  std::optional<DriverSpecificResult> result;
  a_->driver->send_driver_specific(request(2, kind(MicroModemTransmission::PING)), kStart + 1e6,
                                   [&](DriverSpecificResult r) { result = std::move(r); });
  run(300ms);
  a_->modem.reboot();
  run(2s);
  ASSERT_TRUE(result.has_value());
  EXPECT_EQ(result->status, DriverSpecificStatus::kAborted);
  EXPECT_NE(result->error.find("reboot"), std::string::npos) << result->error;
}

TEST_F(MicroModemExtrasTest, BadExtrasSettingsAreConfigErrorsNamingTheField) {
  FakeMicroModem modem(water_, FakeModemConfig{});
  std::string written;
  v1::DriverConfig config;
  config.set_name("micromodem");
  config.set_modem_id(1);
  config.mutable_micromodem()->set_sound_speed_mps(50);
  try {
    MicroModemDriver driver(config, scheduler_, std::make_unique<FakeModemPort>(modem, scheduler_, &written));
    ADD_FAILURE() << "a sound speed of 50 m/s was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("driver.micromodem.sound_speed_mps"), std::string::npos) << e.what();
  }
  config.mutable_micromodem()->set_sound_speed_mps(0);
  config.mutable_micromodem()->add_mm1_modems(200);
  try {
    MicroModemDriver driver(config, scheduler_, std::make_unique<FakeModemPort>(modem, scheduler_, &written));
    ADD_FAILURE() << "mm1_modems 200 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("driver.micromodem.mm1_modems 200"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace acomms::fake_micromodem
