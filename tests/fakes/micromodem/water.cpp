#include "water.h"

#include <algorithm>
#include <stdexcept>

namespace acomms::fake_micromodem {

Water::Water(core::Scheduler& scheduler, Settings settings)
    : scheduler_(scheduler), settings_(settings), random_(settings.seed) {
  if (!(settings_.sound_speed > 0)) throw std::invalid_argument("sound speed must be > 0 m/s");
  if (!(settings_.loss_probability >= 0 && settings_.loss_probability <= 1)) {
    throw std::invalid_argument("loss probability must be within 0..1");
  }
}

void Water::join(WaterListener* listener) { listeners_.push_back(listener); }

void Water::leave(WaterListener* listener) { std::erase(listeners_, listener); }

bool Water::joined(const WaterListener* listener) const {
  return std::find(listeners_.begin(), listeners_.end(), listener) != listeners_.end();
}

void Water::transmit(const WaterListener* sender, const AcousticPacket& packet, Duration air) {
  Position from = sender->position();
  if (tap_) tap_(WaterDatagram{from, std::chrono::duration<double>(air).count(), packet});
  propagate(sender, from, packet, air);
}

void Water::arrive_from_elsewhere(const WaterDatagram& datagram) {
  auto air = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(datagram.air_seconds));
  propagate(nullptr, datagram.from, datagram.packet, air);
}

void Water::propagate(const WaterListener* sender, const Position& from,
                      const AcousticPacket& packet, Duration air) {
  std::bernoulli_distribution lose(settings_.loss_probability);
  for (WaterListener* listener : listeners_) {
    if (listener == sender) continue;
    if (lose(random_)) {
      ++lost_;
      continue;
    }
    double range = distance(from, listener->position());
    auto travel = std::chrono::duration_cast<Duration>(
        std::chrono::duration<double>(range / settings_.sound_speed));
    scheduler_.after(travel, [this, listener, packet, air, range] {
      if (joined(listener)) listener->on_arrival(packet, air, range);
    });
  }
}

}  // namespace acomms::fake_micromodem
