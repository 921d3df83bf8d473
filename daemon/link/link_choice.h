#pragma once
// Which of a node's links may carry a message now.
//
// A vehicle holds an acoustic modem and a satellite modem; the shore is
// reached by either, and bytes on the satellite are paid for. The operator
// says, per type and destination, which links to use in order
// (LinkRoute: acoustic, then iridium when acoustic has not reached the
// shore for 10 min), and per link what sending there costs
// (LinkConfig.cost, in the queues' priority units). The rule, in full:
//
//   * A link that is disabled or whose driver is down carries nothing.
//   * A route applies: the type's own routes, then the queue-wide ones,
//     the first whose dest is the message's or unset. Its carrier is the
//     first usable link in its list that reached the destination (an ACK
//     or any reception from that node on that link) within
//     fallback_after_s; when none did, the last usable link in the list.
//     Only the carrier may carry the message. A link not yet heard from
//     counts as reached when the choice was made (the node's start), so
//     the first link gets its full silence before the next takes over.
//   * No route applies: any usable link may.
//   * Either way, the type's priority must beat the link's cost (cost 0:
//     no bar).
//
// One link at a time is the queues' half (queue/frame.h DataRequest::link):
// a message awaiting an ACK on one link is not in another link's contest.
//
// Core thread only (the links' controllers call it); asserted.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "acomms/v1/config.pb.h"

namespace acomms::link {

class LinkChoice {
 public:
  struct Link {
    std::string name;
    double cost = 0;
  };
  struct Route {
    std::string type;              // "": every type
    std::optional<int32_t> dest;   // nullopt: every destination
    std::vector<int> links;        // indices into the links, preferred first
    double fallback_after_s = 600;
  };

  // `start_s`: when the node started (what "not heard since" counts from).
  LinkChoice(std::vector<Link> links, std::vector<Route> routes, double start_s);

  // The links and routes of a node's config (node_links order); throws
  // std::invalid_argument for a route naming no such link.
  static LinkChoice from_config(const std::vector<v1::LinkConfig>& links, const v1::QueueConfig& queue,
                                double start_s);

  // `node` was heard on `link` at `now_s` (a reception from it, or its ACK).
  void reached(int link, int32_t node, double now_s);
  // Enabled (operator, depth) and driver running: both needed to carry.
  void set_enabled(int link, bool enabled);
  void set_driver_up(int link, bool up);
  bool enabled(int link) const { return state_.at(link).enabled; }
  bool usable(int link) const { return state_.at(link).enabled && state_.at(link).driver_up; }

  // Whether `link` may carry a `type` message to `dest` now, its type's
  // priority being `priority` (the rule above). For a routed message `dest`
  // is its next hop, not its final destination: the link reaches the
  // neighbour, and the route (route/) chose that neighbour.
  bool may_carry(int link, const std::string& type, int32_t dest, double priority, double now_s) const;
  // The link that carries (`type`, `dest`) now, cost aside: -1 when none
  // may, or when no route applies (any may).
  int carrier(const std::string& type, int32_t dest, double now_s) const;

  size_t size() const { return links_.size(); }
  const Link& link(int index) const { return links_.at(index); }
  // -1 when no link has that name.
  int index_of(const std::string& name) const;

 private:
  struct State {
    bool enabled = true;
    bool driver_up = true;
    std::map<int32_t, double> heard;  // node -> last time reached
    double any_heard = -1;            // any node (a broadcast's "reached")
  };
  const Route* route_for(const std::string& type, int32_t dest) const;
  double last_reached(int link, int32_t dest) const;

  std::vector<Link> links_;
  std::vector<Route> routes_;
  std::vector<State> state_;
  double start_s_;
};

}  // namespace acomms::link
