#pragma once
// Turns navigation fixes at any rate into the evenly spaced samples the
// observers assume (y[n] at t_f + n tau, Schneider 2013 section 3.2).
//
// Sample times are the multiples of tau (whole seconds) on the fixes' clock,
// so both ends agree on them and a full transmission codes its time to the
// second. Each sample is interpolated linearly between the two fixes around
// it. A gap of more than tau between two fixes (the vehicle surfaced, the
// navigation dropped out) ends the segment: the next sample starts a new one
// (Sample::new_segment), which the encoder sends as a full transmission.
// Fixes that do not move time forward are ignored; fixes with a non-finite
// field are refused (std::invalid_argument).
//
// Not thread-safe: a Sampler is one stream's state, owned by one thread (the
// core thread in acommsd); sample_track() is a pure function.

#include <optional>
#include <vector>

#include "telemetry/telemetry_encoder.h"

namespace acomms::telemetry {

struct Fix {
  double time_s = 0;
  std::array<double, kAxes> position_m{};
};

class Sampler {
 public:
  explicit Sampler(uint32_t tau_s);

  // The samples that fall in (previous fix, fix] (the first fix of a segment
  // yields a sample only when it lies exactly on the tau grid).
  std::vector<Sample> add(const Fix& fix);

 private:
  int64_t tau_;
  std::optional<Fix> last_;
  int64_t next_time_s_ = 0;  // the next sample time
  bool segment_started_ = false;  // a sample of the current segment was made
};

// All samples of a track.
std::vector<Sample> sample_track(const std::vector<Fix>& fixes, uint32_t tau_s);

}  // namespace acomms::telemetry
