#pragma once
// `acommsctl fleet import FILE...`: a starting fleet file from existing
// per-node config files.
//
// The decision: one abstract class, "common", holds every field on which
// all the configs agree (a scalar with the same value in all, a list equal
// in all); each node is named after its file (stem) and holds what differs
// from "common". Resolving a node of the result (core/fleet.h) gives back
// its config exactly: a list is in "common" only when every node has it
// equal (so no node repeats it), otherwise only in the nodes, whole, where
// merging onto nothing is the list itself. Deeper factoring (classes) is the
// person's: import is the first draft, not the design.
//
// Thread-safe: a function of its arguments.

#include <string>
#include <utility>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "acomms/v1/fleet.pb.h"

namespace acomms::core {

// (node name, its config) in order; names must be unique.
v1::FleetFile import_fleet(const std::vector<std::pair<std::string, v1::Config>>& nodes);

}  // namespace acomms::core
