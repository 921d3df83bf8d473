// The route table's rules (route_table.h says why they are these).
#include "route/route_table.h"

#include <algorithm>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "core/core_thread.h"
#include "route/route_journal.h"

namespace acomms::route {
namespace {

constexpr int32_t kMaxNodeId = 65535;  // the envelope's 16-bit ids

bool valid_id(int64_t id) { return id >= 1 && id <= kMaxNodeId; }

}  // namespace

const char* to_string(RouteSource source) {
  switch (source) {
    case RouteSource::kStatic: return "static";
    case RouteSource::kLearnedDirect: return "heard";
    case RouteSource::kLearnedRelay: return "relayed";
  }
  return "?";
}

RouteTable::RouteTable(const v1::RoutingConfig& config, std::vector<std::string> links, int32_t own_id)
    : own_id_(own_id),
      links_(links),
      learned_max_age_s_(config.has_learned_max_age_s() ? config.learned_max_age_s() : kDefaultLearnedMaxAgeS) {
  if (!(learned_max_age_s_ > 0)) {
    throw std::invalid_argument("routing.learned_max_age_s must be > 0 (seconds a learned route stays usable)");
  }
  for (int i = 0; i < config.route_size(); ++i) {
    const v1::StaticRoute& r = config.route(i);
    const std::string where = "routing.route[" + std::to_string(i) + "]";
    const bool single = r.has_dest();
    const bool range = r.has_dest_min() || r.has_dest_max();
    if (single == range) {
      throw std::invalid_argument(where + ": give either dest or both dest_min and dest_max");
    }
    if (range && !(r.has_dest_min() && r.has_dest_max())) {
      throw std::invalid_argument(where + ": a range needs both dest_min and dest_max");
    }
    StaticRoute route;
    route.dest_min = single ? r.dest() : r.dest_min();
    route.dest_max = single ? r.dest() : r.dest_max();
    if (!valid_id(route.dest_min) || !valid_id(route.dest_max)) {
      throw std::invalid_argument(where + (single ? ".dest" : ".dest_min/dest_max") +
                                  ": node ids are 1..65535 (0 is broadcast, which is not routed)");
    }
    if (route.dest_min > route.dest_max) {
      throw std::invalid_argument(where + ": dest_min " + std::to_string(route.dest_min) + " is above dest_max " +
                                  std::to_string(route.dest_max));
    }
    if (!valid_id(r.next_hop()) || r.next_hop() == own_id) {
      throw std::invalid_argument(where + ".next_hop " + std::to_string(r.next_hop()) +
                                  ": must be another node's id, 1..65535 (this node is " + std::to_string(own_id) +
                                  ")");
    }
    if (links.empty()) throw std::invalid_argument(where + ": the node has no link");
    const std::string link = r.link().empty() ? links.front() : r.link();
    if (std::find(links.begin(), links.end(), link) == links.end()) {
      throw std::invalid_argument(where + ".link \"" + link + "\": the node has no such link");
    }
    route.next = {r.next_hop(), link, RouteSource::kStatic};
    static_.push_back(std::move(route));
  }
}

void RouteTable::attach(RouteJournal* journal, double now) {
  if (journal == nullptr) return;
  for (const StoredRoute& stored : journal->load_learned()) {
    if (stored.dest == own_id_ || stored.next.node == own_id_ ||
        std::find(links_.begin(), links_.end(), stored.next.link) == links_.end()) {
      spdlog::info("route: stored route to node {} through node {} on link \"{}\" no longer fits this node: dropped",
                   stored.dest, stored.next.node, stored.next.link);
      continue;
    }
    const double confirmed = std::min(stored.last_confirmed, now);
    Learned& learned = learned_[stored.dest];
    learned.next = stored.next;
    learned.last_confirmed = confirmed;
    learned.persisted = confirmed;
  }
  journal_ = journal;
}

void RouteTable::persist(int32_t dest, bool changed) {
  if (journal_ == nullptr) return;
  Learned& learned = learned_.at(dest);
  if (!changed && learned.persisted >= 0 && learned.last_confirmed - learned.persisted < kPersistEveryS) return;
  learned.persisted = learned.last_confirmed;
  journal_->save_learned(dest, learned.next, learned.last_confirmed);
}

std::optional<NextHop> RouteTable::next_hop(int32_t dest, double now) const {
  ACOMMS_ASSERT_CORE_THREAD();
  if (dest == own_id_) return std::nullopt;  // ours: delivered, never routed
  for (const StaticRoute& route : static_) {
    if (dest >= route.dest_min && dest <= route.dest_max) return route.next;
  }
  auto it = learned_.find(dest);
  if (it != learned_.end() && fresh(it->second, now)) return it->second.next;
  return std::nullopt;
}

void RouteTable::heard(int32_t node, const std::string& link, double now, bool two_way) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!valid_id(node) || node == own_id_) return;
  for (StaticRoute& route : static_) {
    if (route.next.node == node && route.next.link == link) route.last_confirmed = now;
  }
  auto it = learned_.find(node);
  if (it != learned_.end() && it->second.next.source == RouteSource::kLearnedRelay && fresh(it->second, now) &&
      !two_way && ++it->second.direct_hearings < kDirectHearings) {
    return;  // overheard: the relay that works stays until the node is heard again
  }
  const NextHop next{node, link, RouteSource::kLearnedDirect};
  Learned& learned = learned_[node];
  const bool changed = !(learned.next == next);
  learned.next = next;
  learned.last_confirmed = now;
  learned.direct_hearings = 0;
  persist(node, changed);
}

void RouteTable::heard_through(int32_t origin, int32_t via, const std::string& link, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!valid_id(origin) || !valid_id(via) || origin == own_id_ || origin == via) return;
  auto it = learned_.find(origin);
  // A neighbour heard directly lately beats a relay.
  if (it != learned_.end() && it->second.next.source == RouteSource::kLearnedDirect && fresh(it->second, now)) return;
  const NextHop next{via, link, RouteSource::kLearnedRelay};
  Learned& learned = learned_[origin];
  const bool changed = !(learned.next == next);
  learned.next = next;
  learned.last_confirmed = now;
  learned.direct_hearings = 0;
  persist(origin, changed);
}

std::vector<RouteEntry> RouteTable::list(double now) const {
  ACOMMS_ASSERT_CORE_THREAD();
  std::vector<RouteEntry> out;
  for (const StaticRoute& route : static_) {
    out.push_back({route.dest_min, route.dest_max, route.next, route.last_confirmed, false});
  }
  for (const auto& [dest, learned] : learned_) {
    out.push_back({dest, dest, learned.next, learned.last_confirmed, !fresh(learned, now)});
  }
  return out;
}

}  // namespace acomms::route
