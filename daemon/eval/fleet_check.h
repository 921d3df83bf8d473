#pragma once
// `acommsctl fleet check FLEET`: what would fail at sea, found before
// launch (README "Fleet configuration").
//
// The problem: each node's config can be valid alone and the fleet still
// broken: two nodes binding one DCCL id to different types (or to different
// versions of one type) decode each other's messages wrong; nodes on one
// link with different MAC cycles collide; a slot for a source no node has
// stays silent; two nodes with one modem id steal each other's ACKs; a route
// to nobody, or round in a loop, strands messages; a receiver without the
// sender's key refuses every authenticated or encrypted message; a slot too
// short for its rate sends nothing. Each is only visible across nodes.
//
// The decision: load every node (not class) of the fleet as acommsd would,
// its DCCL files included, and report each inconsistency as a Finding that
// names both places (file:line) a person must look at to fix it. Nodes
// "share a link" when they have a link of the same name and driver (the
// single top-level driver/mac is the link "default").
//
// Thread-safe: check_fleet shares nothing between calls (each node's DCCL
// definitions load into a codec of its own).

#include <string>
#include <vector>

#include "core/fleet.h"

namespace acomms::eval {

struct FleetFinding {
  std::string kind;  // "dccl-id", "dccl-version", "mac-cycle", "slot-source", "modem-id",
                     // "route-dest", "route-loop", "key", "slot-short", "node"
  std::string message;
  core::Origin first;
  core::Origin second;
};

// "FILE:LINE: KIND: MESSAGE (and FILE:LINE)".
std::string to_string(const FleetFinding& finding);

// Every finding, in the order: node errors, modem ids, DCCL, MAC, slots,
// routes, keys. Empty: the fleet may launch.
std::vector<FleetFinding> check_fleet(const core::Fleet& fleet);

}  // namespace acomms::eval
