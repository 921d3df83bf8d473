#pragma once
// Where a message for a node that is not this one goes next: the route
// table of a gateway (config `routing`, README "Gateways: routes and the
// envelope").
//
// The problem. A gateway buoy forwards a shore's command to a vehicle it
// hears acoustically; the shore must know to hand that command to the buoy,
// over the satellite link. Some of this is known in advance (the fleet's
// plan: "vehicles 10-19 through buoy 2 on iridium"), some only from traffic
// (which buoy last heard vehicle 12; which vehicle is in range now).
//
// The decision. Two kinds of route, each listed with where it came from and
// when it was last confirmed:
//  - static, from the config, tried in the config's order (first match
//    wins: put exact destinations before ranges). One is confirmed each
//    time its next hop is heard on its link.
//  - learned: a node heard on a link is reachable there directly (next hop
//    itself); a routed message from origin O handed over by neighbour N on
//    link L says O is reachable through N on L, unless O was heard directly
//    within the age limit (a direct neighbour beats a relay). A relayed
//    route that still works is not given up for one packet overheard from
//    the far node (at the fringe of range it proves nothing): it turns
//    direct after kDirectHearings receptions from that node since the
//    relay was last confirmed, or at once on an ACK from it to this node
//    (both ways work). A learned
//    route is used until `learned_max_age_s` after it was last confirmed;
//    older ones are still listed (stale), never chosen.
// Learned routes outlive a restart when a RouteJournal is attached
// (route_journal.h, migrations/0015): each is stored with its source and
// last-confirmed time (the wall clock's, so it ages while the node is
// down), when it changes and at most every kPersistEveryS while it is only
// confirmed again (a stored time is at most that much older than the real
// one: after a restart a route looks older, never younger, than it is).
// A relay's count of direct hearings is not kept; a stored route for a
// link the node no longer has, or to the node itself, is dropped at start.
// Static routes are tried before learned ones: the operator's plan wins.
// A route never leads to this node itself or to a link it does not have
// (checked at construction, naming the field).
//
// Threads: core thread only (plain class, no locks): the link controllers
// that hear traffic and the forwarder that asks for routes both run there.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"

namespace acomms::route {

class RouteJournal;  // route_journal.h

enum class RouteSource { kStatic, kLearnedDirect, kLearnedRelay };

// "static", "heard", "relayed".
const char* to_string(RouteSource source);

struct NextHop {
  int32_t node = 0;  // the neighbour to hand the message to
  std::string link;  // on this link (LinkConfig.name)
  RouteSource source = RouteSource::kStatic;
  bool operator==(const NextHop&) const = default;
};

// One row of `acommsctl route ls`.
struct RouteEntry {
  int32_t dest_min = 0;
  int32_t dest_max = 0;  // == dest_min for a single destination
  NextHop next;
  // When the route was last confirmed (next hop heard on its link), in the
  // clock's seconds; nullopt: never since start.
  std::optional<double> last_confirmed;
  // Learned routes: past learned_max_age_s, listed but not used.
  bool stale = false;
};

class RouteTable {
 public:
  inline static constexpr double kDefaultLearnedMaxAgeS = 1800;
  // Receptions from a node that turn a fresh relayed route to it direct.
  inline static constexpr int kDirectHearings = 3;
  // A learned route confirmed again is written at most this often.
  inline static constexpr double kPersistEveryS = 30;

  // `links`: the node's link names, first is the default. Throws
  // std::invalid_argument naming routing.route[i] and the field when a
  // route has neither or both of dest and dest_min/dest_max, a range with
  // min > max or ids outside 1..65535, a next hop that is this node or not
  // in 1..65535, or a link the node does not have.
  RouteTable(const v1::RoutingConfig& config, std::vector<std::string> links, int32_t own_id);

  // Reads back the learned routes `journal` holds (a last-confirmed time
  // after `now`, the clock having gone back, is taken as `now`) and writes
  // learned routes through to it from then on. `journal` must outlive
  // this. At start, before any other call. Throws store::StoreError.
  void attach(RouteJournal* journal, double now);

  // The next hop for `dest` at `now`, or nullopt: the message waits.
  std::optional<NextHop> next_hop(int32_t dest, double now) const;

  // Node `node` was heard on `link` (any reception from it; `two_way`: an
  // ACK from it to this node): it is a neighbour there, and static routes
  // through it on that link are confirmed.
  void heard(int32_t node, const std::string& link, double now, bool two_way = false);
  // A routed message from `origin` was handed over by neighbour `via` on
  // `link`: `origin` is reachable through `via` there.
  void heard_through(int32_t origin, int32_t via, const std::string& link, double now);

  // Every route, static ones first in config order, then learned ones by
  // destination.
  std::vector<RouteEntry> list(double now) const;

  double learned_max_age_s() const { return learned_max_age_s_; }

 private:
  struct StaticRoute {
    int32_t dest_min;
    int32_t dest_max;
    NextHop next;
    std::optional<double> last_confirmed;
  };
  struct Learned {
    NextHop next;
    double last_confirmed;
    int direct_hearings = 0;  // a relayed route: receptions from the node itself since
    double persisted = -1;    // the last_confirmed last written (-1: not written)
  };
  // Writes the learned route to `dest` when it changed or kPersistEveryS
  // passed since it was last written (`changed`: its next hop did).
  void persist(int32_t dest, bool changed);
  bool fresh(const Learned& learned, double now) const { return now - learned.last_confirmed <= learned_max_age_s_; }

  int32_t own_id_;
  std::vector<std::string> links_;
  RouteJournal* journal_ = nullptr;
  double learned_max_age_s_;
  std::vector<StaticRoute> static_;
  std::map<int32_t, Learned> learned_;
};

}  // namespace acomms::route
