#pragma once
// A test fixture with a real store: the SQLite store in a fresh directory,
// its group-commit writer and a SqliteJournal over them.
//
// The queue tests that need durability (the journal, the event log and its
// retention, received sequence numbers, stored link figures) each built the
// same three objects by hand and had to close them in the one safe order:
// the journal before the writer it posts to, the writer before the store
// whose connection its thread owns. Here they are opened together and
// closed in reverse, by close_store() (to reopen, as after a restart) or at
// the fixture's end; the directory goes last.
//
// Thread-compatible: the fixture belongs to the test's thread; the store's
// connection belongs to the writer's thread (run queries through writer_).

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "queue/sqlite_journal.h"
#include "store/group_commit_writer.h"
#include "store/store.h"
#include "temp_dir.h"

namespace acomms::testing {

class StoreFixture : public ::testing::Test {
 protected:
  // Opens store_ on `data_dir` (default: dir_/data), then writer_ and journal_.
  void open_store();
  void open_store(const std::filesystem::path& data_dir);
  // Closes journal_, writer_ and store_, in that order. Safe when closed.
  void close_store();
  void TearDown() override { close_store(); }

  TempDir dir_{"acomms-store"};
  std::unique_ptr<store::Store> store_;
  std::unique_ptr<store::GroupCommitWriter> writer_;
  std::unique_ptr<queue::SqliteJournal> journal_;
};

}  // namespace acomms::testing
