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

void GroupCommitWriter::run_batch(std::vector<Request>& batch) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point batch_start = Clock::now();
  const size_t n = batch.size();
  std::vector<std::exception_ptr> errors(n);
  // The first request of the open transaction: a transaction SQLite rolls
  // back by itself takes every request since then with it.
  size_t first_in_transaction = 0;
  uint64_t commits = 0;

  auto lose_transaction = [&](size_t end, const std::string& reason) {
    auto error = std::make_exception_ptr(StoreError(
        "store " + db_.path() + ": " + reason + "; the write was not stored"));
    for (size_t j = first_in_transaction; j < end; ++j) {
      if (!errors[j]) errors[j] = error;
    }
  };
  auto begin = [&](size_t i) {
    first_in_transaction = i;
    try {
      db_.exec("BEGIN IMMEDIATE");
      return true;
    } catch (const StoreError& e) {
      spdlog::error("store {}: cannot start a transaction for {} write(s): {}", db_.path(), n - i,
                    e.what());
      if (!sqlite3_get_autocommit(db_.handle())) {
        sqlite3_exec(db_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
      }
      lose_transaction(n, std::string("cannot start a transaction: ") + e.what());
      return false;
    }
  };

  bool open = begin(0);
  // One name serves every request: savepoints nest, but these never do.
  Statement* savepoint = nullptr;
  Statement* release = nullptr;
  Statement* rollback_to = nullptr;
  if (open) {
    try {
      savepoint = &prepared("SAVEPOINT request");
      release = &prepared("RELEASE request");
      rollback_to = &prepared("ROLLBACK TO request");
    } catch (const StoreError& e) {
      sqlite3_exec(db_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
      lose_transaction(n, std::string("cannot prepare savepoints: ") + e.what());
      open = false;
    }
  }
  for (size_t i = 0; open && i < n; ++i) {
    try {
      savepoint->reset();
      savepoint->step();
      try {
        batch[i].work(db_);
      } catch (...) {
        errors[i] = std::current_exception();
        // Most failures (a constraint, a bad argument) leave the transaction
        // open and only this request's savepoint needs undoing. Some (I/O
        // error, disk full) make SQLite roll back the whole transaction.
        if (sqlite3_get_autocommit(db_.handle())) {
          lose_transaction(i, "the transaction was rolled back by a failure of a write in the "
                              "same batch (" + what(errors[i]) + ")");
          open = begin(i + 1);
          continue;
        }
        rollback_to->reset();
        rollback_to->step();
      }
      release->reset();
      release->step();
    } catch (const StoreError& e) {
      // The savepoint machinery itself failed: nothing of this transaction
      // can be trusted any more.
      if (!errors[i]) errors[i] = std::current_exception();
      spdlog::error("store {}: savepoint failed: {}", db_.path(), e.what());
      sqlite3_exec(db_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
      lose_transaction(i, std::string("savepoint failed: ") + e.what());
      open = begin(i + 1);
    }
  }
  Clock::duration commit_time{};
  if (open) {
    const Clock::time_point commit_start = Clock::now();
    try {
      db_.exec("COMMIT");
      commit_time = Clock::now() - commit_start;
      ++commits;
    } catch (const StoreError& e) {
      spdlog::error("store {}: commit of {} write(s) failed: {}", db_.path(),
                    n - first_in_transaction, e.what());
      // A failed COMMIT may leave the transaction open (SQLITE_BUSY); end it
      // so that the next batch starts clean.
      if (!sqlite3_get_autocommit(db_.handle())) {
        sqlite3_exec(db_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
      }
      lose_transaction(n, std::string("commit failed: ") + e.what());
    }
  }

  uint64_t failed = 0;
  for (size_t i = 0; i < n; ++i) failed += errors[i] ? 1 : 0;
  // Counted before anyone is answered: a caller whose write returned must
  // find it in stats().
  {
    std::lock_guard lock(mutex_);
    stats_.batches += commits;
    stats_.committed += n - failed;
    stats_.failed += failed;
    stats_.max_batch = std::max<uint64_t>(stats_.max_batch, n);
    stats_.commit_seconds += std::chrono::duration<double>(commit_time).count();
    stats_.busy_seconds += std::chrono::duration<double>(Clock::now() - batch_start).count();
  }
  for (size_t i = 0; i < n; ++i) {
    if (batch[i].done) {
      // A throwing done must not take the writer (and every later write)
      // down with it.
      try {
        batch[i].done(errors[i]);
      } catch (const std::exception& e) {
        spdlog::error("store {}: a write's completion failed: {}", db_.path(), e.what());
      }
    } else if (errors[i]) {
      // A post() has no caller to tell: the log is where it must show.
      spdlog::error("store {}: an asynchronous write was not stored: {}", db_.path(),
                    what(errors[i]));
    }
  }
}

}  // namespace acomms::store
