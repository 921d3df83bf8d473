#pragma once
// What `fleet check` knows of one node of a fleet (eval/fleet_check.h): its
// resolved config, its id, its links, the DCCL types it loads, each with
// the place in the fleet files that gave it.
//
// Thread-safe: functions of their arguments; each node's definitions load
// into a codec of its own.

#include <cstdint>
#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "core/fleet.h"

namespace acomms::eval {

struct FleetType {
  std::string name;
  int id = -1;
  std::string fingerprint;  // the descriptor and every type it uses: equal means the same version
  core::Origin where;       // the proto_files line that loaded it
};

struct FleetNodeFacts {
  core::ResolvedNode node;
  bool loaded = false;  // false: `problem` says why nothing else is known
  std::string problem;
  core::Origin problem_where;
  int32_t id = 1;
  core::Origin id_where;
  std::vector<v1::LinkConfig> links;
  std::vector<std::string> link_paths;  // "" (the top-level driver/mac) or "link[i]."
  std::vector<FleetType> types;
};

FleetNodeFacts node_facts(const core::Fleet& fleet, const std::string& name);

// The place `path` (or the nearest enclosing field that has one) was
// written; the node's own line if none.
core::Origin origin_of(const FleetNodeFacts& node, const std::string& path);

// The first field where two messages of one type differ, as a path under
// each (prefixed with `a_prefix` / `b_prefix`); "" if equal.
std::pair<std::string, std::string> first_difference(const google::protobuf::Message& a, const std::string& a_prefix,
                                                     const google::protobuf::Message& b, const std::string& b_prefix);

}  // namespace acomms::eval
