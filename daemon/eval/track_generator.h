#pragma once
// Generated vehicle tracks for the position-telemetry evaluation and tests.
//
// Real AUV navigation logs are not ours to ship, so the evaluation runs on
// tracks generated here with the features that decide what telemetry costs:
// the vehicle's own motion (legs, turns, a yo-yo or sawtooth in depth), the
// navigation solution's behaviour (a smooth dead-reckoning drift, small
// jitter, heading wander) and the events that force full transmissions
// (surfacing: no fixes for minutes, then a GPS fix that moves the position
// by the accumulated drift, tens to a hundred metres). Deterministic: the
// same kind and seed give the same track on every machine (util/splitmix64.h,
// and only basic arithmetic plus sin/cos of the vehicle's own heading, which
// shapes the track but is never compared across ends).
//
//   auv     torpedo AUV (Bluefin-21-like): 1.5 m/s lawnmower, 1500 m legs
//           150 m apart, yo-yo between 5 and 45 m at 15 degrees of pitch,
//           surfacing for GPS every hour; fixes every 5 s
//   glider  buoyancy glider: 0.3 m/s through the water, sawtooth 1-150 m at
//           0.15 m/s, a tidal current (0.15 m/s, 12.42 h) it estimates only
//           at the surface, surfacing every second dive; fixes every 10 s
//
// Thread-safe: pure functions of the kind and the seed.

#include <cstdint>
#include <string>
#include <vector>

#include "telemetry/sampler.h"

namespace acomms::eval {

enum class TrackKind { kAuv, kGlider };

// Throws std::invalid_argument for an unknown name ("auv", "glider").
TrackKind track_kind_of(const std::string& name);

std::vector<telemetry::Fix> generate_track(TrackKind kind, uint64_t seed, double duration_s);

// "t,x,y,z" then one fix per line (t in s, x/y/z in m to the centimetre).
std::string format_track_csv(const std::vector<telemetry::Fix>& fixes);

}  // namespace acomms::eval
