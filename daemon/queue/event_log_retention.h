#pragma once
// Keeps the event log from filling the disk over weeks at sea.
//
// Problem: every queued, sent, acked and received message adds rows to
// event_log, forever. Decision: prune it by age and by size
// (store { event_retention_days event_retention_mb }), oldest first, in
// steps of at most `rows_per_step` rows, each one small request on the
// store's writer. A step shares a group commit with Submits, so it must
// stay short (a few milliseconds with a million events: tests/bench); a
// step that found a full batch asks for the next one soon, so a backlog is
// worked off in many small bites rather than one long stall.
//
// Never pruned (the invariant the step's WHERE clause keeps):
//  - events of messages still in queued_messages (their history is live;
//    the messages themselves are in another table, never touched here);
//  - received events at or after `keep_received_since`: what the duplicate
//    filter reads back at start (QueueManager::duplicate_window_s);
//  - the received sequence counter (event_sequence): numbers are never
//    handed out again, whatever is pruned.
//
// Threads: start() and stop() on the core thread, where the steps are
// scheduled; each step runs on the writer's thread and reports back through
// atomics.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>

#include "core/scheduler.h"
#include "store/group_commit_writer.h"

namespace acomms::queue {

struct RetentionPolicy {
  double max_age_s = 90 * 86400.0;    // 0: no age bound
  int64_t max_bytes = 1024LL << 20;   // 0: no size bound
  size_t rows_per_step = 500;
};

// One pruning step, on the writer thread inside its transaction: deletes up
// to policy.rows_per_step unprotected events, oldest first, that are older
// than the age bound, or (while the store uses more than max_bytes) the
// oldest at all. Returns how many it deleted.
size_t prune_event_log_step(store::Database& db, const RetentionPolicy& policy, double now,
                            double keep_received_since);

class EventLogRetention {
 public:
  // `keep_received_since(now)` names the oldest received event that must
  // stay (asked on the core thread before every step). `writer` and
  // `scheduler` must outlive this object.
  EventLogRetention(store::GroupCommitWriter& writer, core::Scheduler& scheduler, RetentionPolicy policy,
                    std::function<double(double now)> keep_received_since);
  ~EventLogRetention();

  // Core thread: schedules the first step (and each one the next).
  void start();
  void stop();

  // How long to wait between steps while there is nothing, or a backlog,
  // to prune.
  static constexpr std::chrono::seconds kIdleInterval{60};
  static constexpr std::chrono::seconds kBacklogInterval{1};

  uint64_t pruned() const { return pruned_; }

 private:
  void tick();

  store::GroupCommitWriter& writer_;
  core::Scheduler& scheduler_;
  const RetentionPolicy policy_;
  std::function<double(double)> keep_received_since_;
  core::Scheduler::TaskId task_ = 0;
  bool running_ = false;
  // Written by the writer thread when a step ends, read by the core thread.
  std::atomic<bool> step_in_flight_{false};
  std::atomic<bool> backlog_{false};
  std::atomic<uint64_t> pruned_{0};
};

}  // namespace acomms::queue
