#pragma once
// One vehicle for the Iridium driver's tests: a fake 9603 on an in-memory
// gateway, the driver on it through a port that carries bytes in scheduler
// tasks (as a real port delivers them from the event loop, never inside a
// write), and a small stand-in for the queues that behaves as they do for
// this driver: messages packed into one frame up to the limit, a frame's
// messages in flight until its ACK, released again at the next request.
//
// `Shore` reads the gateway as the shore endpoint would: dedup by
// (MOMSN, payload) (spec §9.4), then the messages split back out, so a test
// can say "every message once".

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/scheduler.h"
#include "fake_sbd_modem.h"
#include "iridium/iridium_driver.h"
#include "sbd_gateway.h"

namespace acomms::fake_iridium {

using namespace std::chrono_literals;
using drivers::iridium::IridiumDriver;
using v1::ModemTransmission;

class FakeSbdPort final : public drivers::iridium::SbdPort {
 public:
  FakeSbdPort(FakeSbdModem& modem, core::Scheduler& scheduler, std::string* written)
      : modem_(modem), scheduler_(scheduler), written_(written) {}
  ~FakeSbdPort() override { close(); }
  void open(DataCallback on_data, link::TransportStateCallback on_state) override {
    on_data_ = std::make_shared<DataCallback>(std::move(on_data));
    std::weak_ptr<DataCallback> target = on_data_;
    core::Scheduler* scheduler = &scheduler_;
    const std::string* noise = &noise_;
    modem_.set_output([target, scheduler, noise](std::string_view bytes) {
      scheduler->after(std::chrono::system_clock::duration::zero(), [target, copy = *noise + std::string(bytes)] {
        if (auto callback = target.lock()) (*callback)(copy);
      });
    });
    on_state(link::TransportState::kOpen, name());
  }
  void close() override {
    on_data_.reset();
    modem_.set_output(nullptr);
  }
  bool write(std::string_view bytes) override {
    if (!on_data_) return false;
    written_->append(bytes);
    modem_.from_host(bytes);
    return true;
  }
  std::string name() const override { return "fake 9603"; }
  // Put before every chunk the modem writes (garbage, unsolicited lines).
  void set_noise(std::string noise) { noise_ = std::move(noise); }

 private:
  FakeSbdModem& modem_;
  core::Scheduler& scheduler_;
  std::string* written_;
  std::shared_ptr<DataCallback> on_data_;
  std::string noise_;
};

// Messages are "<id>;" padded with '.' to `size` bytes: self-delimiting
// enough to be split back out at the shore.
inline std::string message(int id, size_t size) {
  std::string m = "m" + std::to_string(id) + ";";
  m.resize(size, '.');
  m.back() = '|';
  return m;
}

inline std::vector<std::string> split_messages(const std::string& payload) {
  std::vector<std::string> out;
  size_t at = 0;
  while (at < payload.size()) {
    size_t end = payload.find('|', at);
    if (end == std::string::npos) end = payload.size() - 1;
    out.push_back(payload.substr(at, end - at + 1));
    at = end + 1;
  }
  return out;
}

struct Vehicle {
  static constexpr int kId = 2;
  static constexpr int kShore = 1;

  Vehicle(core::Scheduler& scheduler, FakeSbdConfig modem_config = {}, v1::DriverConfig driver_config = {})
      : modem(scheduler, gateway, modem_config), port_owner(std::make_unique<FakeSbdPort>(modem, scheduler, &written)) {
    port = port_owner.get();
    config = driver_config;
    config.set_name("iridium");
    config.set_modem_id(kId);
    config.mutable_iridium()->set_shore_id(kShore);
    driver = std::make_unique<IridiumDriver>(config, scheduler, std::move(port_owner));
  }

  void start() {
    link::DriverCallbacks callbacks;
    callbacks.on_receive = [this](const ModemTransmission& tx) {
      if (tx.type() == ModemTransmission::ACK) {
        ++acks;
        in_flight.clear();  // delivered: the queues forget them
        return;
      }
      received.push_back(tx);
    };
    callbacks.on_data_request = [this](ModemTransmission* tx) {
      ++data_requests;
      max_frame_bytes = tx->max_frame_bytes();
      max_num_frames = tx->max_num_frames();
      // Unacknowledged messages go back into the contest first.
      queued.insert(queued.begin(), in_flight.begin(), in_flight.end());
      in_flight.clear();
      std::string frame;
      while (!queued.empty() && frame.size() + queued.front().size() <= tx->max_frame_bytes()) {
        frame += queued.front();
        in_flight.push_back(queued.front());
        queued.erase(queued.begin());
      }
      tx->add_frame(frame);  // "" when empty, as the link controller does
    };
    callbacks.on_transmit_result = [this](const ModemTransmission&, bool ok, const std::string&) {
      (ok ? sent_ok : sent_failed)++;
    };
    driver->start(std::move(callbacks));
  }

  // Every message the shore would deliver, after its (MOMSN, payload) dedup.
  std::vector<std::string> shore_messages() const {
    std::set<std::pair<uint16_t, std::string>> seen;
    std::vector<std::string> out;
    for (const auto& mo : gateway.mo()) {
      if (!seen.emplace(mo.momsn, mo.payload).second) continue;
      for (auto& m : split_messages(mo.payload)) out.push_back(m);
    }
    return out;
  }
  std::vector<std::string> host_commands() const {
    std::vector<std::string> out;
    size_t at = 0;
    while (at < written.size()) {
      size_t end = written.find('\r', at);
      if (end == std::string::npos) break;
      std::string line = written.substr(at, end - at);
      if (line.starts_with("AT")) out.push_back(line);
      at = end + 1;
    }
    return out;
  }
  int count_command(const std::string& text) const {
    int n = 0;
    for (const auto& c : host_commands()) n += c == text;
    return n;
  }

  InMemorySbdGateway gateway;
  FakeSbdModem modem;
  std::string written;
  std::unique_ptr<FakeSbdPort> port_owner;
  FakeSbdPort* port = nullptr;
  v1::DriverConfig config;
  std::unique_ptr<IridiumDriver> driver;
  std::vector<std::string> queued;
  std::vector<std::string> in_flight;
  std::vector<ModemTransmission> received;
  int acks = 0, data_requests = 0, sent_ok = 0, sent_failed = 0;
  uint32_t max_frame_bytes = 0, max_num_frames = 0;
};

class IridiumDriverTest : public ::testing::Test {
 protected:
  static core::Clock::time_point start_time() { return core::Clock::time_point(std::chrono::seconds(1'700'000'000)); }

  // As the supervisor does: do_work a few times a second.
  void run_for(std::chrono::system_clock::duration d) {
    auto until = scheduler_.clock().now() + d;
    while (scheduler_.clock().now() < until) {
      scheduler_.run_for(200ms);
      vehicle_->driver->do_work();
    }
  }
  // Runs until `done` or `limit`; returns whether `done` held.
  template <typename Predicate>
  bool run_until(Predicate done, std::chrono::system_clock::duration limit) {
    auto until = scheduler_.clock().now() + limit;
    while (scheduler_.clock().now() < until) {
      if (done()) return true;
      scheduler_.run_for(200ms);
      vehicle_->driver->do_work();
    }
    return done();
  }
  void make(FakeSbdConfig modem = {}, v1::DriverConfig driver = {}) {
    vehicle_ = std::make_unique<Vehicle>(scheduler_, modem, driver);
  }
  // Built, started and through its bring-up and first mailbox check.
  void ready(FakeSbdConfig modem = {}, v1::DriverConfig driver = {}) {
    make(modem, driver);
    vehicle_->start();
    ASSERT_TRUE(run_until([&] { return vehicle_->driver->stats().sessions >= 1; }, 120s));
    if (::testing::Test::HasFailure()) std::cout << vehicle_->modem.transcript();
  }

  // The fake's session transcript, printed when a test fails or when
  // IRIDIUM_TRANSCRIPT is set (to see an exchange while reading a test).
  void TearDown() override {
    if (vehicle_ && (HasFailure() || std::getenv("IRIDIUM_TRANSCRIPT") != nullptr)) {
      std::cout << "fake 9603 transcript:\n" << vehicle_->modem.transcript();
    }
  }

  core::SimulatedScheduler scheduler_{start_time()};
  std::unique_ptr<Vehicle> vehicle_;
};

}  // namespace acomms::fake_iridium
