#pragma once
// A reconstructed telemetry position (telemetry/stream_receiver.h) as
// clients see it: acomms.telemetry.Position, alone (Track) or wrapped as a
// received message of that type (Subscribe).
//
// Thread-safe: pure conversions.

#include "acomms/telemetry/position.pb.h"
#include "acomms/v1/acomms.pb.h"
#include "telemetry/node_settings.h"
#include "telemetry/stream_receiver.h"

namespace acomms::service {

inline constexpr const char* kPositionType = "acomms.telemetry.Position";

// lat/lon through the settings' datum when there is one.
telemetry::Position to_position(const telemetry::ReceivedPosition& position, const telemetry::NodeSettings& settings);

// Type kPositionType, from position.src to `own_id`, received at `now`
// (reconstructed, that is; the sample's own time is in the payload), with
// the position's number in the received sequence (ReceivedPosition::seq;
// Subscribe's `after` replays positions by it).
v1::ReceivedMessage to_received_message(const telemetry::Position& position, int32_t own_id, double now,
                                        int64_t seq);

}  // namespace acomms::service
