#pragma once
// The simulated water that fake Micro-Modems share: a transmission reaches
// every other modem after range / sound speed and lasts its air time.
// Each receiver independently loses it with `loss_probability`; half-duplex
// and collisions are the receiving modem's business (it knows whether it is
// transmitting or already receiving).
//
// In one process every fake joins the same Water. Fakes in separate
// processes each have a Water of their own, joined by a UdpWaterBus on
// loopback: the tap sends every local transmission to the other processes,
// and arrive_from_elsewhere() plays theirs here. Runs on the scheduler's
// thread only.

#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "acoustic_packet.h"
#include "core/scheduler.h"
#include "transponder.h"

namespace acomms::fake_micromodem {

using Duration = std::chrono::system_clock::duration;

// What Water needs from a modem.
class WaterListener {
 public:
  virtual ~WaterListener() = default;
  virtual Position position() const = 0;
  // The first sound of `packet` reaches this modem now and lasts `air`.
  virtual void on_arrival(const AcousticPacket& packet, Duration air, double range_m) = 0;
};

class Water {
 public:
  struct Settings {
    double sound_speed = 1500;     // m/s
    double loss_probability = 0;   // per receiver and packet
    uint32_t seed = 1;             // losses are repeatable
    std::vector<Transponder> transponders;  // LBL (transponder.h)
  };

  Water(core::Scheduler& scheduler, Settings settings);
  core::Scheduler& scheduler() { return scheduler_; }
  const Settings& settings() const { return settings_; }

  void join(WaterListener* listener);
  void leave(WaterListener* listener);  // pending arrivals for it are dropped

  // `sender` starts transmitting `packet` now, for `air`.
  void transmit(const WaterListener* sender, const AcousticPacket& packet, Duration air);
  // A transmission from another process starts now at datagram.from.
  void arrive_from_elsewhere(const WaterDatagram& datagram);
  // Sees every local transmission (for the UDP bus).
  void set_tap(std::function<void(const WaterDatagram&)> tap) { tap_ = std::move(tap); }

  uint64_t lost() const { return lost_; }

 private:
  void propagate(const WaterListener* sender, const Position& from, const AcousticPacket& packet,
                 Duration air);
  bool joined(const WaterListener* listener) const;

  core::Scheduler& scheduler_;
  Settings settings_;
  std::mt19937 random_;
  std::vector<WaterListener*> listeners_;
  std::function<void(const WaterDatagram&)> tap_;
  uint64_t lost_ = 0;
};

}  // namespace acomms::fake_micromodem
