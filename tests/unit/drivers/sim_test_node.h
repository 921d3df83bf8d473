#pragma once
// A simulated modem with its callbacks recorded, for the sim driver tests.

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "core/scheduler.h"
#include "sim/sim_driver.h"

namespace acomms::drivers::testing {

struct Heard {
  v1::ModemTransmission tx;
  core::Clock::time_point at;
};

struct TestNode {
  TestNode(core::Scheduler& scheduler, std::shared_ptr<SimChannel> channel, int id, double x, double y = 0,
           v1::DriverConfig config = {})
      : scheduler(scheduler) {
    config.set_name("sim");
    config.set_modem_id(id);
    config.mutable_sim()->mutable_position()->set_x(x);
    config.mutable_sim()->mutable_position()->set_y(y);
    driver = std::make_unique<SimDriver>(config, scheduler, std::move(channel));
    link::DriverCallbacks callbacks;
    callbacks.on_receive = [this](const v1::ModemTransmission& tx) {
      received.push_back({tx, this->scheduler.clock().now()});
    };
    callbacks.on_data_request = [this](v1::ModemTransmission* tx) {
      requests.push_back(*tx);
      if (next_frames.empty()) return;
      for (const auto& frame : next_frames.front()) tx->add_frame(frame);
      next_frames.pop_front();
      if (tx->dest() < 0) tx->set_dest(next_dest);
    };
    callbacks.on_transmit_result = [this](const v1::ModemTransmission& tx, bool ok, const std::string& error) {
      results.push_back({tx, ok, error, this->scheduler.clock().now()});
    };
    driver->start(callbacks);
  }

  // The MAC asks this node to send DATA to `dest` at `rate` with `frames`.
  void send(int dest, std::vector<std::string> frames, int rate = 0, bool ack = true) {
    next_frames.push_back(std::move(frames));
    v1::ModemTransmission tx;
    tx.set_src(driver->modem_id());
    tx.set_dest(dest);
    tx.set_rate(rate);
    tx.set_ack_requested(ack);
    driver->initiate_transmission(tx);
  }

  struct Result {
    v1::ModemTransmission tx;
    bool ok;
    std::string error;
    core::Clock::time_point at;
  };
  core::Scheduler& scheduler;
  std::unique_ptr<SimDriver> driver;
  std::vector<Heard> received;
  std::vector<v1::ModemTransmission> requests;
  std::vector<Result> results;
  std::deque<std::vector<std::string>> next_frames;
  int next_dest = 0;
};

}  // namespace acomms::drivers::testing
