#include "queue/memory_journal.h"

#include <algorithm>
#include <map>

namespace acomms::queue {

void MemoryJournal::append(JournalMessage message, Appended appended) {
  int64_t id = 0;
  {
    std::lock_guard lock(mutex_);
    message.id = next_id_++;
    id = message.id;
    events_.push_back(queued_event(message));
    messages_.emplace(id, std::move(message));
  }
  appended(id, nullptr);
}

void MemoryJournal::record(const QueueEvent& event) {
  std::lock_guard lock(mutex_);
  events_.push_back(event);
  if (event.removes_message) messages_.erase(event.message_id);
}

std::vector<JournalMessage> MemoryJournal::load() {
  std::lock_guard lock(mutex_);
  std::vector<JournalMessage> out;
  for (const auto& [id, message] : messages_) out.push_back(message);
  return out;
}

std::vector<QueueEvent> MemoryJournal::received_since(double since) {
  std::lock_guard lock(mutex_);
  std::vector<QueueEvent> out;
  for (const QueueEvent& event : events_) {
    if (event.kind == QueueEventKind::kReceived && event.time >= since) out.push_back(event);
  }
  return out;
}

std::vector<RoutedIdentity> MemoryJournal::routed_since(double now) {
  std::lock_guard lock(mutex_);
  // Newest row per identity, as the store's INSERT OR REPLACE keeps it.
  std::map<std::pair<int32_t, int32_t>, RoutedIdentity> latest;
  for (const QueueEvent& event : events_) {
    if (event.routed) latest[{event.routed->origin, event.routed->seq}] = *event.routed;
  }
  std::vector<RoutedIdentity> out;
  for (const auto& [key, routed] : latest) {
    if (routed.forget_after >= now) out.push_back(routed);
  }
  return out;
}

std::vector<QueueEvent> MemoryJournal::authenticated_since(double sent_since) {
  std::lock_guard lock(mutex_);
  std::vector<QueueEvent> out;
  for (const QueueEvent& event : events_) {
    if (event.auth_sent_s && *event.auth_sent_s >= sent_since) out.push_back(event);
  }
  return out;
}

std::vector<QueueEvent> MemoryJournal::events() const {
  std::lock_guard lock(mutex_);
  return events_;
}

size_t MemoryJournal::stored() const {
  std::lock_guard lock(mutex_);
  return messages_.size();
}

}  // namespace acomms::queue

namespace acomms::queue {

int64_t MemoryJournal::last_received_seq() {
  std::lock_guard lock(mutex_);
  int64_t last = 0;
  for (const QueueEvent& event : events_) last = std::max(last, event.seq);
  return last;
}

}  // namespace acomms::queue
