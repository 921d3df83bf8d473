#include "store/group_commit_writer.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <string>

#include <spdlog/spdlog.h>

namespace acomms::store {
namespace {

std::string what(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "unknown exception";
  }
}

// SQLite's result code behind a request's failure, 0 if it was not SQLite's.
int code_of(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const StoreError& e) {
    return e.code();
  } catch (...) {
    return 0;
  }
}

}  // namespace

GroupCommitWriter::GroupCommitWriter(Database& db, Options options)
    : db_(db), options_(options) {
  if (options_.max_batch == 0) throw StoreError("GroupCommitWriter: max_batch must be at least 1");
  thread_ = std::thread([this] { run(); });
  // Read by the writer only once a request arrived through mutex_, which
  // orders it after this assignment.
  writer_id_ = thread_.get_id();
}

GroupCommitWriter::~GroupCommitWriter() { stop(); }

void GroupCommitWriter::post(Work work) { enqueue(Request{std::move(work), {}}); }

void GroupCommitWriter::post(Work work, Done done) {
  if (!done) throw StoreError("GroupCommitWriter::post: done must be callable");
  enqueue(Request{std::move(work), std::move(done)});
}

void GroupCommitWriter::flush() {
  submit([](Database&) {}).get();
}

void GroupCommitWriter::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  // Two threads may call stop(); only one may join.
  std::lock_guard lock(stop_mutex_);
  if (thread_.joinable()) thread_.join();
}

bool GroupCommitWriter::running() const {
  std::lock_guard lock(mutex_);
  return !stopping_;
}

GroupCommitWriter::Stats GroupCommitWriter::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void GroupCommitWriter::enqueue(Request request) {
  {
    std::lock_guard lock(mutex_);
    if (stopping_) {
      throw StoreError("store " + db_.path() +
                       ": write refused, the store writer is stopped (the daemon is shutting down)");
    }
    queue_.push_back(std::move(request));
  }
  wake_.notify_one();
}

Statement& GroupCommitWriter::prepared(std::string_view sql) {
  if (std::this_thread::get_id() != writer_id_) {
    throw StoreError("store " + db_.path() +
                     ": GroupCommitWriter::prepared() called outside the writer thread");
  }
  auto it = statements_.find(sql);
  if (it == statements_.end()) {
    it = statements_.emplace(std::string(sql), std::make_unique<Statement>(db_, sql)).first;
  }
  it->second->reset();
  return *it->second;
}

void GroupCommitWriter::run() {
  std::vector<Request> batch;
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      // Stopping still drains: everything accepted before stop() is written.
      if (queue_.empty()) break;
      // Everything that arrived while the previous batch was on its way to
      // disk goes into this one: that is the whole point.
      size_t n = std::min(queue_.size(), options_.max_batch);
      batch.assign(std::make_move_iterator(queue_.begin()),
                   std::make_move_iterator(queue_.begin() + static_cast<ptrdiff_t>(n)));
      queue_.erase(queue_.begin(), queue_.begin() + static_cast<ptrdiff_t>(n));
    }
    run_batch(batch);
    batch.clear();
  }
  // Statements belong to this thread's use of the connection: finalize them
  // here, so that after stop() the connection holds nothing of the writer.
  statements_.clear();
}

// The state of one batch while its requests run. Normally one transaction
// holds them all; when SQLite rolls a transaction back by itself, the
// requests after the one that caused it go on in a fresh transaction.
struct GroupCommitWriter::Batch {
  using Clock = std::chrono::steady_clock;

  explicit Batch(std::vector<Request>& requests) : requests(requests), errors(requests.size()) {}
  size_t size() const { return requests.size(); }

  std::vector<Request>& requests;
  // Why each request failed; null for those that are committed.
  std::vector<std::exception_ptr> errors;
  const Clock::time_point start = Clock::now();
  // The first request of the open transaction: a transaction SQLite rolls
  // back by itself takes every request since then with it.
  size_t first_in_transaction = 0;
  // A transaction is open and requests may run in it.
  bool open = false;
  bool committed = false;
  Clock::duration commit_time{};
  // One name serves every request: savepoints nest, but these never do.
  Statement* savepoint = nullptr;
  Statement* release = nullptr;
  Statement* rollback_to = nullptr;
};

void GroupCommitWriter::run_batch(std::vector<Request>& requests) {
  Batch batch(requests);
  batch.open = begin(batch, 0) && prepare_savepoints(batch);
  for (size_t i = 0; batch.open && i < batch.size(); ++i) run_request(batch, i);
  if (batch.open) commit(batch);
  record_stats(batch);
  answer(batch);
}

// Fails every request of the open transaction before `end` that has not
// failed for a reason of its own: their changes are gone with it. `code` is
// SQLite's code for the cause, so that callers can tell a full disk.
void GroupCommitWriter::lose_transaction(Batch& batch, size_t end, const std::string& reason, int code) {
  auto error = std::make_exception_ptr(StoreError(
      "store " + db_.path() + ": " + reason + "; the write was not stored", code));
  for (size_t j = batch.first_in_transaction; j < end; ++j) {
    if (!batch.errors[j]) batch.errors[j] = error;
  }
}

// Ends whatever transaction a failure left open. SQLite rolls back by itself
// on most I/O errors; when it did not (a failed COMMIT that only met a lock,
// a savepoint statement that failed), the connection must not carry the
// broken transaction into the next batch: every BEGIN would fail after it.
void GroupCommitWriter::roll_back() {
  if (sqlite3_get_autocommit(db_.handle())) return;
  int rc = sqlite3_exec(db_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
  if (rc != SQLITE_OK) {
    spdlog::error("store {}: rollback after a failed write failed too ({}); the next batch tries again",
                  db_.path(), sqlite3_errstr(rc));
  }
}

// Opens the transaction for the requests from `first` on. When it cannot be
// opened, all of them fail and it returns false.
bool GroupCommitWriter::begin(Batch& batch, size_t first) {
  batch.first_in_transaction = first;
  // A transaction still open here was left by a failure whose rollback
  // failed too: nothing of it was reported as stored, so end it now.
  if (!sqlite3_get_autocommit(db_.handle())) {
    spdlog::warn("store {}: a failed transaction was still open; rolling it back", db_.path());
    roll_back();
  }
  try {
    db_.exec("BEGIN IMMEDIATE");
    return true;
  } catch (const StoreError& e) {
    spdlog::error("store {}: cannot start a transaction for {} write(s): {}", db_.path(), batch.size() - first,
                  e.what());
    roll_back();
    lose_transaction(batch, batch.size(), std::string("cannot start a transaction: ") + e.what(), e.code());
    return false;
  }
}

// The statements that give each request its savepoint. Without them no
// request can run alone, so the whole batch fails.
bool GroupCommitWriter::prepare_savepoints(Batch& batch) {
  try {
    batch.savepoint = &prepared("SAVEPOINT request");
    batch.release = &prepared("RELEASE request");
    batch.rollback_to = &prepared("ROLLBACK TO request");
    return true;
  } catch (const StoreError& e) {
    spdlog::error("store {}: cannot prepare savepoints: {}", db_.path(), e.what());
    roll_back();
    lose_transaction(batch, batch.size(), std::string("cannot prepare savepoints: ") + e.what(), e.code());
    return false;
  }
}

// Runs request i inside its own savepoint, so that its failure undoes only
// its own changes. Leaves batch.open false only if no transaction could be
// opened again after losing one.
void GroupCommitWriter::run_request(Batch& batch, size_t i) {
  try {
    batch.savepoint->reset();
    batch.savepoint->step();
    try {
      batch.requests[i].work(db_);
    } catch (...) {
      batch.errors[i] = std::current_exception();
      // Most failures (a constraint, a bad argument) leave the transaction
      // open and only this request's savepoint needs undoing. Some (I/O
      // error, disk full) make SQLite roll back the whole transaction.
      if (sqlite3_get_autocommit(db_.handle())) {
        spdlog::error("store {}: a write failed and SQLite rolled back its transaction of {} write(s): {}",
                      db_.path(), i + 1 - batch.first_in_transaction, what(batch.errors[i]));
        lose_transaction(batch, i, "the transaction was rolled back by a failure of a write in the "
                                   "same batch (" + what(batch.errors[i]) + ")", code_of(batch.errors[i]));
        batch.open = begin(batch, i + 1);
        return;
      }
      batch.rollback_to->reset();
      batch.rollback_to->step();
    }
    batch.release->reset();
    batch.release->step();
  } catch (const StoreError& e) {
    // The savepoint machinery itself failed: nothing of this transaction
    // can be trusted any more.
    if (!batch.errors[i]) batch.errors[i] = std::current_exception();
    spdlog::error("store {}: savepoint failed: {}", db_.path(), e.what());
    roll_back();
    lose_transaction(batch, i, std::string("savepoint failed: ") + e.what(), e.code());
    batch.open = begin(batch, i + 1);
  }
}

void GroupCommitWriter::commit(Batch& batch) {
  const Batch::Clock::time_point commit_start = Batch::Clock::now();
  try {
    db_.exec("COMMIT");
    batch.commit_time = Batch::Clock::now() - commit_start;
    batch.committed = true;
  } catch (const StoreError& e) {
    spdlog::error("store {}: commit of {} write(s) failed: {}", db_.path(),
                  batch.size() - batch.first_in_transaction, e.what());
    // A failed COMMIT may leave the transaction open (SQLITE_BUSY); end it
    // so that the next batch starts clean.
    roll_back();
    lose_transaction(batch, batch.size(), std::string("commit failed: ") + e.what(), e.code());
  }
}

// Counted before anyone is answered: a caller whose write returned must
// find it in stats().
void GroupCommitWriter::record_stats(const Batch& batch) {
  const size_t n = batch.size();
  const auto failed = static_cast<uint64_t>(
      std::count_if(batch.errors.begin(), batch.errors.end(), [](const std::exception_ptr& e) { return e != nullptr; }));
  std::lock_guard lock(mutex_);
  stats_.batches += batch.committed ? 1 : 0;
  stats_.committed += n - failed;
  stats_.failed += failed;
  stats_.max_batch = std::max<uint64_t>(stats_.max_batch, n);
  stats_.commit_seconds += std::chrono::duration<double>(batch.commit_time).count();
  stats_.busy_seconds += std::chrono::duration<double>(Batch::Clock::now() - batch.start).count();
}

// Tells each request its fate, in the order they were queued.
void GroupCommitWriter::answer(const Batch& batch) {
  for (size_t i = 0; i < batch.size(); ++i) {
    const Request& request = batch.requests[i];
    if (request.done) {
      // A throwing done must not take the writer (and every later write)
      // down with it.
      try {
        request.done(batch.errors[i]);
      } catch (const std::exception& e) {
        spdlog::error("store {}: a write's completion failed: {}", db_.path(), e.what());
      }
    } else if (batch.errors[i]) {
      // A post() has no caller to tell: the log is where it must show.
      spdlog::error("store {}: an asynchronous write was not stored: {}", db_.path(), what(batch.errors[i]));
    }
  }
}

}  // namespace acomms::store
