#pragma once
// A MessageJournal in memory: for tests and simulations, where durability
// is not the point. Keeps the event log so tests can read it.

#include <map>
#include <mutex>
#include <vector>

#include "queue/message_journal.h"

namespace acomms::queue {

class MemoryJournal final : public MessageJournal {
 public:
  using MessageJournal::append;
  // `appended` runs at once, on the caller's thread.
  void append(JournalMessage message, Appended appended) override;
  void record(const QueueEvent& event) override;
  std::vector<JournalMessage> load() override;
  std::vector<QueueEvent> received_since(double since) override;
  std::vector<QueueEvent> authenticated_since(double sent_since) override;
  std::vector<RoutedIdentity> routed_since(double now) override;
  void flush() override {}
  int64_t last_received_seq() override;
  // Runs `committed` at once: memory has nothing to wait for.
  void when_committed(Committed committed) override { committed(nullptr); }
  uint64_t events_not_stored() const override { return 0; }

  std::vector<QueueEvent> events() const;
  size_t stored() const;

 private:
  mutable std::mutex mutex_;
  int64_t next_id_ = 1;
  std::map<int64_t, JournalMessage> messages_;
  std::vector<QueueEvent> events_;
};

}  // namespace acomms::queue
