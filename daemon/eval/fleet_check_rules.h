#pragma once
// The route and key checks of `fleet check` (eval/fleet_check.h), private
// to eval/.
//
// Thread-safe: functions of their arguments.

#include <vector>

#include "eval/fleet_check.h"
#include "eval/fleet_node_facts.h"

namespace acomms::eval {

// Static routes to or through an id no node has; routes that go round.
void check_routes(const std::vector<FleetNodeFacts>& nodes, std::vector<FleetFinding>& out);

// Authenticated types whose sender's signing key a receiver lacks;
// encrypted types whose receiver has another passphrase, or none.
void check_keys(const std::vector<FleetNodeFacts>& nodes, std::vector<FleetFinding>& out);

}  // namespace acomms::eval
