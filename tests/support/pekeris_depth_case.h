#pragma once
// The depth objective's end-to-end case, stated once: the Pekeris 500 Hz
// environment of shared/conformance (100 m of water) with 600 beams and 21
// receiver ranges over 1.9-2.4 km, and a vehicle 2 km out at 1.5 m/s asking
// for the best depth between 5 and 90 m. tests/unit/gram/depth_objective_test
// checks this run's answer and tests/bench/depth_objective_bench times it:
// both must run the same case, or the bench's figure says nothing of the
// tested run.
//
// Thread-safe: pure functions.

#include <string>

#include "gram/bellhop_import.h"
#include "gram/depth_objective.h"

namespace acomms::gram::test {

inline Environment pekeris_depth_case_environment(const std::string& shared_dir) {
  Environment env = import_bellhop_env_file(shared_dir + "/conformance/gram/envs/pekeris_500hz.env").environment;
  env.clear_receiver_range_m();
  for (int i = 0; i <= 20; ++i) env.add_receiver_range_m(1900 + 25.0 * i);  // 1.9-2.4 km
  env.set_beam_count(600);
  env.set_box_range_m(2500);
  return env;
}

inline DepthObjectiveRequest pekeris_depth_case_request() {
  DepthObjectiveRequest req;
  req.range_m = 2000;
  req.speed_mps = 1.5;
  req.heading_deg = 0;
  req.horizon_s = 120;
  req.h_max_db = 70;
  req.limits = {5, 90, 10};
  req.lowpass = LowpassOptions{};
  return req;
}

}  // namespace acomms::gram::test
