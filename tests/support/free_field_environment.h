#pragma once
// Free field, stated once: 25 kHz in 100 m of 1500 m/s water whose surface
// and bottom are the same water (no reflection), incoherent, 400 beams over
// ±80°: TL is spherical spreading, 20 log10(r). The link prediction's test
// (tests/unit/node/link_prediction_test.cpp), the test of the daemon's
// unheard packets (tests/unit/node/unheard_links_test.cpp) and the link
// prediction's bench (tests/bench/link_prediction_bench.cpp) run on it: the
// bench must time the case the tests check, or its figure says nothing of
// them.
//
// Thread-safe: a constant.

namespace acomms::test {

// A gram::Environment in protobuf text format.
inline constexpr const char* kFreeFieldEnvironment = R"(
  frequency_hz: 25000
  sound_speed { depth_m: 0 speed_mps: 1500 }
  sound_speed { depth_m: 100 speed_mps: 1500 }
  surface { kind: HALF_SPACE half_space { speed_mps: 1500 density_ratio: 1 } }
  bottom { kind: HALF_SPACE half_space { speed_mps: 1500 density_ratio: 1 } }
  field_mode: INCOHERENT
  beam_count: 400
  launch_angle_min_deg: -80
  launch_angle_max_deg: 80
)";

}  // namespace acomms::test
