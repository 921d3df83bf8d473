#include "queue/event_log_retention.h"

#include <spdlog/spdlog.h>

#include <limits>
#include <string>

#include "core/core_thread.h"

namespace acomms::queue {
namespace {

using store::Database;
using store::Statement;

// Oldest first (event_log_by_time), skipping what must stay. The inner
// SELECT bounds the step; deleting by rowid then touches only those rows.
constexpr std::string_view kPruneStep =
    "DELETE FROM event_log WHERE id IN ("
    "  SELECT id FROM event_log WHERE time < ?1"
    "    AND (message_id IS NULL OR message_id NOT IN (SELECT id FROM queued_messages))"
    "    AND NOT (kind = 'received' AND time >= ?2)"
    "  ORDER BY time LIMIT ?3)";

int64_t pragma(Database& db, const char* sql) {
  Statement statement = db.prepare(sql);
  return statement.step() ? statement.column_int64(0) : 0;
}

// Bytes in pages holding data: freed pages are reused before the file
// grows, so this is what the bound limits.
int64_t used_bytes(Database& db) {
  return (pragma(db, "PRAGMA page_count") - pragma(db, "PRAGMA freelist_count")) *
         pragma(db, "PRAGMA page_size");
}

}  // namespace

size_t prune_event_log_step(Database& db, const RetentionPolicy& policy, double now,
                            double keep_received_since) {
  double cutoff = policy.max_age_s > 0 ? now - policy.max_age_s : -std::numeric_limits<double>::infinity();
  if (policy.max_bytes > 0 && used_bytes(db) > policy.max_bytes) {
    cutoff = std::numeric_limits<double>::infinity();  // over the size bound: the oldest, whatever age
  }
  if (cutoff == -std::numeric_limits<double>::infinity()) return 0;
  Statement statement = db.prepare(kPruneStep);
  statement.bind_double(1, cutoff);
  statement.bind_double(2, keep_received_since);
  statement.bind(3, static_cast<int64_t>(policy.rows_per_step));
  statement.step();
  return static_cast<size_t>(sqlite3_changes(db.handle()));
}

EventLogRetention::EventLogRetention(store::GroupCommitWriter& writer, core::Scheduler& scheduler,
                                     RetentionPolicy policy, std::function<double(double)> keep_received_since)
    : writer_(writer),
      scheduler_(scheduler),
      policy_(policy),
      keep_received_since_(std::move(keep_received_since)) {}

EventLogRetention::~EventLogRetention() { stop(); }

void EventLogRetention::start() {
  if (policy_.max_age_s <= 0 && policy_.max_bytes <= 0) return;  // nothing to bound
  running_ = true;
  task_ = scheduler_.after(kBacklogInterval, [this] { tick(); });
}

void EventLogRetention::stop() {
  if (!running_) return;
  running_ = false;
  scheduler_.cancel(task_);
}

void EventLogRetention::tick() {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!running_) return;
  // One step at a time: a slow disk gets no queue of steps behind Submits.
  if (!step_in_flight_.exchange(true)) {
    const double now = scheduler_.clock().now_seconds();
    const double keep_received_since = keep_received_since_(now);
    try {
      writer_.post(
          [this, now, keep_received_since](Database& db) {
            size_t deleted = prune_event_log_step(db, policy_, now, keep_received_since);
            pruned_ += deleted;
            backlog_ = deleted == policy_.rows_per_step;
          },
          [this](std::exception_ptr error) {
            if (error) backlog_ = false;
            step_in_flight_ = false;
          });
    } catch (const std::exception& e) {
      step_in_flight_ = false;
      spdlog::warn("store: event log not pruned: {}", e.what());
    }
  }
  // Soon while a step is still committing (its outcome is not known yet) or
  // the last one was full; otherwise the store is within its bounds.
  const bool soon = step_in_flight_ || backlog_;
  task_ = scheduler_.after(soon ? kBacklogInterval : kIdleInterval, [this] { tick(); });
}

}  // namespace acomms::queue
