#pragma once
// Group commit: one thread owns the store's connection and turns everything
// queued while the previous commit was on its way to disk into one
// transaction, so many concurrent writers share one fsync.
//
// With synchronous=FULL every COMMIT waits for the disk (milliseconds on
// real storage). One transaction per Submit would cap the daemon at a few
// hundred Submits a second; batched, the cost of that wait is shared by every
// request that arrived during it.
//
// Each request runs in its own SAVEPOINT inside the batch transaction: one
// failing request rolls back only its own changes and only its own caller
// sees the error. When the disk fails instead (a BEGIN, a write SQLite
// answers by rolling the whole transaction back, the COMMIT), every request
// of the lost transaction fails, none is reported stored, and the next
// batch starts on a connection with no transaction open
// (tests/unit/store/*_fault_test.cpp inject those faults). Requests run in the order they were queued (submit and post
// share one FIFO), each seeing the effects of those before it.
//
// The connection was opened NOMUTEX: once a writer is started on it, only the
// writer thread may touch it, until stop() returns.

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "store/sqlite.h"
#include "store/store_error.h"

namespace acomms::store {

class GroupCommitWriter {
 public:
  // A unit of work: statements on `db` inside the batch transaction. It must
  // not BEGIN, COMMIT or ROLLBACK itself, nor wait for another request (it
  // would wait for itself); it reports failure by throwing.
  using Work = std::function<void(Database& db)>;

  struct Options {
    // Upper bound on requests per transaction: bounds the time one batch
    // holds the write lock and the memory of undelivered results.
    size_t max_batch = 8192;
  };

  // Counters, for tests and benchmarks.
  struct Stats {
    uint64_t batches = 0;    // transactions committed
    uint64_t committed = 0;  // requests committed in them
    uint64_t failed = 0;     // requests whose work threw, or whose batch failed
    uint64_t max_batch = 0;  // largest batch so far
    // Wall time spent in COMMIT (with synchronous=FULL: mostly the fsync),
    // and in whole batches. Their difference over `committed` is the CPU
    // cost per request, which bounds throughput however large the batches.
    double commit_seconds = 0;
    double busy_seconds = 0;
  };

  // Starts the writer thread on `db`, which must outlive the writer.
  explicit GroupCommitWriter(Database& db) : GroupCommitWriter(db, Options{}) {}
  GroupCommitWriter(Database& db, Options options);
  // stop()
  ~GroupCommitWriter();
  GroupCommitWriter(const GroupCommitWriter&) = delete;
  GroupCommitWriter& operator=(const GroupCommitWriter&) = delete;

  // Runs `work` (callable as work(Database&), copyable: it is kept in a
  // std::function) on the writer thread; the future
  // becomes ready once its batch committed, with work's result, or with the
  // exception work threw, or with StoreError when the batch failed to commit
  // (naming the store; its code() is SQLite's for the cause, SQLITE_FULL
  // when the disk is full).
  // Throws StoreError if the writer is stopped.
  template <typename F>
  auto submit(F&& work) -> std::future<std::invoke_result_t<F&, Database&>>;

  // Fire and forget: `work` runs in FIFO order with submit()s; a failure is
  // logged (it has nobody else to go to). Throws StoreError if stopped.
  void post(Work work);

  // For callers that must not park a thread on the commit: `done` runs on
  // the writer thread once `work`'s batch is committed (null) or failed (why
  // not), in the order the requests were queued. It must be short and must
  // not throw or wait: the next batch waits for it. Throws StoreError if
  // stopped (then `done` never runs).
  using Done = std::function<void(std::exception_ptr)>;
  void post(Work work, Done done);

  // Returns once every request queued before the call is committed. Throws
  // StoreError if the last batch failed to commit.
  void flush();

  // Drains every queued request, commits, and stops the thread. Idempotent.
  // After it returns, the Database may be used by the calling thread again.
  // Never call it from work (the writer thread would wait for itself).
  void stop();

  // For work only (it runs on the writer thread): the statement for `sql`,
  // prepared on first use and kept until stop(), so a hot insert is parsed
  // once, not once per request. Reset it when done (before the batch
  // commits); it is finalized on the writer thread when the writer stops.
  Statement& prepared(std::string_view sql);

  bool running() const;
  Stats stats() const;
  const std::string& path() const { return db_.path(); }

 private:
  struct Request {
    Work work;
    // Called on the writer thread once the request's fate is known: null on
    // commit, else why it failed. Empty for a fire-and-forget post().
    Done done;
  };

  // One batch on its way through its transaction(s) (see the .cpp).
  struct Batch;

  void enqueue(Request request);
  void run();
  void run_batch(std::vector<Request>& requests);
  bool begin(Batch& batch, size_t first);
  bool prepare_savepoints(Batch& batch);
  void run_request(Batch& batch, size_t i);
  void commit(Batch& batch);
  void lose_transaction(Batch& batch, size_t end, const std::string& reason, int code);
  void roll_back();
  void record_stats(const Batch& batch);
  void answer(const Batch& batch);

  Database& db_;
  const Options options_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Request> queue_;  // guarded by mutex_
  bool stopping_ = false;      // guarded by mutex_
  Stats stats_;                // guarded by mutex_

  // Owned by the writer thread.
  std::map<std::string, std::unique_ptr<Statement>, std::less<>> statements_;
  std::thread::id writer_id_;

  std::mutex stop_mutex_;  // one joiner
  std::thread thread_;
};

template <typename F>
auto GroupCommitWriter::submit(F&& work) -> std::future<std::invoke_result_t<F&, Database&>> {
  using Result = std::invoke_result_t<F&, Database&>;
  // Shared between the work (sets the result before COMMIT) and done
  // (delivers it after): a result must not reach the caller before it is
  // durable.
  struct State {
    std::promise<Result> promise;
    std::conditional_t<std::is_void_v<Result>, bool, std::optional<Result>> result{};
  };
  auto state = std::make_shared<State>();
  std::future<Result> future = state->promise.get_future();
  Request request;
  request.work = [state, fn = std::forward<F>(work)](Database& db) mutable {
    if constexpr (std::is_void_v<Result>) {
      fn(db);
    } else {
      state->result.emplace(fn(db));
    }
  };
  request.done = [state](std::exception_ptr error) {
    if (error) {
      state->promise.set_exception(error);
    } else if constexpr (std::is_void_v<Result>) {
      state->promise.set_value();
    } else {
      state->promise.set_value(std::move(*state->result));
    }
  };
  enqueue(std::move(request));
  return future;
}

}  // namespace acomms::store
