#include "eval/fleet_check_rules.h"

#include <algorithm>
#include <map>
#include <set>

namespace acomms::eval {

namespace {

using core::Origin;

const FleetNodeFacts* node_with_id(const std::vector<FleetNodeFacts>& nodes, int32_t id) {
  for (const FleetNodeFacts& node : nodes) {
    if (node.id == id) return &node;
  }
  return nullptr;
}

std::string route_path(int k) { return "routing.route[" + std::to_string(k) + "]"; }

bool covers(const v1::StaticRoute& route, int32_t dest) {
  if (route.has_dest()) return route.dest() == dest;
  return route.has_dest_min() && route.has_dest_max() && route.dest_min() <= dest && dest <= route.dest_max();
}

// The first static route of `node` for `dest`; -1 if none.
int route_for(const FleetNodeFacts& node, int32_t dest) {
  const v1::RoutingConfig& routing = node.node.config.routing();
  for (int k = 0; k < routing.route_size(); ++k) {
    if (covers(routing.route(k), dest)) return k;
  }
  return -1;
}

Origin keys_origin(const FleetNodeFacts& node, const std::string& path) {
  for (const std::string& at : {path, path + "[0]"}) {
    auto it = node.node.keys_where.find(at);
    if (it != node.node.keys_where.end()) return it->second;
  }
  return node.node.where;
}

bool loads(const FleetNodeFacts& node, const std::string& type) {
  return std::any_of(node.types.begin(), node.types.end(), [&](const FleetType& t) { return t.name == type; });
}

bool encrypts(const FleetNodeFacts& node) {
  const v1::DcclConfig& dccl = node.node.config.dccl();
  return dccl.has_passphrase() || !dccl.passphrase_file().empty();
}

std::string passphrase_name(const FleetNodeFacts& node) {
  if (!encrypts(node)) return "none";
  return node.node.keys.passphrase_id().empty() ? "(unnamed)" : node.node.keys.passphrase_id();
}

Origin passphrase_origin(const FleetNodeFacts& node) {
  if (!node.node.keys.passphrase_id().empty()) return keys_origin(node, "passphrase_id");
  const v1::DcclConfig& dccl = node.node.config.dccl();
  if (dccl.has_passphrase()) return origin_of(node, "dccl.passphrase");
  if (!dccl.passphrase_file().empty()) return origin_of(node, "dccl.passphrase_file");
  return node.node.where;
}

void check_loop_from(const std::vector<FleetNodeFacts>& nodes, const FleetNodeFacts& start, int k,
                     std::set<std::string>& reported, std::vector<FleetFinding>& out) {
  const int32_t dest = start.node.config.routing().route(k).dest();
  std::vector<const FleetNodeFacts*> visited{&start};
  const FleetNodeFacts* current = &start;
  int current_route = k;
  while (current->id != dest) {
    const FleetNodeFacts* next = node_with_id(nodes, current->node.config.routing().route(current_route).next_hop());
    if (next == nullptr || next->id == dest) return;
    if (std::find(visited.begin(), visited.end(), next) != visited.end()) {
      std::vector<std::string> names;
      for (const FleetNodeFacts* v : visited) names.push_back(v->node.name);
      std::sort(names.begin(), names.end());
      std::string key = std::to_string(dest);
      for (const std::string& name : names) key += "," + name;
      if (!reported.insert(key).second) return;
      std::string cycle;
      for (const FleetNodeFacts* v : visited) cycle += v->node.name + " -> ";
      out.push_back({"route-loop",
                     "routes for " + std::to_string(dest) + " go round: " + cycle + next->node.name,
                     origin_of(start, route_path(k)), origin_of(*current, route_path(current_route))});
      return;
    }
    visited.push_back(next);
    current = next;
    current_route = route_for(*current, dest);
    if (current_route < 0) return;  // learned routes take over from here
  }
}

}  // namespace

void check_routes(const std::vector<FleetNodeFacts>& nodes, std::vector<FleetFinding>& out) {
  std::set<std::string> reported;
  for (const FleetNodeFacts& node : nodes) {
    const v1::RoutingConfig& routing = node.node.config.routing();
    for (int k = 0; k < routing.route_size(); ++k) {
      const v1::StaticRoute& route = routing.route(k);
      if (route.has_dest() && route.dest() != 0 && node_with_id(nodes, route.dest()) == nullptr) {
        out.push_back({"route-dest",
                       node.node.name + ": a route to " + std::to_string(route.dest()) +
                           ", which no node of the fleet has (node " + node.node.name + " at the second place)",
                       origin_of(node, route_path(k) + ".dest"), node.node.where});
        continue;
      }
      const FleetNodeFacts* hop = node_with_id(nodes, route.next_hop());
      if (hop == nullptr) {
        out.push_back({"route-dest",
                       node.node.name + ": next hop " + std::to_string(route.next_hop()) +
                           " is no node of the fleet (node " + node.node.name + " at the second place)",
                       origin_of(node, route_path(k) + ".next_hop"), node.node.where});
        continue;
      }
      if (route.has_dest()) check_loop_from(nodes, node, k, reported, out);
    }
  }
}

void check_keys(const std::vector<FleetNodeFacts>& nodes, std::vector<FleetFinding>& out) {
  for (const FleetNodeFacts& sender : nodes) {
    const v1::AuthConfig& auth = sender.node.config.auth();
    for (int k = 0; k < auth.type_size(); ++k) {
      const std::string& type = auth.type(k).type();
      const Origin type_where = origin_of(sender, "auth.type[" + std::to_string(k) + "]");
      if (!sender.node.keys.has_sign_key_id()) {
        out.push_back({"key", sender.node.name + " authenticates " + type + " but its keys name no sign_key_id",
                       type_where, sender.node.where});
        continue;
      }
      const uint32_t sign = sender.node.keys.sign_key_id();
      for (const FleetNodeFacts& receiver : nodes) {
        if (&receiver == &sender || !loads(receiver, type)) continue;
        const auto& held = receiver.node.keys.key_id();
        if (std::find(held.begin(), held.end(), sign) != held.end()) continue;
        out.push_back({"key",
                       receiver.node.name + " receives " + type + " from " + sender.node.name +
                           ", authenticated with key id " + std::to_string(sign) + ", which " +
                           receiver.node.name + "'s keys lack",
                       keys_origin(sender, "sign_key_id"), keys_origin(receiver, "key_id")});
      }
    }
  }
  std::set<std::pair<std::string, std::string>> reported;
  for (const FleetNodeFacts& sender : nodes) {
    if (!encrypts(sender)) continue;
    const auto& exempt = sender.node.config.dccl().crypto_exempt_ids();
    for (const FleetNodeFacts& receiver : nodes) {
      if (&receiver == &sender || passphrase_name(receiver) == passphrase_name(sender)) continue;
      for (const FleetType& type : sender.types) {
        if (std::find(exempt.begin(), exempt.end(), type.id) != exempt.end() || !loads(receiver, type.name)) continue;
        auto pair = std::minmax(sender.node.name, receiver.node.name);
        if (!reported.insert({pair.first, pair.second}).second) break;
        out.push_back({"key",
                       sender.node.name + " encrypts " + type.name + " with passphrase " + passphrase_name(sender) +
                           "; " + receiver.node.name + " has " + passphrase_name(receiver),
                       passphrase_origin(sender), passphrase_origin(receiver)});
        break;
      }
    }
  }
}

}  // namespace acomms::eval
