// driver.micromodem.fdp_data: the queue's DATA as MM2 FDP packets between
// two fake MM2s on simulated time, acknowledged in software; refused on an
// MM1 and without the FDP header setting.

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
using drivers::micromodem::MicroModemDriver;
using v1::ModemTransmission;

const std::string kFdpHeader = "psk.packet.mod_hdr_version,1";

struct Result {
  ModemTransmission transmission;
  bool ok = false;
  std::string error;
};

struct Node {
  Node(Water& water, core::Scheduler& scheduler, int id, Generation generation, Position position,
       bool fdp_data, std::vector<std::string> cfg)
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
    config.mutable_micromodem()->set_fdp_data(fdp_data);
    for (const std::string& entry : cfg) config.mutable_micromodem()->add_cfg(entry);
    driver = std::make_unique<MicroModemDriver>(config, scheduler,
                                                std::make_unique<FakeModemPort>(modem, scheduler, &written));
  }
  void start() {
    link::DriverCallbacks callbacks;
    callbacks.on_receive = [this](const ModemTransmission& tx) {
      received.push_back(tx);
      // As the queues do: an ACK for us removes the frames it names.
      if (tx.type() != ModemTransmission::ACK || tx.dest() != static_cast<int32_t>(this->config.modem_id()) || asked.empty()) return;
      std::vector<std::string> left;
      for (size_t i = 0; i < to_send.size(); ++i) {
        bool acked = false;
        for (uint32_t frame : tx.acked_frame()) acked |= frame == i && i < given;
        if (!acked) left.push_back(to_send[i]);
      }
      to_send = left;
      given = 0;
    };
    callbacks.on_data_request = [this](ModemTransmission* tx) {
      asked.push_back(*tx);
      for (uint32_t i = 0; i < tx->max_num_frames() && i < to_send.size(); ++i) tx->add_frame(to_send[i]);
      given = static_cast<size_t>(tx->frame_size());
    };
    callbacks.on_transmit_result = [this](const ModemTransmission& tx, bool ok, const std::string& error) {
      results.push_back({tx, ok, error});
    };
    driver->start(std::move(callbacks));
    modem.power_on();
  }
  std::vector<ModemTransmission> received_of(ModemTransmission::Type type) const {
    std::vector<ModemTransmission> out;
    for (const auto& tx : received) {
      if (tx.type() == type) out.push_back(tx);
    }
    return out;
  }

  FakeMicroModem modem;
  v1::DriverConfig config;
  std::string written;
  std::unique_ptr<MicroModemDriver> driver;
  std::vector<std::string> to_send;  // the "queue": given to data requests, cleared by ACKs
  size_t given = 0;                  // frames of to_send in the last data request
  std::vector<ModemTransmission> asked;
  std::vector<ModemTransmission> received;
  std::vector<Result> results;
};

ModemTransmission data(int rate) {
  ModemTransmission tx;
  tx.set_type(ModemTransmission::DATA);
  tx.set_src(1);
  tx.set_dest(2);
  tx.set_rate(rate);
  tx.set_ack_requested(true);
  return tx;
}

class MicroModemFdpDataTest : public ::testing::Test {
 protected:
  // Runs the scheduler; returns a driver's DriverError text, if one threw.
  std::string run(Duration d) {
    auto until = scheduler_.clock().now() + d;
    while (scheduler_.clock().now() < until) {
      scheduler_.run_for(100ms);
      for (Node* node : nodes_) {
        try {
          node->driver->do_work();
        } catch (const link::DriverError& e) {
          return e.what();
        }
      }
    }
    return "";
  }
  void two_mm2s() {
    a_ = std::make_unique<Node>(water_, scheduler_, 1, Generation::kMM2, Position{0, 0, 0}, true,
                                std::vector<std::string>{kFdpHeader});
    b_ = std::make_unique<Node>(water_, scheduler_, 2, Generation::kMM2, Position{1500, 0, 0}, true,
                                std::vector<std::string>{kFdpHeader});
    nodes_ = {a_.get(), b_.get()};
    for (Node* node : nodes_) node->start();
    ASSERT_EQ(run(8s), "");
    ASSERT_TRUE(a_->driver->ready());
    ASSERT_TRUE(b_->driver->ready());
  }

  core::SimulatedScheduler scheduler_{core::Clock::time_point(std::chrono::seconds(1'700'000'000))};
  Water water_{scheduler_, Water::Settings{1500, 0, 1, {}}};
  std::unique_ptr<Node> a_, b_;
  std::vector<Node*> nodes_;
};

TEST_F(MicroModemFdpDataTest, QueuedFramesGoOutAsFdpAndTheSoftwareAckComesBack) {
  two_mm2s();
  a_->to_send = {"first frame", std::string(64, 'x'), "a third the packet cannot hold"};
  a_->driver->initiate_transmission(data(1));
  ASSERT_EQ(run(20s), "");

  // Rate 1: 192 data bytes hold two 64-byte frames with their headers.
  ASSERT_EQ(a_->asked.size(), 1u);
  EXPECT_EQ(a_->asked[0].max_num_frames(), 2u);
  EXPECT_EQ(a_->written.find("$CCCYC"), std::string::npos) << a_->written;
  // 0xDD, ack requested, then length-prefixed frames.
  EXPECT_NE(a_->written.find("$CCTDP,2,1,0,0,DD01000B6669727374206672616D650040"), std::string::npos)
      << a_->written;
  ASSERT_EQ(a_->results.size(), 1u);
  EXPECT_TRUE(a_->results[0].ok) << a_->results[0].error;

  auto heard = b_->received_of(ModemTransmission::DATA);
  ASSERT_EQ(heard.size(), 1u);
  EXPECT_EQ(heard[0].src(), 1);
  EXPECT_EQ(heard[0].dest(), 2);
  EXPECT_EQ(heard[0].rate(), 1);
  EXPECT_TRUE(heard[0].ack_requested());
  ASSERT_EQ(heard[0].frame_size(), 2);
  EXPECT_EQ(heard[0].frame(0), "first frame");
  EXPECT_EQ(heard[0].frame(1), std::string(64, 'x'));

  // The software ACK (0xDA, 2 frames: 0, 1), an FDP packet, not the firmware's.
  EXPECT_NE(b_->written.find("$CCTDP,1,1,0,0,DA020001"), std::string::npos) << b_->written;
  auto acks = a_->received_of(ModemTransmission::ACK);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].src(), 2);
  EXPECT_EQ(acks[0].dest(), 1);
  ASSERT_EQ(acks[0].acked_frame_size(), 2);
  EXPECT_EQ(acks[0].acked_frame(0), 0u);
  EXPECT_EQ(acks[0].acked_frame(1), 1u);
  // The sender's queue lost what the ACK named, and kept what did not fit.
  EXPECT_EQ(a_->to_send, std::vector<std::string>{"a third the packet cannot hold"});
}

// An extra (here a ping) asked for while the slot's FDP DATA is on the air
// is refused as busy: sent, it would take that packet's $CATXF as its own.
TEST_F(MicroModemFdpDataTest, AnExtraWhileFdpDataIsOnTheAirIsRefusedAndTheDataStillGoesOut) {
  two_mm2s();
  a_->to_send = {"first frame", std::string(64, 'x')};
  a_->driver->initiate_transmission(data(1));
  // Step until $CCTDP is out: the packet is on the air until its $CATXF.
  for (int step = 0; step < 50 && a_->written.find("$CCTDP") == std::string::npos; ++step) {
    ASSERT_EQ(run(100ms), "");
  }
  ASSERT_NE(a_->written.find("$CCTDP"), std::string::npos) << a_->written;
  ASSERT_TRUE(a_->results.empty()) << "the FDP packet finished before the extra was asked for";

  ModemTransmission ping;
  ping.set_type(ModemTransmission::DRIVER_SPECIFIC);
  ping.set_src(1);
  ping.set_dest(2);
  ping.MutableExtension(drivers::micromodem_transmission)->set_kind(drivers::MicroModemTransmission::PING);
  std::optional<link::DriverSpecificResult> result;
  const double deadline = scheduler_.clock().now_seconds() + 30;
  a_->driver->send_driver_specific(ping, deadline, [&](link::DriverSpecificResult r) { result = std::move(r); });
  ASSERT_TRUE(result.has_value());
  EXPECT_EQ(result->status, link::DriverSpecificStatus::kAborted);
  EXPECT_NE(result->error.find("FDP data"), std::string::npos) << result->error;

  ASSERT_EQ(run(20s), "");
  ASSERT_EQ(a_->results.size(), 1u);
  EXPECT_TRUE(a_->results[0].ok) << a_->results[0].error;
  EXPECT_TRUE(a_->to_send.empty());  // acknowledged
  EXPECT_EQ(a_->written.find("$CCMPC"), std::string::npos) << a_->written;
}

TEST_F(MicroModemFdpDataTest, ARateFdpDoesNotHaveIsRefusedBeforeTheQueuesAreAsked) {
  two_mm2s();
  a_->to_send = {"x"};
  a_->driver->initiate_transmission(data(2));
  ASSERT_EQ(run(1s), "");
  EXPECT_TRUE(a_->asked.empty());
  ASSERT_EQ(a_->results.size(), 1u);
  EXPECT_FALSE(a_->results[0].ok);
  EXPECT_NE(a_->results[0].error.find("rate 2 is not an FDP rate"), std::string::npos) << a_->results[0].error;
  EXPECT_EQ(a_->written.find("$CCTDP"), std::string::npos);
}

TEST_F(MicroModemFdpDataTest, FdpDataOnAnMm1FailsStartUpNamingTheSetting) {
  a_ = std::make_unique<Node>(water_, scheduler_, 1, Generation::kMM1, Position{}, true,
                              std::vector<std::string>{kFdpHeader});
  nodes_ = {a_.get()};
  a_->start();
  std::string error = run(8s);
  EXPECT_NE(error.find("driver.micromodem.fdp_data needs a Micro-Modem 2"), std::string::npos) << error;
  EXPECT_NE(error.find("MM1"), std::string::npos) << error;
  EXPECT_FALSE(a_->driver->ready());
  EXPECT_EQ(a_->written.find("mod_hdr_version"), std::string::npos) << a_->written;
}

TEST_F(MicroModemFdpDataTest, FdpDataWithoutTheFdpHeaderSettingIsAConfigErrorNamingBoth) {
  try {
    Node node(water_, scheduler_, 1, Generation::kMM2, Position{}, true, {});
    ADD_FAILURE() << "fdp_data without psk.packet.mod_hdr_version,1 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("driver.micromodem.fdp_data needs cfg: \"psk.packet.mod_hdr_version,1\""),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace acomms::fake_micromodem
