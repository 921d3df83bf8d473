// The queues' side of a gateway (queue/routing.h): custody queues, which
// hold envelopes for other nodes and have no DCCL type, and the routed form
// of what the contest chooses. Kept apart from the rest of the manager so
// that a node without routing runs none of it. Core thread only, but for
// journal_custody (any thread).
#include <spdlog/spdlog.h>

#include "core/core_thread.h"
#include "queue/queue_manager.h"

namespace acomms::queue {

QueueManager::TypeState* QueueManager::custody_state(const std::string& type) {
  auto it = by_name_.find(type);
  if (it != by_name_.end()) return it->second;
  if (routing_ == nullptr) return nullptr;
  std::optional<QueuePolicy> policy = routing_->custody_policy(type);
  if (!policy) return nullptr;
  const int key = next_custody_key_++;
  TypeState& state = by_id_.try_emplace(key).first->second;
  state.queue = std::make_unique<Queue>(type, key, *policy, clock_.now_seconds());
  state.custody = true;
  // No roles and no duplicate filter: nothing here is decoded, and a
  // custody queue never receives (its messages come from journal_custody).
  by_name_[type] = &state;
  spdlog::info("route: custody queue {} made (value_base {}, max {} messages)", type, policy->value_base,
               policy->max_queue);
  return &state;
}

void QueueManager::journal_custody(JournalMessage record, MessageJournal::Appended appended) {
  journal_.append(std::move(record), std::move(appended));
}

bool QueueManager::accept_custody(QueuedMessage message) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (custody_state(message.record.type) == nullptr) {
    spdlog::error("route: custody message {} names no custody queue ({})", message.record.id, message.record.type);
    return false;
  }
  return accept(std::move(message));
}

std::vector<std::shared_ptr<std::atomic<bool>>> QueueManager::take_ack_conditions() {
  ACOMMS_ASSERT_CORE_THREAD();
  return std::exchange(ack_conditions_, {});
}

void QueueManager::heard_ack(int link, int32_t src) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (routing_ != nullptr) routing_->acked_by(link, src, clock_.now_seconds());
}

void QueueManager::set_acks_in_hardware(int link, bool in_hardware) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (routing_ != nullptr) routing_->set_acks_in_hardware(link, in_hardware);
}

std::vector<ReceivedMessage> QueueManager::receive_routed(std::string_view payload, int32_t origin, uint16_t seq,
                                                          double forget_after,
                                                          std::optional<std::string_view> link_figures, int link) {
  ACOMMS_ASSERT_CORE_THREAD();
  receiving_routed_ = RoutedIdentity{origin, seq, forget_after};
  struct Clear {
    std::optional<RoutedIdentity>& routed;
    ~Clear() { routed.reset(); }
  } clear{receiving_routed_};
  return receive(payload, origin, link_figures, link, own_id_);
}

bool QueueManager::report_routed(const std::string& type, QueueEventKind kind, const JournalMessage& message,
                                 const std::string& detail) {
  ACOMMS_ASSERT_CORE_THREAD();
  auto it = by_name_.find(type);
  if (it == by_name_.end()) return false;
  emit(*it->second, clock_.now_seconds(), {.kind = kind, .message = message, .detail = detail, .remote = true});
  return true;
}

bool QueueManager::custody_passed(const std::string& type, int64_t id, const std::string& detail) {
  ACOMMS_ASSERT_CORE_THREAD();
  auto it = by_name_.find(type);
  if (it == by_name_.end()) return false;
  TypeState& state = *it->second;
  std::optional<QueuedMessage> m = state.queue->take(id);
  if (!m) return false;
  const std::string more = routing_ != nullptr ? routing_->acked_detail(*state.queue, *m) : "";
  const std::string text = more.empty() ? detail : detail + "; " + more;
  emit(state, clock_.now_seconds(), {.kind = QueueEventKind::kAcked, .message = m->record, .detail = text,
                                     .removes_message = true});
  return true;
}

RoutedForm QueueManager::routed_form(const Queue& queue, const QueuedMessage& next, const DataRequest& request,
                                     double now) {
  if (routing_ == nullptr) return {};
  return routing_->outgoing(queue, next, request, now);
}

}  // namespace acomms::queue
