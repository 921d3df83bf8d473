#include "mac/auto_discovery_mac.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "mac/blank_slot.h"
#include "core/core_thread.h"
#include "util/seconds.h"

namespace acomms::mac {
namespace {

const AutoDiscoveryConfig& checked(const AutoDiscoveryConfig& config, int32_t own_id) {
  if (own_id < 1)
    throw std::invalid_argument("auto_discovery needs this node's modem id >= 1, got " +
                                std::to_string(own_id));
  if (!std::isfinite(config.slot_seconds) || config.slot_seconds < 1e-3)
    throw std::invalid_argument(
        "mac.slot_seconds must be positive (at least 0.001 s) for auto_discovery, got " +
        std::to_string(config.slot_seconds));
  if (config.coolness < 1)
    throw std::invalid_argument(
        "mac.coolness must be >= 1 for auto_discovery (Schneider (2013), section 2.4.3, "
        "recommends the expected network size + 1)");
  if (config.expire_cycles < 1)
    throw std::invalid_argument("mac.expire_cycles must be >= 1 for auto_discovery");
  return config;
}

}  // namespace

AutoDiscoveryMac::AutoDiscoveryMac(const AutoDiscoveryConfig& config, int32_t own_id,
                                   core::Scheduler& scheduler)
    : scheduler_(scheduler),
      config_(checked(config, own_id)),
      own_id_(own_id),
      slot_(to_nanoseconds(config.slot_seconds)) {
  build_cycle(0);
}

AutoDiscoveryMac::~AutoDiscoveryMac() { stop(); }

void AutoDiscoveryMac::start(Transmit transmit) {
  ACOMMS_ASSERT_CORE_THREAD();
  stop();
  transmit_ = std::move(transmit);
  running_ = true;
  plan(scheduler_.clock().now());
}

void AutoDiscoveryMac::stop() {
  ACOMMS_ASSERT_CORE_THREAD();
  cancel_task();
  running_ = false;
  in_cycle_ = false;
}

void AutoDiscoveryMac::set_cycle(const Cycle&) {
  ACOMMS_ASSERT_CORE_THREAD();
  throw std::invalid_argument(
      "the auto_discovery MAC builds its cycle from the nodes it hears and cannot be given "
      "one; use the \"fixed\" MAC for a configured cycle");
}

std::vector<int32_t> AutoDiscoveryMac::known_ids() const {
  std::vector<int32_t> ids;
  ids.reserve(last_heard_.size() + 1);
  bool own_placed = false;
  for (const auto& [id, heard] : last_heard_) {
    if (!own_placed && own_id_ < id) {
      ids.push_back(own_id_);
      own_placed = true;
    }
    ids.push_back(id);
  }
  if (!own_placed) ids.push_back(own_id_);
  return ids;
}

MacStatus AutoDiscoveryMac::status() const { return MacStatus{known_ids(), blank_rule_name(config_.blank_rule)}; }

AutoDiscoveryMac::Activity AutoDiscoveryMac::activity() const {
  if (!running_) return Activity::kOff;
  if (!in_cycle_) return Activity::kWaiting;
  const int32_t src = cycle_[slot_index_].src;
  if (src == own_id_) return Activity::kSending;
  if (src == 0) return Activity::kBlank;
  return Activity::kListening;
}

void AutoDiscoveryMac::on_receive(const v1::ModemTransmission& transmission) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!running_) return;
  const int32_t id = transmission.src();
  if (id < 1 || id == own_id_) return;
  const core::Clock::time_point now = scheduler_.clock().now();
  const bool discovered = last_heard_.insert_or_assign(id, now).second;
  if (!discovered) return;
  spdlog::debug("mac: node {} discovered node {}", own_id_, id);
  // In a cycle: it is finished unchanged, and end_cycle() plans the longer
  // one. Waiting: the boundary being waited for belonged to the old length.
  if (!in_cycle_) {
    cancel_task();
    plan(now);
  }
}

Nanoseconds AutoDiscoveryMac::cycle_length() const {
  return slot_ * static_cast<int64_t>(last_heard_.size() + 2);
}

void AutoDiscoveryMac::plan(core::Clock::time_point t) {
  in_cycle_ = false;
  const CycleGrid::CycleStart next = CycleGrid(config_.epoch, cycle_length()).next(t);
  task_ = scheduler_.at(next.start, [this, next] { begin_cycle(next); });
}

void AutoDiscoveryMac::begin_cycle(CycleGrid::CycleStart start) {
  task_.reset();
  if (expire(start.start)) {
    plan(start.start);
    return;
  }
  build_cycle(start.count);
  cycle_start_ = start.start;
  cycle_count_ = start.count;
  in_cycle_ = true;
  begin_slot(0);
}

void AutoDiscoveryMac::begin_slot(size_t index) {
  ACOMMS_ASSERT_CORE_THREAD();
  task_.reset();
  slot_index_ = index;
  const core::Clock::time_point slot_start = cycle_start_ + slot_ * static_cast<int64_t>(index);
  if (index + 1 < cycle_.size()) {
    task_ = scheduler_.at(slot_start + slot_, [this, index] { begin_slot(index + 1); });
  } else {
    task_ = scheduler_.at(slot_start + slot_, [this] { end_cycle(); });
  }
  const Slot& slot = cycle_[index];
  if (slot.src != own_id_ || !transmit_) return;
  const double seconds = util::seconds_since_epoch(slot_start);
  transmit_(slot_transmission(slot, seconds));
}

void AutoDiscoveryMac::end_cycle() {
  task_.reset();
  // Same length and no midnight remainder: the next cycle starts now.
  plan(scheduler_.clock().now());
}

bool AutoDiscoveryMac::expire(core::Clock::time_point now) {
  const Nanoseconds limit = cycle_length() * static_cast<int64_t>(config_.expire_cycles);
  bool expired = false;
  for (auto it = last_heard_.begin(); it != last_heard_.end();) {
    if (now - it->second > limit) {
      spdlog::debug("mac: node {} expired node {} (silent for {} cycles)", own_id_, it->first,
                   config_.expire_cycles);
      it = last_heard_.erase(it);
      expired = true;
    } else {
      ++it;
    }
  }
  return expired;
}

void AutoDiscoveryMac::build_cycle(int64_t count) {
  const std::vector<int32_t> ids = known_ids();
  int64_t sum = 0;
  for (int32_t id : ids) sum += id;
  const size_t slots = ids.size() + 1;
  const size_t blank = blank_slot_index(config_.blank_rule, slots, count, sum, config_.coolness);
  cycle_.clear();
  cycle_.reserve(slots);
  auto next_id = ids.begin();
  for (size_t i = 0; i < slots; ++i) {
    Slot slot;
    slot.src = i == blank ? 0 : *next_id++;
    slot.dest = -1;
    slot.rate = config_.rate;
    slot.seconds = config_.slot_seconds;
    slot.type = v1::ModemTransmission::DATA;
    cycle_.push_back(slot);
  }
}

void AutoDiscoveryMac::cancel_task() {
  if (task_) scheduler_.cancel(*task_);
  task_.reset();
}

}  // namespace acomms::mac
