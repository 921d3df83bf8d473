// Arrivals (eigenrays) at receivers and their RMS delay spread.
//
// Problem: an acoustic modem cares about the multipath: when each path
// arrives, how strong, from which angle, after how many bounces, and how
// long the channel's impulse response is (Schneider (2013) eq. 4.5).
// Decision (spec §5): every ray segment that gives a receiver a non-zero
// hat weight yields a candidate; candidates from consecutive rays of the
// fan with the same bounce and caustic counts and delays within 1/(10 f) are
// one eigenray, merged (amplitudes summed, delay and angles weight-averaged).
// Arrivals are sorted by delay. Thread-safe: each call is independent.
#pragma once

#include <cstddef>
#include <vector>

#include "acomms/gram/environment.pb.h"
#include "gram/cancel_token.h"

namespace acomms::gram {

struct Arrival {
  double delay_s = 0;
  double amplitude = 0;    // in the normalisation of p (a direct path ≈ 1/R)
  double phase_deg = 0;    // arg(ΠR) − 90° per caustic, our exp(−iωt) convention
  double launch_deg = 0;   // positive down
  double arrival_deg = 0;  // direction of travel at the receiver, positive down
  int top_bounces = 0, bottom_bounces = 0, caustics = 0;
};

struct ReceiverArrivals {
  double range_m = 0, depth_m = 0;
  std::vector<Arrival> arrivals;  // by delay
};

struct ArrivalOptions {
  std::size_t max_arrivals = 200;  // per receiver, the strongest kept
  const CancelToken* cancel = nullptr;  // polled once per beam (ModelCancelled)
};

// For the environment's receivers (grid: depth-major, like TL). Throws
// std::invalid_argument with the validation message.
std::vector<ReceiverArrivals> compute_arrivals(const Environment& env,
                                               const ArrivalOptions& options = {});

struct DelaySpread {
  double tau_rms_s = 0;
  double first_delay_s = 0;
  std::size_t arrivals_used = 0;
};

// Schneider (2013) eq. 4.5 over the arrivals down to `floor_db` below the strongest.
DelaySpread rms_delay_spread(const std::vector<Arrival>& arrivals, double floor_db = 60.0);

}  // namespace acomms::gram
