// The depth objective end to end, as a vehicle's request runs it in
// process: the built-in model's TL on the Pekeris 500 Hz environment (600
// beams, 21 ranges over 1.9-2.4 km, 100 m water), then the range window,
// H̄, the objective, the low-pass and the best depth
// (gram/depth_objective.h). Budget about 2 s in a Release build (the
// model run is nearly all of it); tests/unit/gram/depth_objective_test.cpp
// checks the same run's answer. The time is the median of the repetitions;
// it depends on the machine's load: reported, not enforced.
//
//   build/tests/bench/depth_objective_bench [--repeat=N]
//   build/tests/bench/depth_objective_bench --smoke     (what ctest runs: one run)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "gram/depth_objective.h"
#include "gram/transmission_loss.h"
#include "pekeris_depth_case.h"

using namespace acomms::gram;

int main(int argc, char** argv) {
  int repeat = 5;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--smoke") == 0) repeat = 1;
    else if (std::strncmp(argv[i], "--repeat=", 9) == 0) repeat = std::max(1, std::atoi(argv[i] + 9));
    else {
      std::fprintf(stderr, "usage: depth_objective_bench [--repeat=N] [--smoke]\n");
      return 2;
    }
  }
  // The file is parsed once, outside the timing.
  const Environment env = test::pekeris_depth_case_environment(ACOMMS_SHARED_DIR);
  const DepthObjectiveRequest req = test::pekeris_depth_case_request();
  std::vector<double> seconds;
  bool answered = true;
  for (int i = 0; i < repeat; ++i) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<TransmissionLoss> tl{compute_transmission_loss(env)};
    const DepthObjectiveResult r = compute_depth_objective(tl, env, req);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    answered = answered && r.best.any_signal;
  }
  std::sort(seconds.begin(), seconds.end());
  std::printf("depth objective, pekeris_500hz, 600 beams x 21 ranges  %d run(s)  median %7.3f s  max %7.3f s  "
              "budget about 2 s%s\n",
              repeat, seconds[seconds.size() / 2], seconds.back(), answered ? "" : "  NO BEST DEPTH");
  return answered ? 0 : 1;
}
