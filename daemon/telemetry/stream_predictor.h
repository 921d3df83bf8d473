#pragma once
// One end's observer and probability model, fed in the same order on both
// ends: reset at a full transmission, then prior() and accept() once per
// delta. The sender's and the receiver's StreamPredictor hold the same state
// after the same messages; that is the whole protocol.

#include <array>
#include <memory>

#include "telemetry/observer.h"
#include "telemetry/probability_model.h"

namespace acomms::telemetry {

using Innovation = std::array<int32_t, kAxes>;

struct Prior {
  GridPosition position{};
  // Per axis; valid until accept() or the next prior().
  std::array<const dccl::arith::FrequencyTable*, kAxes> tables{};
};

class StreamPredictor {
 public:
  explicit StreamPredictor(const TelemetryConfig& config);

  void reset(const GridPosition& full_position);
  // The prediction of the next sample and the tables to code its innovation.
  Prior prior();
  // The next sample and its innovation (sample - prior().position).
  void accept(const GridPosition& sample, const Innovation& innovation);

  const ProbabilityModel& model() const { return *model_; }

 private:
  std::unique_ptr<Observer> observer_;
  std::unique_ptr<ProbabilityModel> model_;
};

}  // namespace acomms::telemetry
