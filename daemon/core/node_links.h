#pragma once
// The links a node holds, from its config: the `link` blocks, or the
// single top-level `driver` and `mac` as one link named "default" (every
// config written before a node could hold several links).
//
// The decision on the node's id: one node has one id on every link (its
// queues, telemetry and routes know one address), so every link's
// driver.modem_id must agree; a link that leaves it unset takes the
// others', and a node that sets none is 1, as before.
//
// Thread-safe: functions of their input only.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "acomms/v1/config.pb.h"

namespace acomms::core {

inline constexpr std::string_view kDefaultLinkName = "default";

// What is wrong with the config's links, and where: `field` is the path
// under Config ("link.name"), `index` the link's place among the blocks.
struct LinkConfigProblem {
  std::vector<std::string> field;
  int index = 0;
  std::string problem;
};

// The first problem: both forms at once, a link without a name or with a
// name used twice or not of [a-z0-9_], modem ids that disagree, a route
// naming no link, a cost below 0. nullopt: fine.
std::optional<LinkConfigProblem> link_config_problem(const v1::Config& config);

// The node's links in config order, each with its modem_id set to the
// node's. Throws std::invalid_argument with link_config_problem's text.
std::vector<v1::LinkConfig> node_links(const v1::Config& config);

// The node's modem id (see the file comment). Throws like node_links.
int32_t node_id(const v1::Config& config);

}  // namespace acomms::core
