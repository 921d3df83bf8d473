#include "telemetry/stream_predictor.h"

#include "telemetry/state_bytes.h"

namespace acomms::telemetry {

StreamPredictor::StreamPredictor(const TelemetryConfig& config)
    : observer_(make_observer(config)), model_(make_model(config)) {}

void StreamPredictor::start_fresh(const GridPosition& full_position) {
  model_->reset();
  accepted_ = 0;
  re_anchor(full_position);
}

void StreamPredictor::re_anchor(const GridPosition& full_position) {
  observer_->reset(full_position);
  model_->trim();
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
  ++accepted_;
  // The tables of this sample are used: the cache may let go of them (it
  // must not grow with a track whose fulls no longer reset the model).
  model_->trim();
}

// accepted (8), the observer's bytes (4 + n), the statistics' count (4)
// and values (8 each).
std::string StreamPredictor::save() const {
  StateWriter out;
  out.put(static_cast<uint64_t>(accepted_), 8);
  out.put_bytes(observer_->save());
  const std::vector<int64_t> statistics = model_->statistics();
  out.put(statistics.size(), 4);
  for (int64_t v : statistics) out.put(static_cast<uint64_t>(v), 8);
  return out.take();
}

bool StreamPredictor::load(std::string_view bytes) {
  StateReader in(bytes);
  uint64_t accepted = 0, count = 0;
  std::string observer;
  if (!in.get(8, &accepted) || accepted > uint64_t{INT64_MAX} || !in.get_bytes(&observer) || !in.get(4, &count) ||
      count > 100000)
    return false;
  std::vector<int64_t> statistics(count);
  for (int64_t& v : statistics) {
    uint64_t raw = 0;
    if (!in.get(8, &raw)) return false;
    v = static_cast<int64_t>(raw);
  }
  if (!in.done()) return false;
  // Both or neither: the statistics are checked before the observer changes.
  const std::vector<int64_t> before = model_->statistics();
  if (!model_->restore_statistics(statistics)) return false;
  if (!observer_->load(observer)) {
    model_->restore_statistics(before);
    return false;
  }
  model_->trim();
  accepted_ = static_cast<int64_t>(accepted);
  return true;
}

uint32_t StreamPredictor::check() const {
  // FNV-1a over little-endian 64-bit words: accepted, then the statistics.
  uint32_t hash = 2166136261u;
  auto add = [&hash](int64_t value) {
    for (int i = 0; i < 8; ++i) {
      hash ^= static_cast<uint8_t>(static_cast<uint64_t>(value) >> (8 * i));
      hash *= 16777619u;
    }
  };
  add(accepted_);
  for (int64_t v : model_->statistics()) add(v);
  return hash;
}

}  // namespace acomms::telemetry
