#include "telemetry/sampler.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace acomms::telemetry {

Sampler::Sampler(uint32_t tau_s) : tau_(tau_s) {
  if (tau_s == 0) throw std::invalid_argument("sampler: tau must be at least 1 s");
}

std::vector<Sample> Sampler::add(const Fix& fix) {
  if (!std::isfinite(fix.time_s) || !std::isfinite(fix.position_m[0]) || !std::isfinite(fix.position_m[1]) ||
      !std::isfinite(fix.position_m[2]))
    throw std::invalid_argument("navigation fix at t=" + std::to_string(fix.time_s) + " has a non-finite field");
  if (std::abs(fix.time_s) > 1e15) throw std::invalid_argument("navigation fix time out of range");
  std::vector<Sample> samples;
  if (last_ && fix.time_s <= last_->time_s) return samples;
  if (!last_ || fix.time_s - last_->time_s > static_cast<double>(tau_)) {
    // A new segment: the first sample time at or after this fix.
    next_time_s_ = static_cast<int64_t>(std::ceil(fix.time_s / static_cast<double>(tau_))) * tau_;
    segment_started_ = false;
    if (static_cast<double>(next_time_s_) == fix.time_s) {
      samples.push_back(Sample{next_time_s_, fix.position_m, true});
      segment_started_ = true;
      next_time_s_ += tau_;
    }
    last_ = fix;
    return samples;
  }
  const Fix& a = *last_;
  while (static_cast<double>(next_time_s_) <= fix.time_s) {
    const double w = (static_cast<double>(next_time_s_) - a.time_s) / (fix.time_s - a.time_s);
    Sample sample;
    sample.time_s = next_time_s_;
    for (int axis = 0; axis < kAxes; ++axis)
      sample.position_m[axis] = a.position_m[axis] + w * (fix.position_m[axis] - a.position_m[axis]);
    sample.new_segment = !segment_started_;
    segment_started_ = true;
    samples.push_back(sample);
    next_time_s_ += tau_;
  }
  last_ = fix;
  return samples;
}

std::vector<Sample> sample_track(const std::vector<Fix>& fixes, uint32_t tau_s) {
  Sampler sampler(tau_s);
  std::vector<Sample> samples;
  for (const Fix& fix : fixes) {
    std::vector<Sample> more = sampler.add(fix);
    samples.insert(samples.end(), more.begin(), more.end());
  }
  return samples;
}

}  // namespace acomms::telemetry
