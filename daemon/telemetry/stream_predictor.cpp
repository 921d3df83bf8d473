#include "telemetry/stream_predictor.h"

namespace acomms::telemetry {

StreamPredictor::StreamPredictor(const TelemetryConfig& config)
    : observer_(make_observer(config)), model_(make_model(config)) {}

void StreamPredictor::reset(const GridPosition& full_position) {
  observer_->reset(full_position);
  model_->reset();
}

Prior StreamPredictor::prior() {
  const Prediction prediction = observer_->predict();
  Prior prior;
  prior.position = prediction.position;
  for (int axis = 0; axis < kAxes; ++axis) prior.tables[axis] = &model_->table(axis, prediction.variance[axis]);
  return prior;
}

void StreamPredictor::accept(const GridPosition& sample, const Innovation& innovation) {
  observer_->update(sample);
  for (int axis = 0; axis < kAxes; ++axis) model_->observe(axis, innovation[axis]);
}

}  // namespace acomms::telemetry
