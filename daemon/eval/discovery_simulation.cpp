// One discovery scenario, slot by slot: the real AutoDiscoveryMac of every
// node on one SimulatedScheduler and SimulatedChannel, observed at each
// slot's start (what every node does) and end (what was sent, heard and
// learnt), until the network has shared one cycle long enough that it
// cannot break, or the horizon passes. The definitions it measures are in
// discovery_simulation.h; the text of a run is discovery_report.cpp's.
#include "eval/discovery_simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <set>
#include <stdexcept>

#include "core/scheduler.h"
#include "eval/simulated_channel.h"
#include "mac/auto_discovery_mac.h"
#include "mac/cycle_grid.h"

namespace acomms::eval {
namespace {

using mac::AutoDiscoveryConfig;
using mac::AutoDiscoveryMac;
using mac::BlankRule;
using mac::Nanoseconds;
using time_point = core::Clock::time_point;

// The simulated day: 2024-06-01T00:00:00Z.
constexpr int64_t kDayStart = 1717200000;

time_point at_seconds(double seconds_since_midnight) {
  // Milliseconds, as the start times are; integer arithmetic, as a
  // double cannot hold nanoseconds since 1970.
  const Nanoseconds since_epoch = std::chrono::seconds(kDayStart) +
                                  std::chrono::milliseconds(std::llround(seconds_since_midnight * 1e3));
  return time_point(std::chrono::duration_cast<time_point::duration>(since_epoch));
}

double seconds_of(time_point t) {
  return std::chrono::duration<double>(t - time_point(std::chrono::seconds(kDayStart))).count();
}

NodeAction action_of(AutoDiscoveryMac::Activity activity) {
  switch (activity) {
    case AutoDiscoveryMac::Activity::kOff: return NodeAction::kOff;
    case AutoDiscoveryMac::Activity::kWaiting: return NodeAction::kWait;
    case AutoDiscoveryMac::Activity::kSending: return NodeAction::kSend;
    case AutoDiscoveryMac::Activity::kBlank: return NodeAction::kBlank;
    case AutoDiscoveryMac::Activity::kListening: return NodeAction::kListen;
  }
  return NodeAction::kOff;
}

std::vector<int32_t> srcs_of(const mac::Cycle& cycle) {
  std::vector<int32_t> srcs;
  srcs.reserve(cycle.size());
  for (const mac::Slot& slot : cycle) srcs.push_back(slot.src);
  return srcs;
}

// Elements of `a` not in `b` (both ascending).
std::vector<int32_t> minus(const std::vector<int32_t>& a, const std::vector<int32_t>& b) {
  std::vector<int32_t> out;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

void check(const DiscoveryScenario& scenario) {
  if (scenario.ids.empty()) throw std::invalid_argument("--ids: at least one node is needed");
  std::set<int32_t> unique(scenario.ids.begin(), scenario.ids.end());
  if (unique.size() != scenario.ids.size()) throw std::invalid_argument("--ids: ids must differ");
  if (*unique.begin() < 1) throw std::invalid_argument("--ids: modem ids must be >= 1");
  if (scenario.start_s.size() != 1 && scenario.start_s.size() != scenario.ids.size())
    throw std::invalid_argument("--start: give one time for all nodes or one per node");
  for (double start : scenario.start_s)
    if (!std::isfinite(start)) throw std::invalid_argument("--start: times must be finite");
  if (!(scenario.p_collide >= 0 && scenario.p_collide <= 1))
    throw std::invalid_argument("--p-collide must be within [0, 1]");
  if (!(scenario.horizon_cycles > 0))
    throw std::invalid_argument("--horizon-cycles must be positive");
}

// Does every node run the same cycle, started together, holding everybody?
bool shared_cycle(const std::vector<std::unique_ptr<AutoDiscoveryMac>>& macs,
                  const std::vector<int32_t>& sorted_ids) {
  const AutoDiscoveryMac& first = *macs.front();
  for (const auto& mac : macs) {
    if (mac->activity() == AutoDiscoveryMac::Activity::kOff || !mac->in_cycle()) return false;
    if (mac->cycle_start() != first.cycle_start()) return false;
    if (mac->cycle().size() != first.cycle().size()) return false;
    for (size_t i = 0; i < first.cycle().size(); ++i)
      if (mac->cycle()[i].src != first.cycle()[i].src) return false;
  }
  return first.known_ids() == sorted_ids;
}

}  // namespace

DiscoveryResult simulate_discovery(const DiscoveryScenario& scenario, bool keep_trace) {
  check(scenario);
  const size_t n = scenario.ids.size();
  std::vector<time_point> starts;
  for (size_t i = 0; i < n; ++i)
    starts.push_back(at_seconds(scenario.start_s.size() == 1 ? scenario.start_s[0] : scenario.start_s[i]));
  const time_point first_start = *std::min_element(starts.begin(), starts.end());
  const time_point last_start = *std::max_element(starts.begin(), starts.end());

  AutoDiscoveryConfig config;
  config.slot_seconds = scenario.slot_seconds;
  config.coolness = scenario.coolness;
  config.expire_cycles = scenario.expire_cycles;
  config.blank_rule = scenario.blank_rule;

  core::SimulatedScheduler scheduler(first_start);
  const Nanoseconds slot = mac::to_nanoseconds(scenario.slot_seconds);
  SimulatedChannel channel(scheduler, slot * 9 / 10, scenario.p_collide, scenario.seed);
  std::optional<SimulatedChannel::SlotOutcome> outcome;
  channel.set_observer([&outcome](const SimulatedChannel::SlotOutcome& o) { outcome = o; });

  std::vector<std::unique_ptr<AutoDiscoveryMac>> macs;
  for (size_t i = 0; i < n; ++i) {
    const int32_t id = scenario.ids[i];
    macs.push_back(std::make_unique<AutoDiscoveryMac>(config, id, scheduler));
    AutoDiscoveryMac* mac = macs.back().get();
    channel.attach(id, [mac](const v1::ModemTransmission& t) { mac->on_receive(t); });
    scheduler.at(starts[i], [&channel, mac, id] {
      channel.switch_on(id);
      mac->start([&channel, id](const v1::ModemTransmission& t) { channel.transmit(id, t); });
    });
  }

  std::vector<int32_t> sorted_ids = scenario.ids;
  std::sort(sorted_ids.begin(), sorted_ids.end());
  std::vector<std::vector<int32_t>> known;
  for (const auto& mac : macs) known.push_back(mac->known_ids());

  DiscoveryResult result;
  result.last_start_s = seconds_of(last_start);
  const Nanoseconds full_cycle = slot * static_cast<int64_t>(n + 1);
  const time_point end = last_start + std::chrono::duration_cast<Nanoseconds>(
                                          full_cycle * scenario.horizon_cycles);
  const mac::CycleGrid slots(std::nullopt, slot);
  const Nanoseconds probe = std::max(Nanoseconds(1), slot / 100);

  // Start of the cycle from which the network has been converged, if it is.
  bool converged = false;
  time_point converged_since{};
  Nanoseconds converged_cycle{0};
  int64_t collisions = 0, transmissions = 0, collided = 0;
  int64_t counts_at_convergence[3] = {0, 0, 0};

  for (time_point t = slots.next(first_start).start; t <= end; t = slots.next(t + probe).start) {
    // Slot start: what every node does (cycle starts and expiries happen at
    // the boundary, so they are settled a moment later).
    scheduler.run_until(t + probe);
    SlotTrace slot_trace;
    slot_trace.time_s = seconds_of(t);
    for (size_t i = 0; i < n; ++i) {
      const AutoDiscoveryMac& mac = *macs[i];
      NodeSlot node;
      node.action = action_of(mac.activity());
      node.cycle_start = mac.in_cycle() && mac.cycle_start() == t;
      if (node.cycle_start) node.cycle = srcs_of(mac.cycle());
      std::vector<int32_t> now_known = mac.known_ids();
      node.expired = minus(known[i], now_known);
      known[i] = std::move(now_known);
      slot_trace.nodes.push_back(std::move(node));
    }
    if (shared_cycle(macs, sorted_ids)) {
      if (!converged) {
        converged = true;
        converged_since = macs.front()->cycle_start();
        converged_cycle = slot * static_cast<int64_t>(macs.front()->cycle().size());
        counts_at_convergence[0] = collisions;
        counts_at_convergence[1] = transmissions;
        counts_at_convergence[2] = collided;
      }
      if (t >= converged_since + 2 * converged_cycle) break;
    } else {
      converged = false;
    }

    // Slot end: what was sent, heard and learnt.
    outcome.reset();
    scheduler.run_until(t + slot * 19 / 20);
    if (outcome && outcome->start == t) {
      slot_trace.transmitters = outcome->transmitters;
      transmissions += static_cast<int64_t>(outcome->transmitters.size());
      if (outcome->collision()) {
        ++collisions;
        collided += static_cast<int64_t>(outcome->transmitters.size());
        converged = false;
        for (size_t i = 0; i < n; ++i) {
          const int32_t id = scenario.ids[i];
          const bool sending = std::binary_search(outcome->transmitters.begin(),
                                                  outcome->transmitters.end(), id);
          if (!sending && slot_trace.nodes[i].action != NodeAction::kOff &&
              !outcome->received.count(id))
            slot_trace.lost.push_back(id);
        }
        std::sort(slot_trace.lost.begin(), slot_trace.lost.end());
      }
    }
    for (size_t i = 0; i < n; ++i) {
      std::vector<int32_t> now_known = macs[i]->known_ids();
      slot_trace.nodes[i].discovered = minus(now_known, known[i]);
      known[i] = std::move(now_known);
    }
    if (keep_trace) result.trace.push_back(std::move(slot_trace));
  }

  if (converged) {
    result.converged_at_s = seconds_of(converged_since);
    result.cycle_seconds = std::chrono::duration<double>(converged_cycle).count();
    collisions = counts_at_convergence[0];
    transmissions = counts_at_convergence[1];
    collided = counts_at_convergence[2];
  }
  result.collisions = collisions;
  result.transmissions = transmissions;
  result.collided_transmissions = collided;
  return result;
}

}  // namespace acomms::eval
