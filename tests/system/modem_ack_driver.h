// A sim modem that ACKs "in hardware", as a Micro-Modem without FDP or an
// Iridium gateway does (link::Driver::acks_in_hardware): its ACK goes out
// as soon as a frame is heard, whatever the daemon makes of it (custody
// full or not), so a gateway's answer can only be a custody receipt
// (route/custody_receipt.h). It can also lose chosen receptions (`drop`):
// a custody receipt lost on the way back.
//
// Core thread only, as the driver it wraps.

#pragma once
#include <functional>
#include <utility>

#include "link/driver.h"

namespace acomms::gateway_test {

class ModemAckDriver final : public link::Driver {
 public:
  explicit ModemAckDriver(link::Driver& inner) : inner_(inner) {}

  void start(link::DriverCallbacks callbacks) override {
    callbacks.on_receive = [this, receive = std::move(callbacks.on_receive)](const v1::ModemTransmission& t) {
      if (drop && drop(t)) {
        ++dropped;
        return;
      }
      if (receive) receive(t);
    };
    // The modem has ACKed already: nothing the daemon does holds it back.
    callbacks.after_receipt_durable = [](std::function<void()> then) { then(); };
    inner_.start(std::move(callbacks));
  }
  void stop() override { inner_.stop(); }
  void do_work() override { inner_.do_work(); }
  void initiate_transmission(const v1::ModemTransmission& t) override { inner_.initiate_transmission(t); }
  std::chrono::nanoseconds packet_air_time(int32_t rate, uint32_t frames) const override {
    return inner_.packet_air_time(rate, frames);
  }
  std::chrono::nanoseconds ack_time(int32_t rate) const override { return inner_.ack_time(rate); }
  double sound_speed() const override { return inner_.sound_speed(); }
  bool acks_in_hardware() const override { return true; }

  // Receptions it says yes to are lost (counted in `dropped`).
  std::function<bool(const v1::ModemTransmission&)> drop;
  int dropped = 0;

 private:
  link::Driver& inner_;
};

}  // namespace acomms::gateway_test
