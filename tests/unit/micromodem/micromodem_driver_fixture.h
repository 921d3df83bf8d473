#pragma once
// The micromodem driver's test rig: nodes of a fake Micro-Modem and the
// driver on it, on simulated time, with what each driver reported
// (shared by micromodem_driver_test.cpp and micromodem_lost_packets_test.cpp).

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "fake_micromodem.h"
#include "fake_modem_port.h"
#include "link/driver.h"
#include "micromodem/micromodem_driver.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::fake_micromodem {

using namespace std::chrono_literals;
using drivers::micromodem::MicroModemDriver;
using drivers::micromodem::ModemGeneration;
using v1::ModemTransmission;

inline core::Clock::time_point start_time() {
  return core::Clock::time_point(std::chrono::seconds(1'700'000'000));
}

// One node: a fake modem, the driver on it, and what the driver reported.
struct Node {
  Node(Water& water, core::Scheduler& scheduler, int id, Generation generation, Position position,
       std::vector<std::string> cfg = {}, int nvram_address = 0, double frame_error_probability = 0,
       double header_error_probability = 0)
      : modem(water, [&] {
          FakeModemConfig c;
          c.address = nvram_address ? nvram_address : id;
          c.frame_error_probability = frame_error_probability;
          c.header_error_probability = header_error_probability;
          c.generation = generation;
          c.position = position;
          return c;
        }()) {
    config.set_name("micromodem");
    config.set_modem_id(static_cast<uint32_t>(id));
    for (const std::string& entry : cfg) config.mutable_micromodem()->add_cfg(entry);
    driver = std::make_unique<MicroModemDriver>(config, scheduler,
                                                std::make_unique<FakeModemPort>(modem, scheduler, &written));
  }

  void start() {
    link::DriverCallbacks callbacks;
    callbacks.on_receive = [this](const ModemTransmission& tx) { received.push_back(tx); };
    callbacks.on_data_request = [this](ModemTransmission* tx) {
      ++data_requests;
      last_max_num_frames = tx->max_num_frames();
      for (const std::string& frame : frames_to_send) {
        if (static_cast<uint32_t>(tx->frame_size()) < tx->max_num_frames()) tx->add_frame(frame);  // as the queues do
      }
      if (tx->dest() < 0) tx->set_dest(0);
    };
    callbacks.on_transmit_result = [this](const ModemTransmission& tx, bool ok, const std::string& error) {
      results.push_back({tx, ok, error});
    };
    callbacks.on_reception_failed = [this](const ModemTransmission& tx) { failed.push_back(tx); };
    driver->start(std::move(callbacks));
  }

  // Host lines written since the last mark, split (without CR LF), less
  // the keep-alive queries ($CCCFQ,SRC every ~10 s of quiet).
  std::vector<std::string> host_lines_since_mark() const {
    std::vector<std::string> lines;
    std::string rest = written.substr(mark);
    size_t at = 0;
    while (at < rest.size()) {
      size_t end = rest.find("\r\n", at);
      if (end == std::string::npos) end = rest.size();
      std::string line = rest.substr(at, end - at);
      if (line != "$CCCFQ,SRC*3A") lines.push_back(line);
      at = end + 2;
    }
    return lines;
  }
  void set_mark() { mark = written.size(); }
  std::vector<ModemTransmission> received_of(ModemTransmission::Type type) const {
    std::vector<ModemTransmission> out;
    for (const ModemTransmission& tx : received) {
      if (tx.type() == type) out.push_back(tx);
    }
    return out;
  }

  struct Result {
    ModemTransmission tx;
    bool ok;
    std::string error;
  };

  FakeMicroModem modem;
  v1::DriverConfig config;
  std::string written;
  size_t mark = 0;
  std::unique_ptr<MicroModemDriver> driver;
  std::vector<ModemTransmission> received;
  std::vector<ModemTransmission> failed;  // on_reception_failed
  std::vector<Result> results;
  std::vector<std::string> frames_to_send;
  int data_requests = 0;
  uint32_t last_max_num_frames = 0;
};

inline ModemTransmission data_to(int src, int dest, int rate) {
  ModemTransmission tx;
  tx.set_type(ModemTransmission::DATA);
  tx.set_src(src);
  tx.set_dest(dest);
  tx.set_rate(rate);
  tx.set_ack_requested(true);
  return tx;
}

class MicroModemDriverTest : public ::testing::Test {
 protected:
  void run(Duration d) {
    // As the supervisor would: do_work a few times a second.
    auto until = scheduler_.clock().now() + d;
    while (scheduler_.clock().now() < until) {
      scheduler_.run_for(200ms);
      for (Node* node : nodes_) node->driver->do_work();
    }
  }
  // Two nodes 1500 m apart (1 s of travel), booted and started.
  void two_nodes(Generation generation = Generation::kMM2) {
    a_ = std::make_unique<Node>(water_, scheduler_, 1, generation, Position{0, 0, 0});
    b_ = std::make_unique<Node>(water_, scheduler_, 2, generation, Position{1500, 0, 0});
    nodes_ = {a_.get(), b_.get()};
    for (Node* node : nodes_) {
      node->start();
      node->modem.power_on();
    }
    run(8s);
    ASSERT_TRUE(a_->driver->ready());
    ASSERT_TRUE(b_->driver->ready());
    a_->set_mark();
    b_->set_mark();
  }

  core::SimulatedScheduler scheduler_{start_time()};
  Water water_{scheduler_, {1500, 0, 1, {}}};
  std::unique_ptr<Node> a_, b_;
  std::vector<Node*> nodes_;
};

}  // namespace acomms::fake_micromodem
