#include "eval/simulated_channel.h"

#include <utility>

namespace acomms::eval {

SimulatedChannel::SimulatedChannel(core::Scheduler& scheduler, std::chrono::nanoseconds delay,
                                   double p_collide, uint64_t seed)
    : scheduler_(scheduler), delay_(delay), p_collide_(p_collide), random_(seed) {}

void SimulatedChannel::attach(int32_t id, Receive receive) {
  nodes_[id].receive = std::move(receive);
}

void SimulatedChannel::switch_on(int32_t id) { nodes_[id].on = true; }

void SimulatedChannel::transmit(int32_t id, const v1::ModemTransmission& transmission) {
  const core::Clock::time_point now = scheduler_.clock().now();
  auto [slot, first] = pending_.try_emplace(now);
  slot->second[id] = transmission;
  if (first) scheduler_.at(now + delay_, [this, now] { deliver(now); });
}

void SimulatedChannel::deliver(core::Clock::time_point start) {
  auto it = pending_.find(start);
  if (it == pending_.end()) return;
  std::map<int32_t, v1::ModemTransmission> sent = std::move(it->second);
  pending_.erase(it);

  SlotOutcome outcome;
  outcome.start = start;
  for (const auto& [id, transmission] : sent) outcome.transmitters.push_back(id);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (auto& [id, node] : nodes_) {
    if (!node.on || sent.count(id)) continue;
    // One draw per listener, even when it cannot matter, keeps the random
    // stream independent of who happened to collide.
    const bool lost = uniform(random_) < p_collide_ && sent.size() > 1;
    if (lost) continue;
    for (const auto& [src, transmission] : sent) {
      outcome.received[id].push_back(src);
      if (node.receive) node.receive(transmission);
    }
  }
  if (observer_) observer_(outcome);
}

}  // namespace acomms::eval
