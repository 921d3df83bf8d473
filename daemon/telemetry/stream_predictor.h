#pragma once
// One end's observer and probability model, fed in the same order on both
// ends: start_fresh or re_anchor at a full transmission, then prior() and
// accept() once per delta (and for a full that a delta could have carried).
// The sender's and the receiver's StreamPredictor hold the same state after
// the same messages; that is the whole protocol.
//
// What was learned outlives fulls: a full re-anchors the observer (or, when
// it is just the next sample sent in full, is accepted like a delta) and
// leaves the model's statistics alone. Only a fresh start, which a full
// announces when either end lost its state, forgets them. check() lets a
// receiver tell whether it holds the sender's statistics before it decodes
// anything against them.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

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

  // Everything starts over from a full's position: observer and statistics.
  void start_fresh(const GridPosition& full_position);
  // The observer starts over from a full's position; the statistics stay.
  void re_anchor(const GridPosition& full_position);
  // The prediction of the next sample and the tables to code its innovation.
  Prior prior();
  // The next sample and its innovation (sample - prior().position).
  void accept(const GridPosition& sample, const Innovation& innovation);

  // The whole state as bytes, and back (stream_history.h). load is false,
  // and the predictor unchanged, for bytes it did not save.
  std::string save() const;
  bool load(std::string_view bytes);
  // A 32-bit digest of what the statistics depend on (the samples accepted
  // since the fresh start and the model's statistics), integers only, so
  // it is the same on any build.
  uint32_t check() const;

  const ProbabilityModel& model() const { return *model_; }

 private:
  std::unique_ptr<Observer> observer_;
  std::unique_ptr<ProbabilityModel> model_;
  int64_t accepted_ = 0;  // samples accepted since the fresh start
};

}  // namespace acomms::telemetry
