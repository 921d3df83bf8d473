#pragma once
// acommsd's telemetry section (config.proto TelemetryConfig) turned into the
// library's TelemetryConfig and what the daemon adds around it.
//
// Thread-safe: pure functions; the NodeSettings they make is only read
// afterwards (its datum is shared const).

#include <memory>
#include <optional>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "telemetry/datum.h"
#include "telemetry/telemetry_config.h"

namespace acomms::telemetry {

struct NodeSettings {
  TelemetryConfig stream;  // what both ends of every stream must agree on
  std::vector<int32_t> receivers;
  std::shared_ptr<const Datum> datum;  // null: fixes must be local x/y
  double ttl_s = 1800;
  double gap_timeout_s = 1800;
};

// Defaults for unset fields (config.proto). Throws std::invalid_argument
// naming the field ("telemetry.ttl_s ...") and the bound it broke.
NodeSettings node_settings(const v1::TelemetryConfig& config, int32_t own_id);

// Adds the telemetry types' queues to `queues` (or completes an entry the
// operator wrote): source and destination roles, acked, oldest first (a
// delta is useless before the one it follows), the settings' ttl, kept
// out of the byte-level duplicate filter (the stream drops repeats by its
// sequence number), and refusing rather than dropping when full (the
// stream then sends a full).
void configure_queues(v1::QueueConfig* queues, const NodeSettings& settings);

}  // namespace acomms::telemetry
