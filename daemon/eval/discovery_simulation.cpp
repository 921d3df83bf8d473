#include "eval/discovery_simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/scheduler.h"
#include "eval/simulated_channel.h"
#include "mac/auto_discovery_mac.h"
#include "mac/cycle_grid.h"
#include "util/splitmix64.h"

namespace acomms::eval {
namespace {

using mac::AutoDiscoveryConfig;
using mac::AutoDiscoveryMac;
using mac::BlankRule;
using mac::blank_rule_name;
using mac::Nanoseconds;
using time_point = core::Clock::time_point;
using util::SplitMix64;

// The simulated day: 2024-06-01T00:00:00Z.
constexpr int64_t kDayStart = 1717200000;
constexpr int32_t kMaxModemId = 127;

time_point at_seconds(double seconds_since_midnight) {
  // Milliseconds, as the issue's start times are; integer arithmetic, as a
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

namespace {

std::string number(double value) {
  std::ostringstream out;
  out << std::setprecision(12) << value;
  return out.str();
}

std::string clock_time(double seconds) {
  double day = std::fmod(seconds, 86400.0);
  if (day < 0) day += 86400;
  const int64_t whole = static_cast<int64_t>(std::floor(day));
  char text[32];
  std::snprintf(text, sizeof text, "%02lld:%02lld:%02lld", static_cast<long long>(whole / 3600),
                static_cast<long long>(whole / 60 % 60), static_cast<long long>(whole % 60));
  std::string out = text;
  const double fraction = day - static_cast<double>(whole);
  if (fraction > 5e-4) {
    std::snprintf(text, sizeof text, "%.3f", fraction);
    out += text + 1;  // ".xyz"
  }
  return out;
}

std::string id_list(const std::vector<int32_t>& ids, const char* separator) {
  std::string out;
  for (size_t i = 0; i < ids.size(); ++i) {
    if (i) out += separator;
    out += std::to_string(ids[i]);
  }
  return out;
}

std::string cycle_text(const std::vector<int32_t>& cycle) {
  std::string out = "[";
  for (size_t i = 0; i < cycle.size(); ++i) {
    if (i) out += ' ';
    out += cycle[i] == 0 ? std::string("_") : std::to_string(cycle[i]);
  }
  return out + "]";
}

const char* action_name(NodeAction action) {
  switch (action) {
    case NodeAction::kOff: return "off";
    case NodeAction::kWait: return "wait";
    case NodeAction::kSend: return "send";
    case NodeAction::kBlank: return "blank";
    case NodeAction::kListen: return "listen";
  }
  return "?";
}

std::string cell(const NodeSlot& node) {
  std::string out = action_name(node.action);
  if (node.cycle_start) {
    out += ' ';
    out += cycle_text(node.cycle);
  }
  for (int32_t id : node.expired) {
    out += " -";
    out += std::to_string(id);
  }
  for (int32_t id : node.discovered) {
    out += " +";
    out += std::to_string(id);
  }
  return out;
}

std::string channel_cell(const SlotTrace& slot) {
  if (slot.transmitters.empty()) return "-";
  if (slot.transmitters.size() == 1) return "tx " + id_list(slot.transmitters, ",");
  std::string out = "COLLISION " + id_list(slot.transmitters, ",");
  if (!slot.lost.empty()) out += " (lost by " + id_list(slot.lost, ",") + ")";
  return out;
}

}  // namespace

std::string format_discovery(const DiscoveryScenario& scenario, const DiscoveryResult& result) {
  std::ostringstream out;
  out << "# mac-discovery: ids " << id_list(scenario.ids, ",") << "; slot " << number(scenario.slot_seconds)
      << " s; coolness " << scenario.coolness << "; p_collide " << number(scenario.p_collide)
      << "; expire_cycles " << scenario.expire_cycles << "; blank rule "
      << blank_rule_name(scenario.blank_rule) << "; seed " << scenario.seed << "\n";
  out << "# power-on (s since midnight UTC):";
  for (size_t i = 0; i < scenario.ids.size(); ++i)
    out << " " << scenario.ids[i] << "@"
        << number(scenario.start_s.size() == 1 ? scenario.start_s[0] : scenario.start_s[i]);
  out << "\n# send: own slot; blank: listening in the blank; listen: another known node's slot;\n"
         "# wait: silent until its next cycle boundary; off: not powered on yet.\n"
         "# [..]: the cycle a node starts here (_ = blank); +N: discovered N; -N: expired N.\n";

  std::vector<std::string> header = {"time_s", "utc"};
  for (int32_t id : scenario.ids) header.push_back("node " + std::to_string(id));
  header.push_back("channel");
  std::vector<std::vector<std::string>> rows;
  for (const SlotTrace& slot : result.trace) {
    std::vector<std::string> row = {number(slot.time_s), clock_time(slot.time_s)};
    for (const NodeSlot& node : slot.nodes) row.push_back(cell(node));
    row.push_back(channel_cell(slot));
    rows.push_back(std::move(row));
  }
  std::vector<size_t> width(header.size());
  for (size_t c = 0; c < header.size(); ++c) {
    width[c] = header[c].size();
    for (const auto& row : rows) width[c] = std::max(width[c], row[c].size());
  }
  auto print = [&](const std::vector<std::string>& row) {
    std::string line;
    for (size_t c = 0; c < row.size(); ++c) {
      line += row[c];
      if (c + 1 < row.size()) line += std::string(width[c] - row[c].size() + 2, ' ');
    }
    out << line << "\n";
  };
  print(header);
  for (const auto& row : rows) print(row);

  if (result.converged_at_s) {
    const double after = *result.converged_at_s - result.last_start_s;
    out << "# converged: one shared collision-free cycle of " << number(result.cycle_seconds)
        << " s from " << number(*result.converged_at_s) << " s (" << clock_time(*result.converged_at_s)
        << "), " << number(after) << " s = " << std::fixed << std::setprecision(2)
        << after / result.cycle_seconds << std::defaultfloat
        << " cycles after the last power-on\n";
    out << "converged_at_s=" << number(*result.converged_at_s);
  } else {
    out << "# never converged within " << number(scenario.horizon_cycles)
        << " full-network cycles after the last power-on\n";
    out << "converged_at_s=never";
  }
  out << " collisions=" << result.collisions << "\n";
  return out.str();
}

namespace {

struct Network {
  std::vector<int32_t> ids;
  std::vector<double> start_s;
  uint64_t channel_seed = 0;
};

Network draw_network(const DiscoveryMonteCarloConfig& config, int nodes, int trial) {
  SplitMix64 random(config.seed * 0x100000001b3ULL ^ (static_cast<uint64_t>(nodes) << 40) ^
                    static_cast<uint64_t>(trial));
  random.next();
  Network network;
  std::set<int32_t> ids;
  while (static_cast<int>(ids.size()) < nodes)
    ids.insert(1 + static_cast<int32_t>(random.below(kMaxModemId)));
  network.ids.assign(ids.begin(), ids.end());
  // Shuffled, so that power-on order is not id order.
  for (size_t i = network.ids.size(); i > 1; --i)
    std::swap(network.ids[i - 1], network.ids[random.below(i)]);
  const double cycle = config.slot_seconds * (nodes + 1);
  const double window = config.start_window_cycles * cycle;
  const double room = 86400 - window - (config.horizon_cycles + 3) * cycle;
  const double base = room > 0 ? std::floor(random.uniform() * room) : 0;
  for (int i = 0; i < nodes; ++i)
    network.start_s.push_back(base + std::round(random.uniform() * window * 1e3) / 1e3);
  network.channel_seed = random.next();
  return network;
}

}  // namespace

std::vector<DiscoveryPoint> simulate_discovery_monte_carlo(const DiscoveryMonteCarloConfig& config) {
  if (config.trials < 1) throw std::invalid_argument("--trials must be >= 1");
  for (int nodes : config.sizes)
    if (nodes < 1 || nodes > kMaxModemId)
      throw std::invalid_argument("--sizes: a network has 1 to 127 nodes");
  std::vector<DiscoveryPoint> points;
  for (int nodes : config.sizes) {
    std::vector<Network> networks;
    for (int j = 0; j < config.trials; ++j) networks.push_back(draw_network(config, nodes, j));
    for (uint32_t coolness_choice : config.coolness) {
      const uint32_t coolness = coolness_choice == 0 ? static_cast<uint32_t>(nodes + 1) : coolness_choice;
      for (double p_collide : config.p_collide) {
        int64_t transmissions = 0, collided = 0, converged = 0;
        double slots_total = 0;
        for (const Network& network : networks) {
          DiscoveryScenario scenario;
          scenario.ids = network.ids;
          scenario.start_s = network.start_s;
          scenario.slot_seconds = config.slot_seconds;
          scenario.coolness = coolness;
          scenario.expire_cycles = config.expire_cycles;
          scenario.blank_rule = config.blank_rule;
          scenario.p_collide = p_collide;
          scenario.seed = network.channel_seed;
          scenario.horizon_cycles = config.horizon_cycles;
          DiscoveryResult result = simulate_discovery(scenario, false);
          transmissions += result.transmissions;
          collided += result.collided_transmissions;
          if (result.converged_at_s) {
            ++converged;
            slots_total += (*result.converged_at_s - result.last_start_s) / config.slot_seconds;
          }
        }
        DiscoveryPoint point;
        point.nodes = nodes;
        point.coolness = coolness;
        point.p_collide = p_collide;
        point.collision_prob =
            transmissions ? static_cast<double>(collided) / static_cast<double>(transmissions) : 0;
        point.mean_discovery_slots =
            converged ? slots_total / static_cast<double>(converged) : std::nan("");
        point.fail_pct = 100.0 * static_cast<double>(config.trials - converged) / config.trials;
        points.push_back(point);
      }
    }
  }
  return points;
}

std::string format_discovery_csv(const std::vector<DiscoveryPoint>& points) {
  std::ostringstream out;
  out << "nodes,coolness,p_collide,collision_prob,mean_discovery_slots,fail_pct\n";
  char line[160];
  for (const DiscoveryPoint& p : points) {
    std::string slots = std::isnan(p.mean_discovery_slots) ? std::string("nan") : [&] {
      char text[32];
      std::snprintf(text, sizeof text, "%.2f", p.mean_discovery_slots);
      return std::string(text);
    }();
    std::snprintf(line, sizeof line, "%d,%u,%s,%.4f,%s,%.2f\n", p.nodes, p.coolness,
                  number(p.p_collide).c_str(), p.collision_prob, slots.c_str(), p.fail_pct);
    out << line;
  }
  return out.str();
}

}  // namespace acomms::eval
