#pragma once
// The node's side of node/unheard_packets.h: which of its links a telemetry
// gap's packets were lost on, and what those links already recorded.
//
// The decision: the losses already recorded are summed over every link
// (a sender heard on two links may have lost packets on either); the
// unheard packets go to the one link that last delivered a message from
// the sender (NodeLink::last_heard), the link it was talking to when the
// gap opened; none when no link ever heard it. No gap is counted while two links heard the
// sender within UnheardPackets::kSeveralLinks_s of each other (its messages
// may be in flight on the other). Kept out of the Daemon so
// that a test drives the same choice with links of its own.
//
// Core thread only (the hooks call NodeLink and LinkController).

#include <memory>
#include <vector>

#include "node/node_link.h"
#include "node/unheard_packets.h"

namespace acomms::node {

// Hooks over `links`, which must outlive them.
UnheardPackets::Hooks unheard_on_links(const std::vector<std::unique_ptr<NodeLink>>& links);

}  // namespace acomms::node
