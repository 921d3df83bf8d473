#pragma once
// The micromodem driver's port, plugged into a fake modem in the same
// process on the simulated scheduler: what the driver writes goes to the
// modem's from_host() (and is kept, byte for byte, for transcript tests);
// what the modem writes reaches the driver in a scheduler task (as bytes
// from a real port arrive from the event loop, never inside a write).

#include <memory>
#include <string>

#include "core/scheduler.h"
#include "fake_micromodem.h"
#include "micromodem/modem_port.h"

namespace acomms::fake_micromodem {

class FakeModemPort final : public drivers::micromodem::ModemPort {
 public:
  // `written` collects every byte the driver writes; it must outlive the port.
  FakeModemPort(FakeMicroModem& modem, core::Scheduler& scheduler, std::string* written)
      : modem_(modem), scheduler_(scheduler), written_(written) {}
  ~FakeModemPort() override { close(); }

  void open(DataCallback on_data, link::TransportStateCallback on_state) override {
    on_data_ = std::make_shared<DataCallback>(std::move(on_data));
    std::weak_ptr<DataCallback> target = on_data_;
    core::Scheduler* scheduler = &scheduler_;
    modem_.set_output([target, scheduler](std::string_view bytes) {
      scheduler->after(std::chrono::system_clock::duration::zero(), [target, copy = std::string(bytes)] {
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
  std::string name() const override { return "fake modem " + std::to_string(modem_.address()); }

 private:
  FakeMicroModem& modem_;
  core::Scheduler& scheduler_;
  std::string* written_;
  std::shared_ptr<DataCallback> on_data_;
};

}  // namespace acomms::fake_micromodem
