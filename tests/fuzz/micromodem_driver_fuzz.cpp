// libFuzzer target: the Micro-Modem driver's sentence handling. Arbitrary
// lines reach the driver's receive path as if its modem wrote them, mixed
// with what the MAC asks of it, time passing and modem reboots; the driver
// talks to a fake Micro-Modem (tests/fakes/micromodem) on the simulated
// scheduler, with a second fake 1500 m away, so that real exchanges run
// (and get in the way of the injected lines) too.
//
// Input: lines split at '\n'. A line starting with '!' is for the harness:
//   !t<c>      time passes: (c % 32) x 250 ms, the driver's do_work between
//   !x<r><d>   the MAC starts our DATA, rate r % 6, to node d % 4 (0 = broadcast)
//   !p<s><r>   the MAC polls node s % 4 at rate r % 6
//   !b         the modem reboots ($CAREV INIT) mid-run
//   !mm1       (first line only) the modem is an MM1, else an MM2
//   !fdp       (first line only) driver.micromodem.fdp_data: DATA and
//              software ACKs as FDP packets, $CARDP decoded as such
// Any other line goes to the driver byte for byte with its '\n', so framing
// (CR, LF, noise, '$' inside a line, over-long lines) is fuzzed as well.
//
// Checked, beyond the sanitizers: nothing but DriverError leaves do_work
// (the supervisor restarts the driver for it; the harness then stops the
// driver as the supervisor would), and every transmission the MAC started
// is answered by on_transmit_result exactly once (driver_sequence.h), by
// the end of a quiet minute or by stop().

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "core/scheduler.h"
#include "fake_micromodem.h"
#include "fake_modem_port.h"
#include "link/driver.h"
#include "micromodem/micromodem_driver.h"

namespace {

using namespace std::chrono_literals;
using acomms::core::SimulatedScheduler;
using acomms::drivers::micromodem::MicroModemDriver;
using acomms::fake_micromodem::FakeMicroModem;
using acomms::fake_micromodem::FakeModemConfig;
using acomms::fake_micromodem::FakeModemPort;
using acomms::fake_micromodem::Generation;
using acomms::fake_micromodem::Water;
using acomms::v1::ModemTransmission;

constexpr int kOwnId = 1;
constexpr auto kMostSimulatedTime = 600s;  // bounds one input's cost

struct Harness {
  explicit Harness(Generation generation, bool fdp_data = false)
      : scheduler(acomms::core::Clock::time_point(std::chrono::seconds(1'700'000'000))),
        water(scheduler, {1500, 0, 1, {}}),
        modem(water, modem_config(kOwnId, generation, 0)),
        peer(water, modem_config(2, generation, 1500)) {
    acomms::v1::DriverConfig config;
    config.set_name("micromodem");
    config.set_modem_id(kOwnId);
    config.mutable_micromodem()->set_max_range_m(2000);
    if (fdp_data) {
      config.mutable_micromodem()->set_fdp_data(true);
      config.mutable_micromodem()->add_cfg("psk.packet.mod_hdr_version,1");
    }
    driver = std::make_unique<MicroModemDriver>(config, scheduler,
                                                std::make_unique<FakeModemPort>(modem, scheduler, &written));
    acomms::link::DriverCallbacks callbacks;
    callbacks.on_data_request = [](ModemTransmission* tx) {
      tx->add_frame("fuzz");
      if (tx->dest() < 0) tx->set_dest(0);
    };
    callbacks.on_transmit_result = [this](const ModemTransmission& tx, bool, const std::string&) {
      // MAC-started transmissions carry their tag in `time`; answers to
      // polls carry a clock time and are not the MAC's to count.
      if (tx.time() > 0 && tx.time() < 1e6) ++results[static_cast<int>(tx.time())];
    };
    driver->start(std::move(callbacks));
    modem.power_on();
    peer.power_on();
    run(8s);
  }

  static FakeModemConfig modem_config(int address, Generation generation, double x) {
    FakeModemConfig c;
    c.address = address;
    c.generation = generation;
    c.position = {x, 0, 0};
    return c;
  }

  // Runs time forward in do_work steps, as the supervisor does.
  void run(std::chrono::system_clock::duration d) {
    auto until = scheduler.clock().now() + d;
    while (running && scheduler.clock().now() < until) {
      scheduler.run_for(250ms);
      try {
        driver->do_work();
      } catch (const acomms::link::DriverError&) {
        driver->stop();  // the supervisor's first step
        running = false;
      }
    }
  }

  void initiate(ModemTransmission tx) {
    if (!running) return;
    tx.set_time(++tag);  // 1, 2, ...: results are counted by it
    started[tag] = true;
    try {
      driver->initiate_transmission(tx);
    } catch (const acomms::link::DriverError&) {
      driver->stop();
      running = false;
    }
  }

  SimulatedScheduler scheduler;
  Water water;
  FakeMicroModem modem;
  FakeMicroModem peer;
  std::string written;
  std::unique_ptr<MicroModemDriver> driver;
  bool running = true;
  int tag = 0;
  std::map<int, bool> started;
  std::map<int, int> results;
};

ModemTransmission data(int src, int dest, int rate) {
  ModemTransmission tx;
  tx.set_type(ModemTransmission::DATA);
  tx.set_src(src);
  tx.set_dest(dest);
  tx.set_rate(rate);
  tx.set_ack_requested(true);
  return tx;
}

unsigned char at(std::string_view line, size_t index) {
  return index < line.size() ? static_cast<unsigned char>(line[index]) : 0;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  spdlog::set_level(spdlog::level::off);  // the driver logs every refusal
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
  std::string_view input(reinterpret_cast<const char*>(bytes), size);
  bool mm1 = input.starts_with("!mm1");
  Harness h(mm1 ? Generation::kMM1 : Generation::kMM2, input.starts_with("!fdp"));
  auto limit = h.scheduler.clock().now() + kMostSimulatedTime;

  size_t start = 0;
  while (start < input.size() && h.running && h.scheduler.clock().now() < limit) {
    size_t end = input.find('\n', start);
    size_t stop = end == std::string_view::npos ? input.size() : end + 1;
    std::string_view line = input.substr(start, stop - start);
    start = stop;
    if (!line.starts_with('!')) {
      h.modem.write_raw(line);
      h.run(250ms);
      continue;
    }
    switch (at(line, 1)) {
      case 't': h.run((at(line, 2) % 32) * 250ms); break;
      case 'x': h.initiate(data(kOwnId, at(line, 3) % 4, at(line, 2) % 6)); break;
      case 'p': h.initiate(data(at(line, 2) % 4, kOwnId, at(line, 3) % 6)); break;
      case 'b': h.modem.reboot(); break;
      default: break;
    }
  }
  h.run(60s);  // a quiet minute: every exchange has ended by its deadline
  if (h.running) h.driver->stop();

  for (const auto& [tag, started] : h.started) {
    auto found = h.results.find(tag);
    int answered = found == h.results.end() ? 0 : found->second;
    if (answered != 1) __builtin_trap();  // a transmission answered never, or twice
  }
  return 0;
}
