#include "core/node_links.h"

#include <set>
#include <stdexcept>

namespace acomms::core {
namespace {

bool valid_link_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  }
  return true;
}

std::optional<LinkConfigProblem> route_problem(const google::protobuf::RepeatedPtrField<v1::LinkRoute>& routes,
                                               const std::set<std::string>& names,
                                               std::vector<std::string> where) {
  for (int i = 0; i < routes.size(); ++i) {
    const v1::LinkRoute& route = routes[i];
    if (route.link().empty()) return LinkConfigProblem{where, i, "a route names at least one link"};
    for (const std::string& link : route.link()) {
      if (names.count(link) == 0) {
        std::string known;
        for (const auto& n : names) known += (known.empty() ? "\"" : ", \"") + n + "\"";
        return LinkConfigProblem{where, i, "\"" + link + "\" is not one of this node's links (" + known + ")"};
      }
    }
    if (route.has_fallback_after_s() && !(route.fallback_after_s() >= 0)) {
      return LinkConfigProblem{where, i, "fallback_after_s must be 0 or more seconds"};
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<LinkConfigProblem> link_config_problem(const v1::Config& config) {
  std::set<std::string> names;
  if (config.link_size() > 0) {
    if (config.has_driver() || config.has_mac()) {
      return LinkConfigProblem{{config.has_driver() ? "driver" : "mac"}, 0,
                               "give the node's links either as `link { name ... driver {...} mac {...} }` "
                               "blocks or as one top-level driver and mac, not both"};
    }
    std::optional<uint32_t> id;
    std::string id_from;
    for (int i = 0; i < config.link_size(); ++i) {
      const v1::LinkConfig& link = config.link(i);
      if (link.name().empty()) return LinkConfigProblem{{"link", "name"}, i, "every link needs a name"};
      if (!valid_link_name(link.name())) {
        return LinkConfigProblem{{"link", "name"}, i,
                                 "\"" + link.name() + "\" is not a link name (lowercase letters, digits, '_')"};
      }
      if (!names.insert(link.name()).second) {
        return LinkConfigProblem{{"link", "name"}, i, "\"" + link.name() + "\" names two links"};
      }
      if (!(link.cost() >= 0)) return LinkConfigProblem{{"link", "cost"}, i, "must be 0 (no bar) or more"};
      uint32_t own = link.driver().modem_id();
      if (own == 0) continue;
      if (id && *id != own) {
        return LinkConfigProblem{{"link", "driver", "modem_id"}, i,
                                 "link \"" + link.name() + "\" has modem_id " + std::to_string(own) + " but link \"" +
                                     id_from + "\" has " + std::to_string(*id) +
                                     ": a node has one id on every link"};
      }
      id = own;
      id_from = link.name();
    }
  } else {
    names.insert(std::string(kDefaultLinkName));
  }
  if (auto p = route_problem(config.queue().route(), names, {"queue", "route", "link"})) return p;
  for (int t = 0; t < config.queue().type_size(); ++t) {
    if (auto p = route_problem(config.queue().type(t).route(), names, {"queue", "type", "route", "link"})) {
      p->index = t;  // the type's place: the field path cannot say both
      return p;
    }
  }
  return std::nullopt;
}

std::vector<v1::LinkConfig> node_links(const v1::Config& config) {
  if (auto p = link_config_problem(config)) {
    std::string dotted;
    for (const auto& part : p->field) dotted += (dotted.empty() ? "" : ".") + part;
    throw std::invalid_argument(dotted + ": " + p->problem);
  }
  std::vector<v1::LinkConfig> links;
  if (config.link_size() == 0) {
    v1::LinkConfig link;
    link.set_name(std::string(kDefaultLinkName));
    *link.mutable_driver() = config.driver();
    *link.mutable_mac() = config.mac();
    links.push_back(std::move(link));
  } else {
    links.assign(config.link().begin(), config.link().end());
  }
  uint32_t id = 0;
  for (const auto& link : links) id = id != 0 ? id : link.driver().modem_id();
  if (id == 0) id = 1;
  for (auto& link : links) link.mutable_driver()->set_modem_id(id);
  return links;
}

int32_t node_id(const v1::Config& config) { return static_cast<int32_t>(node_links(config).front().driver().modem_id()); }

}  // namespace acomms::core
