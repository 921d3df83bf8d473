#include "eval/realistic_track.h"

namespace acomms::eval {

std::vector<telemetry::Fix> generate_realistic_track(TrackKind kind, uint64_t seed, double duration_s) {
  return kind == TrackKind::kAuv ? torpedo_auv_mission(seed, duration_s) : glider_mission(seed, duration_s);
}

}  // namespace acomms::eval
