// The text of the discovery evaluation: a scenario as a per-slot table a
// person can follow (who sends, who listens, which cycle each node starts,
// whom it discovers or expires, and each collision with who lost it), and
// the Monte Carlo as CSV. Tests and tools read the last line of a scenario
// ("converged_at_s=... collisions=...") and the CSV's columns, so those
// keep their shape; numbers print at up to 12 significant digits so a time
// like 43200.25 reads back as it was given.
#include "eval/discovery_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "mac/blank_slot.h"

namespace acomms::eval {
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
      << mac::blank_rule_name(scenario.blank_rule) << "; seed " << scenario.seed << "\n";
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
