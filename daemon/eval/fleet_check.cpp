#include "eval/fleet_check.h"

#include <map>
#include <regex>
#include <set>

#include "eval/fleet_node_facts.h"
#include "eval/fleet_check_rules.h"
#include "link/driver_registry.h"
#include "link/slot_check.h"

namespace acomms::eval {

namespace {

using core::Origin;

void check_modem_ids(const std::vector<FleetNodeFacts>& nodes, std::vector<FleetFinding>& out) {
  std::map<int32_t, const FleetNodeFacts*> first;
  for (const FleetNodeFacts& node : nodes) {
    auto [it, fresh] = first.emplace(node.id, &node);
    if (fresh) continue;
    out.push_back({"modem-id",
                   "nodes " + it->second->node.name + " and " + node.node.name + " both have modem id " +
                       std::to_string(node.id),
                   it->second->id_where, node.id_where});
  }
}

void check_dccl_ids(const std::vector<FleetNodeFacts>& nodes, std::vector<FleetFinding>& out) {
  struct Seen {
    const FleetNodeFacts* node;
    const FleetType* type;
  };
  std::map<int, Seen> by_id;
  std::set<std::string> reported;
  for (const FleetNodeFacts& node : nodes) {
    for (const FleetType& type : node.types) {
      if (type.id < 0) continue;
      auto [it, fresh] = by_id.emplace(type.id, Seen{&node, &type});
      if (fresh) continue;
      const Seen& before = it->second;
      std::string kind;
      std::string what;
      if (before.type->name != type.name) {
        kind = "dccl-id";
        what = "DCCL id " + std::to_string(type.id) + " is " + before.type->name + " in " + before.node->node.name +
               " but " + type.name + " in " + node.node.name;
      } else if (before.type->fingerprint != type.fingerprint) {
        kind = "dccl-version";
        what = "DCCL id " + std::to_string(type.id) + " (" + type.name + ") is defined differently in " +
               before.node->node.name + " and " + node.node.name;
      } else {
        continue;
      }
      if (!reported.insert(kind + std::to_string(type.id) + node.node.name).second) continue;
      out.push_back({kind, what, before.type->where, type.where});
    }
  }
}

// Nodes sharing a link: same link name and driver.
using LinkKey = std::pair<std::string, std::string>;

LinkKey key_of(const v1::LinkConfig& link) { return {link.name(), link.driver().name()}; }

void check_mac_cycles(const std::vector<FleetNodeFacts>& nodes, std::vector<FleetFinding>& out) {
  std::map<LinkKey, std::pair<const FleetNodeFacts*, size_t>> reference;
  for (const FleetNodeFacts& node : nodes) {
    for (size_t l = 0; l < node.links.size(); ++l) {
      const v1::LinkConfig& link = node.links[l];
      if (link.mac().name() == "none" || link.mac().name().empty()) continue;
      auto [it, fresh] = reference.emplace(key_of(link), std::make_pair(&node, l));
      if (fresh) continue;
      const auto& [other, ol] = it->second;
      const v1::LinkConfig& theirs = other->links[ol];
      auto [a, b] = first_difference(theirs.mac(), other->link_paths[ol] + "mac.", link.mac(), node.link_paths[l] + "mac.");
      if (a.empty() && b.empty()) continue;
      out.push_back({"mac-cycle",
                     "link " + link.name() + ": the MAC cycle of " + node.node.name + " differs from " +
                         other->node.name + "'s (" + b + " / " + a + ")",
                     origin_of(*other, a), origin_of(node, b)});
    }
  }
}

// A slot written once for many nodes (a cruise's cycle) is one finding.
bool first_time(std::set<std::string>& reported, const FleetFinding& finding) {
  return reported
      .insert(finding.kind + core::to_string(finding.first) + core::to_string(finding.second) + finding.message)
      .second;
}

void check_slot_sources(const std::vector<FleetNodeFacts>& nodes, std::vector<FleetFinding>& out) {
  std::set<std::string> reported;
  std::map<LinkKey, std::set<int32_t>> ids_on;
  for (const FleetNodeFacts& node : nodes) {
    for (const v1::LinkConfig& link : node.links) ids_on[key_of(link)].insert(node.id);
  }
  for (const FleetNodeFacts& node : nodes) {
    for (size_t l = 0; l < node.links.size(); ++l) {
      const v1::MacConfig& mac = node.links[l].mac();
      if (mac.name() != "fixed" && mac.name() != "polled") continue;
      const std::set<int32_t>& ids = ids_on[key_of(node.links[l])];
      for (int s = 0; s < mac.slot_size(); ++s) {
        if (ids.count(mac.slot(s).src())) continue;
        const std::string path = node.link_paths[l] + "mac.slot[" + std::to_string(s) + "].src";
        FleetFinding finding{"slot-source",
                             "slot " + std::to_string(s + 1) + " is for src " + std::to_string(mac.slot(s).src()) +
                                 ", which no node on link " + node.links[l].name() + " has (the cycle: second place)",
                             origin_of(node, path), origin_of(node, node.link_paths[l] + "mac.name")};
        if (first_time(reported, finding)) out.push_back(std::move(finding));
      }
    }
  }
}

void check_short_slots(const std::vector<FleetNodeFacts>& nodes, std::vector<FleetFinding>& out) {
  std::set<std::string> reported;
  static const std::regex slot_number(R"((?:link (\w+): )?mac slot (\d+) )");
  for (const FleetNodeFacts& node : nodes) {
    std::vector<std::string> warnings;
    try {
      warnings = link::short_slot_warnings(node.node.config, link::DriverRegistry::linked());
    } catch (const std::exception& e) {
      out.push_back({"node", node.node.name + ": " + e.what(), origin_of(node, "mac"), node.node.where});
      continue;
    }
    for (const std::string& warning : warnings) {
      std::smatch match;
      std::string slot_path = "mac";
      std::string rate_path = "mac";
      if (std::regex_search(warning, match, slot_number)) {
        size_t l = 0;
        for (; l < node.links.size() && match[1].matched && node.links[l].name() != match[1].str(); ++l) {
        }
        const std::string prefix = l < node.link_paths.size() ? node.link_paths[l] : "";
        const std::string slot = prefix + "mac.slot[" + std::to_string(std::stoi(match[2]) - 1) + "]";
        slot_path = slot + ".seconds";
        rate_path = slot + ".rate";
      }
      FleetFinding finding{"slot-short", warning, origin_of(node, slot_path), origin_of(node, rate_path)};
      if (first_time(reported, finding)) out.push_back(std::move(finding));
    }
  }
}

}  // namespace

std::string to_string(const FleetFinding& finding) {
  return core::to_string(finding.first) + ": " + finding.kind + ": " + finding.message + " (and " +
         core::to_string(finding.second) + ")";
}

std::vector<FleetFinding> check_fleet(const core::Fleet& fleet) {
  std::vector<FleetFinding> findings;
  std::vector<FleetNodeFacts> nodes;
  for (const std::string& name : fleet.node_names()) {
    FleetNodeFacts facts = node_facts(fleet, name);
    if (!facts.problem.empty()) {
      findings.push_back({"node", facts.problem, facts.problem_where, facts.node.where});
    }
    if (facts.loaded) nodes.push_back(std::move(facts));
  }
  check_modem_ids(nodes, findings);
  check_dccl_ids(nodes, findings);
  check_mac_cycles(nodes, findings);
  check_slot_sources(nodes, findings);
  check_short_slots(nodes, findings);
  check_routes(nodes, findings);
  check_keys(nodes, findings);
  return findings;
}

}  // namespace acomms::eval
