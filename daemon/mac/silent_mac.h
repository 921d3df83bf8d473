#pragma once
// MAC "none": this node never initiates a transmission. Its driver still
// answers polls from a polling master (the driver, not the MAC, does that),
// so this is what every node but the master runs under "polled".

#include "mac/mac.h"

namespace acomms::mac {

class SilentMac final : public Mac {
 public:
  void start(Transmit) override {}
  void stop() override {}
  // Kept, so that cycle() says what was asked, but never acted on.
  void set_cycle(const Cycle& cycle) override { cycle_ = cycle; }
  const Cycle& cycle() const override { return cycle_; }
  void on_receive(const v1::ModemTransmission&) override {}
  std::string cycle_not_settable_reason() const override {
    return "this node's MAC is \"none\": it never starts a transmission, so it has no cycle to change "
           "(configure mac.name \"fixed\" or \"polled\")";
  }

 private:
  Cycle cycle_;
};

}  // namespace acomms::mac
