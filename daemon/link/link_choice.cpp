#include "link/link_choice.h"

#include <algorithm>
#include <stdexcept>

#include "core/core_thread.h"

namespace acomms::link {
namespace {

// Modem id 0 is the broadcast address (DriverConfig.modem_id; the queues'
// kBroadcast).
constexpr int32_t kBroadcastId = 0;

}  // namespace

LinkChoice::LinkChoice(std::vector<Link> links, std::vector<Route> routes, double start_s)
    : links_(std::move(links)), routes_(std::move(routes)), state_(links_.size()), start_s_(start_s) {
  for (const Route& route : routes_) {
    for (int index : route.links) {
      if (index < 0 || static_cast<size_t>(index) >= links_.size()) {
        throw std::invalid_argument("a link route names link " + std::to_string(index) + " of " +
                                    std::to_string(links_.size()));
      }
    }
  }
}

LinkChoice LinkChoice::from_config(const std::vector<v1::LinkConfig>& links, const v1::QueueConfig& queue,
                                   double start_s) {
  std::vector<Link> terms;
  for (const v1::LinkConfig& link : links) terms.push_back({link.name(), link.cost()});
  auto index = [&](const std::string& name) {
    for (size_t i = 0; i < links.size(); ++i) {
      if (links[i].name() == name) return static_cast<int>(i);
    }
    throw std::invalid_argument("route: \"" + name + "\" is not one of this node's links");
  };
  std::vector<Route> routes;
  auto add = [&](const std::string& type, const v1::LinkRoute& configured) {
    Route route;
    route.type = type;
    if (configured.has_dest()) route.dest = configured.dest();
    for (const std::string& name : configured.link()) route.links.push_back(index(name));
    if (configured.has_fallback_after_s()) route.fallback_after_s = configured.fallback_after_s();
    routes.push_back(std::move(route));
  };
  // A type's own routes first, so route_for's first match prefers them.
  for (const v1::QueueTypeConfig& type : queue.type()) {
    for (const v1::LinkRoute& route : type.route()) add(type.type(), route);
  }
  for (const v1::LinkRoute& route : queue.route()) add("", route);
  return LinkChoice(std::move(terms), std::move(routes), start_s);
}

void LinkChoice::reached(int link, int32_t node, double now_s) {
  ACOMMS_ASSERT_CORE_THREAD();
  State& state = state_.at(link);
  state.heard[node] = now_s;
  state.any_heard = now_s;
}

void LinkChoice::set_enabled(int link, bool enabled) {
  ACOMMS_ASSERT_CORE_THREAD();
  state_.at(link).enabled = enabled;
}

void LinkChoice::set_driver_up(int link, bool up) {
  ACOMMS_ASSERT_CORE_THREAD();
  state_.at(link).driver_up = up;
}

int LinkChoice::index_of(const std::string& name) const {
  for (size_t i = 0; i < links_.size(); ++i) {
    if (links_[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

const LinkChoice::Route* LinkChoice::route_for(const std::string& type, int32_t dest) const {
  // Two passes: a type's own routes win over the queue-wide ones wherever
  // they stand in the list.
  for (const Route& route : routes_) {
    if (route.type == type && (!route.dest || *route.dest == dest)) return &route;
  }
  for (const Route& route : routes_) {
    if (route.type.empty() && (!route.dest || *route.dest == dest)) return &route;
  }
  return nullptr;
}

double LinkChoice::last_reached(int link, int32_t dest) const {
  const State& state = state_.at(link);
  // A broadcast reaches whoever hears the link: any reception will do.
  if (dest == kBroadcastId) return std::max(start_s_, state.any_heard);
  auto it = state.heard.find(dest);
  return it == state.heard.end() ? start_s_ : std::max(start_s_, it->second);
}

int LinkChoice::carrier(const std::string& type, int32_t dest, double now_s) const {
  ACOMMS_ASSERT_CORE_THREAD();
  const Route* route = route_for(type, dest);
  if (route == nullptr) return -1;
  int last_usable = -1;
  for (int link : route->links) {
    if (!usable(link)) continue;
    if (now_s - last_reached(link, dest) <= route->fallback_after_s) return link;
    last_usable = link;
  }
  return last_usable;
}

bool LinkChoice::may_carry(int link, const std::string& type, int32_t dest, double priority, double now_s) const {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!usable(link)) return false;
  const double cost = links_.at(link).cost;
  if (cost > 0 && !(priority > cost)) return false;
  if (route_for(type, dest) == nullptr) return true;
  return carrier(type, dest, now_s) == link;
}

}  // namespace acomms::link
