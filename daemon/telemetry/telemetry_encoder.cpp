#include "telemetry/telemetry_encoder.h"

#include <cmath>
#include <stdexcept>

#include "telemetry/deterministic_math.h"

namespace acomms::telemetry {

TelemetryEncoder::TelemetryEncoder(const TelemetryConfig& config)
    : config_((validate(config), config)),
      fingerprint_(fingerprint(config)),
      region_(region_grid(config)),
      predictor_(config) {}

GridPosition TelemetryEncoder::quantise(const Sample& sample) const {
  GridPosition position;
  for (int axis = 0; axis < kAxes; ++axis) {
    const double v = sample.position_m[axis];
    if (!std::isfinite(v)) throw std::out_of_range("telemetry sample: axis " + std::to_string(axis) + " is not finite");
    position[axis] = round_to_int(v / config_.precision_m);
  }
  if (!region_.contains(position)) {
    throw std::out_of_range("telemetry sample at (" + std::to_string(sample.position_m[0]) + ", " +
                            std::to_string(sample.position_m[1]) + ", " + std::to_string(sample.position_m[2]) +
                            ") m lies outside the telemetry region");
  }
  return position;
}

EncodedMessage TelemetryEncoder::encode(const Sample& sample) {
  std::string bytes;
  dccl::BitWriter out(&bytes);
  EncodedMessage message = encode(sample, out);
  message.bytes = std::move(bytes);
  return message;
}

EncodedMessage TelemetryEncoder::encode(const Sample& sample, dccl::BitWriter& out) {
  EncodedMessage message;
  message.position = quantise(sample);
  message.sequence = (history_.sequence + 1) % kSequenceModulus;
  const uint64_t start = out.position();
  const bool fresh = !history_.in_step || fresh_requested_;
  // The next sample of the stream: both ends can predict it.
  const bool next = !fresh && !sample.new_segment && sample.time_s == history_.time_s + config_.tau_s;
  bool in_bounds = next;
  Prior prior;
  Innovation innovation{};
  if (next) {
    prior = predictor_.prior();
    for (int axis = 0; axis < kAxes; ++axis) {
      const int64_t d = message.position[axis] - prior.position[axis];
      if (d < config_.innovation_min || d >= config_.innovation_max) in_bounds = false;
      innovation[axis] = static_cast<int32_t>(d);
    }
  }
  const bool delta = in_bounds && !full_requested_ && history_.since_full.size() <= config_.full_every;
  message.kind = delta ? MessageKind::kDelta : MessageKind::kFull;
  write_header(out, Header{message.kind, message.sequence});
  if (delta) {
    message.innovation = innovation;
    dccl::arith::Encoder coder(out);
    for (int axis = 0; axis < kAxes; ++axis)
      coder.encode(*prior.tables[axis], predictor_.model().symbol_of(message.innovation[axis]));
    coder.finish();
    predictor_.accept(message.position, message.innovation);
    history_.since_full.push_back(message.position);
  } else {
    const int64_t time_of_day = ((sample.time_s % kSecondsPerDay) + kSecondsPerDay) % kSecondsPerDay;
    FullBody body{time_of_day, message.position};
    body.fresh = message.fresh = fresh;
    body.continues = in_bounds;
    body.check = fresh ? 0 : predictor_.check();
    write_full_body(out, region_, body);
    if (fresh) {
      predictor_.start_fresh(message.position);
    } else if (in_bounds) {
      predictor_.accept(message.position, innovation);
    } else {
      predictor_.re_anchor(message.position);
    }
    history_.since_full.assign(1, message.position);
    history_.at_full = predictor_.save();
    history_.in_step = true;
    full_requested_ = fresh_requested_ = false;
  }
  message.bits = out.position() - start;
  message.body_bits = message.bits - kHeaderBits;
  history_.sequence = message.sequence;
  history_.time_s = sample.time_s;
  return message;
}

bool TelemetryEncoder::restore(std::string_view state) {
  std::optional<StreamHistory> history = parse_history(state, fingerprint_);
  if (history && replay(config_, *history, &predictor_)) {
    history_ = std::move(*history);
    full_requested_ = fresh_requested_ = false;
    return true;
  }
  history_ = StreamHistory{};  // not in step: the next message is a fresh full
  full_requested_ = fresh_requested_ = true;
  return false;
}

bool replay(const TelemetryConfig& config, const StreamHistory& history, StreamPredictor* predictor) {
  if (history.since_full.empty()) return true;
  if (!predictor->load(history.at_full)) return false;
  for (size_t i = 1; i < history.since_full.size(); ++i) {
    const Prior prior = predictor->prior();
    Innovation innovation;
    for (int axis = 0; axis < kAxes; ++axis) {
      const int64_t d = history.since_full[i][axis] - prior.position[axis];
      if (d < config.innovation_min || d >= config.innovation_max) return false;
      innovation[axis] = static_cast<int32_t>(d);
    }
    predictor->accept(history.since_full[i], innovation);
  }
  return true;
}

}  // namespace acomms::telemetry
