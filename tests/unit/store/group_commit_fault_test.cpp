// The group-commit writer and the store's opening when SQLite or the disk
// fail in ways the Submit tests (submit_fault_test.cpp) do not reach: a
// savepoint statement that fails, a file that cannot be opened, a disk that
// stays broken for several batches.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "faulty_vfs.h"
#include "store/group_commit_writer.h"
#include "store/store.h"

namespace acomms::store {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using testing::FaultyVfs;
using testing::ScopedVfsFault;
using testing::VfsCall;
using testing::VfsFile;

constexpr auto kPatience = 10s;

class GroupCommitFaultTest : public ::testing::Test {
 protected:
  void SetUp() override {
    FaultyVfs::instance();
    dir_ = fs::temp_directory_path() / ("acomms-writer-fault-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override {
    FaultyVfs::instance().disarm();
    fs::remove_all(dir_);
  }

  std::unique_ptr<Store> open() {
    auto store = std::make_unique<Store>(dir_.string(), Store::Options{FaultyVfs::kName});
    store->db().exec("CREATE TABLE IF NOT EXISTS t (x INTEGER)");
    return store;
  }

  // Rows of t, through a connection of its own on the default VFS.
  std::vector<int64_t> rows() {
    Database reader((dir_ / kStoreFileName).string(), Database::Mode::kReadOnly);
    Statement query = reader.prepare("SELECT x FROM t ORDER BY x");
    std::vector<int64_t> xs;
    while (query.step()) xs.push_back(query.column_int64(0));
    return xs;
  }

  fs::path dir_;
};

// A future's failure text, or "" if it succeeded.
std::string failure_of(std::future<void>& future) {
  if (future.wait_for(kPatience) != std::future_status::ready) return "no answer";
  try {
    future.get();
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::future<void> insert(GroupCommitWriter& writer, int64_t x) {
  return writer.submit([x](Database& db) { db.prepare("INSERT INTO t VALUES (?)").bind(1, x).step(); });
}

TEST_F(GroupCommitFaultTest, AFailedSavepointLosesItsTransactionOnlyAndLaterRequestsCommit) {
  auto store = open();
  GroupCommitWriter writer(store->db());
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::promise<void> entered;
  writer.post([&entered, released](Database&) {
    entered.set_value();
    released.wait_for(kPatience);
  });
  ASSERT_EQ(entered.get_future().wait_for(kPatience), std::future_status::ready);
  // One batch: 1, a request whose savepoint then fails to be released
  // (here it breaks the rule and releases it itself, which stands in for a
  // SAVEPOINT statement SQLite fails), then 3.
  std::future<void> first = insert(writer, 1);
  std::future<void> breaker = writer.submit([](Database& db) {
    db.exec("INSERT INTO t VALUES (2); RELEASE request");
  });
  std::future<void> third = insert(writer, 3);
  release.set_value();

  const std::string path = store->db().path();
  std::string lost = failure_of(first);
  EXPECT_NE(lost.find("store " + path + ": savepoint failed"), std::string::npos) << lost;
  EXPECT_NE(lost.find("the write was not stored"), std::string::npos) << lost;
  EXPECT_NE(failure_of(breaker), "");
  EXPECT_EQ(failure_of(third), "") << "a request after the failed savepoint was lost";
  writer.flush();
  EXPECT_EQ(rows(), std::vector<int64_t>{3});
  EXPECT_TRUE(writer.running());
}

TEST_F(GroupCommitFaultTest, ADiskThatStaysBrokenFailsEveryBatchUntilItWorksAgain) {
  auto store = open();
  GroupCommitWriter writer(store->db());
  {
    ScopedVfsFault broken({VfsCall::kWrite, VfsFile::kWal, SQLITE_IOERR_WRITE, 0, true});
    for (int64_t x = 1; x <= 3; ++x) {
      std::future<void> f = insert(writer, x);
      std::string why = failure_of(f);
      EXPECT_NE(why.find("commit failed"), std::string::npos) << "batch " << x << ": " << why;
    }
  }
  std::future<void> after = insert(writer, 4);
  EXPECT_EQ(failure_of(after), "");
  EXPECT_EQ(rows(), std::vector<int64_t>{4});
  EXPECT_EQ(writer.stats().failed, 3u);
}

TEST_F(GroupCommitFaultTest, AStoreWhoseFileCannotBeOpenedSaysWhichFile) {
  {
    ScopedVfsFault cannot_open({VfsCall::kOpen, VfsFile::kMainDb, SQLITE_CANTOPEN, 0, true});
    try {
      open();
      FAIL() << "opened a file the disk refused";
    } catch (const StoreError& e) {
      EXPECT_NE(std::string(e.what()).find((dir_ / kStoreFileName).string()), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(open());
}

TEST_F(GroupCommitFaultTest, AFullDiskIsReportedAsFullToEveryRequestOfTheBatch) {
  auto store = open();
  GroupCommitWriter writer(store->db());
  ScopedVfsFault full({VfsCall::kWrite, VfsFile::kWal, SQLITE_FULL, 0, true});
  std::future<void> f = insert(writer, 1);
  ASSERT_EQ(f.wait_for(kPatience), std::future_status::ready);
  try {
    f.get();
    FAIL() << "committed onto a full disk";
  } catch (const StoreError& e) {
    EXPECT_TRUE(e.disk_full()) << e.what() << " (code " << e.code() << ")";
    EXPECT_NE(std::string(e.what()).find(store->db().path()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace acomms::store
