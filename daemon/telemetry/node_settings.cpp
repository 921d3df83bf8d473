#include "telemetry/node_settings.h"

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "telemetry/telemetry_message.h"
#include "telemetry/wire_message.h"

namespace acomms::telemetry {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("telemetry." + what);
}

}  // namespace

NodeSettings node_settings(const v1::TelemetryConfig& c, int32_t own_id) {
  NodeSettings s;
  TelemetryConfig& t = s.stream;
  if (c.has_tau_s()) t.tau_s = c.tau_s();
  if (c.has_precision_m()) t.precision_m = c.precision_m();
  if (c.has_innovation_min()) t.innovation_min = c.innovation_min();
  if (c.has_innovation_max()) t.innovation_max = c.innovation_max();
  if (!c.observer().empty()) {
    auto kind = observer_kind_of(c.observer());
    require(kind.has_value(), "observer \"" + c.observer() + "\" is not one of fixed_speed, kalman");
    t.observer = *kind;
  }
  if (!c.model().empty()) {
    auto kind = model_kind_of(c.model());
    require(kind.has_value(), "model \"" + c.model() + "\" is not one of uniform, gaussian, adaptive, learned");
    t.model = *kind;
  }
  if (c.has_speed_mps()) t.speed_mps = c.speed_mps();
  if (c.has_sigma_j2()) t.sigma_j2 = c.sigma_j2();
  if (c.has_r_m2()) t.r_m2 = c.r_m2();
  if (c.has_full_every()) t.full_every = c.full_every();
  require(c.region_min_m_size() == 0 || c.region_min_m_size() == kAxes, "region_min_m needs 3 values (x, y, z)");
  require(c.region_max_m_size() == 0 || c.region_max_m_size() == kAxes, "region_max_m needs 3 values (x, y, z)");
  for (int axis = 0; axis < c.region_min_m_size(); ++axis) t.region_min_m[axis] = c.region_min_m(axis);
  for (int axis = 0; axis < c.region_max_m_size(); ++axis) t.region_max_m[axis] = c.region_max_m(axis);
  try {
    validate(t);
  } catch (const std::invalid_argument& e) {
    // "telemetry config: tau_s must be ..." -> the config's own path.
    std::string what = e.what();
    const std::string prefix = "telemetry config: ";
    if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
    throw std::invalid_argument("telemetry." + what);
  }
  require(full_body_bits(region_grid(t)) <= kMaxFullBodyBits,
          "region_min_m/region_max_m/precision_m: a full transmission would take " +
              std::to_string(full_body_bits(region_grid(t))) + " bits, more than the " +
              std::to_string(kMaxFullBodyBits) + " its DCCL type holds");

  std::set<int32_t> seen;
  for (int32_t receiver : c.receiver()) {
    require(receiver >= 1 && receiver <= 127,
            "receiver " + std::to_string(receiver) + " must be a modem id within [1, 127]");
    require(receiver != own_id, "receiver " + std::to_string(receiver) + " is this node's own modem id");
    require(seen.insert(receiver).second, "receiver " + std::to_string(receiver) + " is listed twice");
    s.receivers.push_back(receiver);
  }
  require(s.receivers.empty() || (own_id >= 1 && own_id <= 127),
          "receiver: this node's modem id " + std::to_string(own_id) + " must be within [1, 127] to send telemetry");
  if (c.has_ttl_s()) s.ttl_s = c.ttl_s();
  const double longest = double{kWireSequenceModulus} / 2 * t.tau_s;
  require(std::isfinite(s.ttl_s) && s.ttl_s > 0 && s.ttl_s <= longest,
          "ttl_s " + std::to_string(s.ttl_s) + " must be within (0, " + std::to_string(longest) +
              "] s (2048 tau_s: the sequence number must not wrap while a message may still be resent)");
  s.gap_timeout_s = c.has_gap_timeout_s() ? c.gap_timeout_s() : s.ttl_s;
  require(std::isfinite(s.gap_timeout_s) && s.gap_timeout_s >= 0, "gap_timeout_s must be >= 0");
  if (c.has_datum()) s.datum = std::make_shared<const Datum>(c.datum().lat(), c.datum().lon(), c.datum().height_m());
  return s;
}

void configure_queues(v1::QueueConfig* queues, const NodeSettings& settings) {
  for (std::string_view type : {kFullType, kDeltaType, kFeedbackType}) {
    v1::QueueTypeConfig* entry = nullptr;
    for (v1::QueueTypeConfig& existing : *queues->mutable_type()) {
      if (existing.type() == type) entry = &existing;
    }
    if (entry == nullptr) {
      entry = queues->add_type();
      entry->set_type(std::string(type));
    }
    v1::QueuePolicy* policy = entry->mutable_policy();
    policy->set_ack(true);
    policy->set_newest_first(false);
    policy->set_ttl_s(settings.ttl_s);
    if (!policy->has_max_queue()) policy->set_max_queue(4096);
    if (!policy->has_on_full()) policy->set_on_full(v1::QueuePolicy::REFUSE_NEW);
    entry->mutable_roles()->set_source_field("src");
    entry->mutable_roles()->set_destination_field("dest");
    entry->set_duplicate_filter(false);
  }
}

}  // namespace acomms::telemetry
