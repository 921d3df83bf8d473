#include "telemetry/telemetry_decoder.h"

#include "telemetry/telemetry_encoder.h"

namespace acomms::telemetry {

TelemetryDecoder::TelemetryDecoder(const TelemetryConfig& config)
    : config_((validate(config), config)),
      fingerprint_(fingerprint(config)),
      region_(region_grid(config)),
      predictor_(config) {}

DecodedMessage TelemetryDecoder::decode(std::string_view bytes) {
  dccl::BitReader in(bytes);
  return decode(in);
}

DecodedMessage TelemetryDecoder::decode(dccl::BitReader& in) {
  const Header header = read_header(in);
  DecodedMessage message;
  message.kind = header.kind;
  message.sequence = header.sequence;
  if (header.kind == MessageKind::kDelta) return decode_delta(in, message);

  const FullBody body = read_full_body(in, region_);
  message.time_s = body.time_of_day_s;
  message.grid = body.position;
  // A resent full arrives right after itself (resends keep the order), so
  // it is a duplicate only if nothing came since and it says the same. Any
  // other full resets, even with the last sequence number: a sender that
  // restarted without its state starts its count again.
  if (history_.in_step && header.sequence == history_.sequence && history_.since_full.size() == 1 &&
      history_.since_full[0] == body.position && history_.time_s == body.time_of_day_s) {
    message.outcome = DecodeOutcome::kDuplicate;
    message.in_step = true;
    return message;
  }
  history_.in_step = apply_full(body);
  history_.sequence = header.sequence;
  history_.time_s = body.time_of_day_s;
  history_.since_full.assign(1, body.position);
  history_.at_full = history_.in_step ? predictor_.save() : std::string();
  if (!history_.in_step) history_.since_full.clear();
  message.in_step = history_.in_step;
  message.outcome = DecodeOutcome::kPosition;
  for (int axis = 0; axis < kAxes; ++axis)
    message.position_m[axis] = static_cast<double>(message.grid[axis]) * config_.precision_m;
  return message;
}

bool TelemetryDecoder::apply_full(const FullBody& body) {
  if (body.fresh) {
    predictor_.start_fresh(body.position);
    return true;
  }
  const uint32_t mask = (1u << kStatisticsCheckBits) - 1;
  if (!history_.in_step || (predictor_.check() & mask) != body.check) return false;
  if (!body.continues) {
    predictor_.re_anchor(body.position);
    return true;
  }
  const Prior prior = predictor_.prior();
  Innovation innovation;
  for (int axis = 0; axis < kAxes; ++axis) {
    const int64_t d = body.position[axis] - prior.position[axis];
    // The sender found it in bounds against the same prediction: not this
    // sender's state after all.
    if (d < config_.innovation_min || d >= config_.innovation_max) return false;
    innovation[axis] = static_cast<int32_t>(d);
  }
  predictor_.accept(body.position, innovation);
  return true;
}

DecodedMessage TelemetryDecoder::decode_delta(dccl::BitReader& in, DecodedMessage message) {
  const bool next = history_.in_step && message.sequence == (history_.sequence + 1) % kSequenceModulus;
  const bool duplicate = history_.in_step && message.sequence == history_.sequence && history_.since_full.size() >= 2;
  if (duplicate) {
    // Consume exactly the resent codeword, so that what follows it in the
    // frame stays readable: it was coded with the state before the last
    // delta, which a replay without that delta rebuilds.
    StreamHistory before = history_;
    before.since_full.pop_back();
    StreamPredictor scratch(config_);
    replay(config_, before, &scratch);
    const Prior prior = scratch.prior();
    dccl::arith::Decoder coder(in);
    for (int axis = 0; axis < kAxes; ++axis) coder.decode(*prior.tables[axis]);
    message.outcome = DecodeOutcome::kDuplicate;
    return message;
  }
  if (!next) {
    // The tables this delta was coded with are unknown, so is its length:
    // nothing after it in the same frame can be read either.
    history_.in_step = false;
    message.outcome = DecodeOutcome::kOutOfStep;
    return message;
  }
  const Prior prior = predictor_.prior();
  dccl::arith::Decoder coder(in);
  Innovation innovation;
  for (int axis = 0; axis < kAxes; ++axis) {
    innovation[axis] = predictor_.model().innovation_of(coder.decode(*prior.tables[axis]));
    message.grid[axis] = prior.position[axis] + innovation[axis];
  }
  predictor_.accept(message.grid, innovation);
  history_.sequence = message.sequence;
  history_.time_s += config_.tau_s;
  history_.since_full.push_back(message.grid);
  message.time_s = history_.time_s;
  message.outcome = DecodeOutcome::kPosition;
  message.in_step = true;
  for (int axis = 0; axis < kAxes; ++axis)
    message.position_m[axis] = static_cast<double>(message.grid[axis]) * config_.precision_m;
  return message;
}

bool TelemetryDecoder::restore(std::string_view state) {
  std::optional<StreamHistory> history = parse_history(state, fingerprint_);
  if (history && replay(config_, *history, &predictor_)) {
    history_ = std::move(*history);
    return true;
  }
  history_ = StreamHistory{};
  return false;
}

}  // namespace acomms::telemetry
