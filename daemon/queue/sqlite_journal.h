#pragma once
// The MessageJournal of a real daemon: queued_messages and event_log in the
// store (migrations/0002_queue.sql), written through the store's
// GroupCommitWriter so that concurrent Submits share one fsync.
//
// An append is reported once its commit is done: a Submit is answered only
// once its message is on disk. record() does not wait (the core thread must
// never block on the disk); it is queued behind every append already made,
// and logs the event and forgets the message in one transaction, so a crash
// can never keep the message and lose the event that removed it, or the
// reverse.

#include <atomic>
#include <cstdint>

#include "queue/message_journal.h"
#include "store/group_commit_writer.h"

namespace acomms::queue {

class SqliteJournal final : public MessageJournal {
 public:
  // `writer` writes the store migrated to 0002_queue or later, and must
  // outlive the journal.
  explicit SqliteJournal(store::GroupCommitWriter& writer) : writer_(writer) {}

  using MessageJournal::append;
  // `appended` runs on the store writer's thread, right after the commit.
  // Throws store::StoreError when the writer is stopped.
  void append(JournalMessage message, Appended appended) override;
  // A failure is logged by the writer: there is no caller to tell.
  void record(const QueueEvent& event) override;
  // Throws store::StoreError when the store cannot be read.
  std::vector<JournalMessage> load() override;
  std::vector<QueueEvent> received_since(double since) override;
  // Throws store::StoreError when the store cannot be read.
  std::vector<QueueEvent> authenticated_since(double sent_since) override;
  std::vector<RoutedIdentity> routed_since(double now) override;
  // Throws store::StoreError when the store cannot be read.
  int64_t last_received_seq() override;
  // Throws store::StoreError when the writer is stopped.
  void when_committed(Committed committed) override;
  uint64_t events_not_stored() const override { return events_not_stored_.load(); }
  // Throws store::StoreError when the last batch failed to commit.
  void flush() override;

 private:
  void write_event(const QueueEvent& event);

  store::GroupCommitWriter& writer_;
  // Counted on the writer thread, as each failed event is reported.
  std::atomic<uint64_t> events_not_stored_{0};
};

}  // namespace acomms::queue
